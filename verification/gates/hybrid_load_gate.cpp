// The hybrid's load against displacement beside the all-PD run's (Noorian et al., adaptive
// SBPD–MPM §2; docs/models/hybrid.md, "Load against displacement"): the edge-crack plate of
// hybrid_gate.cpp, run as a scene the way users run it (grip reaction from history.csv),
// with grips of PD particles and the full-state coupling, at Δx = 1 and 0.5 mm; and the same
// plate uncracked, its load against an extensometer in the bulk, which tells the two
// discretisations' own stiffness apart from the coupling's and the grips'.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "verification/support/gate.hpp"
#include "verification/support/output_files.hpp"
#include "verification/support/scene_gate.hpp"
#include "verification/support/scene_text.hpp"

namespace pdmpm {
namespace {

using test::Compare;
using test::Gate;

const char* kProblem = "hybrid";
const char* kSource = "[noorian] §2; docs/models/hybrid.md (Load against displacement)";
constexpr double kHeight = 0.03, kGrip = 1.5e-3, kPull = 0.3;  // m, m, m/s (ramped over 10 µs)
constexpr double kYoung = 200e9, kThickness = 1e-3;
constexpr double kGaugeLow = 0.0075, kGaugeHigh = 0.0225;  // extensometer probes' y (m), mid-width

struct Plate {
  double dx = 1e-3;
  double width = 0.06;
  bool cracked = true;  // pre-crack from the left edge to x = 15 mm at y = 15.5 mm
  std::string mode{};   // "" = the all-PD run (no [hybrid] table), else the hybrid's mode
  std::string coupling = "full_state";
  double end_time = 9e-5;
  double pull_scale = 1.0;  // the grips' speed over kPull (the all-PD run's own sensitivity)
};

// The edge-crack plate of hybrid_gate.cpp (brittle: critical stretch 0.003 at Δx = 1 mm,
// scaled by √(1 mm/Δx) to keep the fracture energy G ∝ s_c²δ; no yield) with grips of PD
// particles: in the hybrid the grips' particles start PD and stay PD (they are held), so
// both runs hold the same particles. Extensometer probes at y = 7.5 and 22.5 mm, mid-width.
io::Scene plate_scene(const Plate& p) {
  const bool hybrid = !p.mode.empty();
  test::SceneText s;
  s.id = "hybrid_load";
  s.spacing = p.dx;
  s.max = {p.width, kHeight};
  s.youngs_modulus = kYoung;
  s.model = "lps_plastic";
  s.material_keys = "yield_stress = 1e12\ntangent_modulus = 0\n";
  if (p.cracked) s.material_keys += fmt::format("critical_stretch = {}\n", 0.003 * std::sqrt(1e-3 / p.dx));
  s.time = fmt::format("dt = {}\nend_time = {}", p.dx >= 1e-3 ? 2e-8 : 1e-8, p.end_time);
  const std::string v = fmt::format("{}*min(t/1e-5, 1)", kPull * p.pull_scale);
  const std::string bottom = fmt::format("{{ type = \"box\", min = [-1, -1], max = [1, {}] }}", kGrip);
  const std::string top = fmt::format("{{ type = \"box\", min = [-1, {}], max = [1, 1] }}", kHeight - kGrip);
  std::string t = fmt::format(
      "[[boundary]]\nname = \"bottom\"\nkind = \"velocity\"\nregion = {}\nvalue = [\"free\", \"-{}\"]\n"
      "[[boundary]]\nname = \"top\"\nkind = \"velocity\"\nregion = {}\nvalue = [\"free\", \"{}\"]\n"
      "[[probe]]\nname = \"lo\"\npoint = [{}, {}]\n[[probe]]\nname = \"hi\"\npoint = [{}, {}]\n"
      "[output]\nframes = 2\n",
      bottom, v, top, v, p.width / 2, kGaugeLow, p.width / 2, kGaugeHigh);
  if (p.cracked) t += "[[precrack]]\nfrom = [-1e-3, 0.0155]\nto = [0.015, 0.0155]\n";
  if (hybrid)
    t += fmt::format(
        "[mpm]\nshape_function = \"gimp\"\nupdate_scheme = \"musl\"\ncell_factor = 2.0\n"
        "[hybrid]\nmode = \"{}\"\ncoupling = \"{}\"\npd_radius = 2\nexpand_trigger = 1\nexpand_radius = 2\n"
        "keep_radius = 2\ninitial_pd = [{}, {}]\n",
        p.mode, p.coupling, bottom, top);
  s.tables = t;
  return s.parse("hybrid_load.toml");
}

struct LoadHistory {
  std::vector<double> t, load, extension;  // s, N (top grip's reaction), m (probe hi − lo)
  std::vector<double> broken;              // broken bonds (the all-PD run's history has them)
};

LoadHistory run(const Plate& p, const std::string& tag) {
  const test::GateRun g = test::run_for_gate(plate_scene(p), kProblem, "load_" + tag);
  LoadHistory h;
  h.t = g.history("time");
  h.load = g.history("reaction_top_y");
  const std::vector<double> hi = g.history("probe_hi_uy"), lo = g.history("probe_lo_uy");
  for (std::size_t k = 0; k < hi.size(); ++k) h.extension.push_back(hi[k] - lo[k]);
  if (p.mode.empty()) h.broken = g.history("broken_bonds");
  return h;
}

// The largest |load − the all-PD run's load| over the all-PD run's largest load, over the
// samples before the all-PD crack grows (its first broken bond beyond the pre-crack) and over
// the whole run. Both runs write history at the same steps.
struct LoadDeviation {
  double before_growth = 0.0, whole_run = 0.0, growth_time = 0.0;
  double rms_after_growth = 0.0;  // root mean square of the same ratio over the samples from growth on
};

LoadDeviation deviation(const LoadHistory& hybrid, const LoadHistory& pd) {
  EXPECT_EQ(hybrid.t.size(), pd.t.size());
  const std::size_t n = std::min(hybrid.t.size(), pd.t.size());
  double largest = 0.0;
  for (double f : pd.load) largest = std::max(largest, std::abs(f));
  LoadDeviation d;
  const std::size_t growth = static_cast<std::size_t>(
      std::find_if(pd.broken.begin(), pd.broken.end(), [](double b) { return b > 0; }) - pd.broken.begin());
  d.growth_time = growth < pd.t.size() ? pd.t[growth] : pd.t.back();
  double squares = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double e = std::abs(hybrid.load[k] - pd.load[k]) / largest;
    d.whole_run = std::max(d.whole_run, e);
    if (k < growth)
      d.before_growth = std::max(d.before_growth, e);
    else
      squares += e * e;
  }
  if (n > growth) d.rms_after_growth = std::sqrt(squares / static_cast<double>(n - growth));
  return d;
}

// Load over extensometer extension, time-averaged from 150 µs on (ten reverberations of the
// 30 mm plate at ≈ 5 km/s, ramp long over), against the continuum's E t W / gauge.
double stiffness_over_continuum(const LoadHistory& h, double width) {
  double load = 0.0, extension = 0.0;
  for (std::size_t k = 0; k < h.t.size(); ++k)
    if (h.t[k] >= 1.5e-4) load += h.load[k], extension += h.extension[k];
  return (load / extension) / (kYoung * kThickness * width / (kGaugeHigh - kGaugeLow));
}

std::string resolution_tag(double dx) { return dx >= 1e-3 ? "1mm" : "05mm"; }

// The expand_shrink hybrid with this coupling against the all-PD run pd of the same Δx.
LoadDeviation coupling_deviation(double dx, const std::string& coupling, const LoadHistory& pd) {
  return deviation(run({.dx = dx, .mode = "expand_shrink", .coupling = coupling},
                       fmt::format("{}_{}", coupling, resolution_tag(dx))),
                   pd);
}

const nlohmann::json kLoadColumns = {"Δx (mm)",
                                     "coupling",
                                     "all-PD crack grows at (µs)",
                                     "largest load deviation before growth",
                                     "largest load deviation, whole run (to 90 µs)",
                                     "root mean square deviation from growth on"};

// The all-PD run's grips 0.016 % faster: once the crack runs, a perturbation this small (or a
// 1 % smaller step) moves some bond's break by a step, and the load then differs by several
// per cent (docs/models/hybrid.md, "How well the load is defined once the crack runs").
constexpr double kPerturbedPull = 1.00016;

TEST(FastHybrid, LoadAgainstDisplacementBesideTheAllPdRun) {
  nlohmann::json rows = nlohmann::json::array();
  double fine_before_growth = 0.0, blended_before_growth = 0.0;
  LoadDeviation fine_blended, fine_noise;
  for (const double dx : {1e-3, 0.5e-3}) {
    const std::string res = resolution_tag(dx);
    const LoadHistory pd = run({.dx = dx}, "pd_" + res);
    for (const std::string coupling : {"full_state", "blended"}) {
      const LoadDeviation d = coupling_deviation(dx, coupling, pd);
      rows.push_back({dx * 1e3, coupling, d.growth_time * 1e6, d.before_growth, d.whole_run, d.rms_after_growth});
      if (dx < 1e-3 && coupling == "full_state") fine_before_growth = d.before_growth;
      if (dx < 1e-3 && coupling == "blended") fine_blended = d;
      if (coupling == "blended") blended_before_growth = std::max(blended_before_growth, d.before_growth);
    }
    if (dx >= 1e-3) continue;
    fine_noise = deviation(run({.dx = dx, .pull_scale = kPerturbedPull}, "pd_perturbed_" + res), pd);
    rows.push_back({dx * 1e3, "all-PD itself, grips 0.016 % faster", fine_noise.growth_time * 1e6,
                    fine_noise.before_growth, fine_noise.whole_run, fine_noise.rms_after_growth});
  }
  test::record_gate(Gate{
      .id = "hybrid.agreement.load_whole_run_within_noise",
      .claim = "with the blended coupling and grips of PD particles, the edge crack's grip load "
               "(expand_shrink, Δx = 0.5 mm) shall deviate from the all-PD run's over the whole run "
               "(to 90 µs, when the all-PD front is 51 mm into the 60 mm plate) by no more than the all-PD run "
               "deviates from itself when its grips move 0.016 % faster",
      .measured = fine_blended.whole_run,
      .expected = fine_noise.whole_run,
      .compare = Compare::at_most,
      .tolerance_reason = "the problem's own resolution, measured in the same gate: once the crack runs, the "
                          "all-PD load is not defined to better than this (at Δx = 1 mm grips 0.0016 % faster "
                          "leave it unchanged; 0.016 % and 0.16 % faster or Δt 1 % smaller move it by 3.9-7.7 % at "
                          "Δx = 1 and 0.5 mm), so "
                          "the issue's 2 % can be checked only before growth (the gates above)",
      .source = kSource,
      .unit = "",
      .problem = kProblem});
  test::record_gate(Gate{.id = "hybrid.agreement.load_before_growth_blended",
                         .claim = "with the blended coupling (blend_width = 2) and grips of PD particles, the edge "
                                  "crack's grip load (expand_shrink, Δx = 1 and 0.5 mm) shall stay within 2 % (of the "
                                  "all-PD run's largest) of the all-PD run's at every sample until the crack grows",
                         .measured = blended_before_growth,
                         .expected = 0.02,
                         .compare = Compare::at_most,
                         .tolerance_reason = "the issue's 2 % for the load–displacement curve, at both resolutions: "
                                             "the band takes the grids' hole and the free-edge share of the gap with "
                                             "it (table 03c)",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
  test::record_gate(Gate{.id = "hybrid.agreement.load_before_growth",
                         .claim = "with grips of PD particles and coupling full_state, the edge crack's grip load "
                                  "(expand_shrink, Δx = 0.5 mm) shall stay within 2 % (of the all-PD run's largest) "
                                  "of the all-PD run's at every sample until the all-PD crack grows",
                         .measured = fine_before_growth,
                         .expected = 0.02,
                         .compare = Compare::at_most,
                         .tolerance_reason =
                             "the issue's 2 % for the load–displacement curve. At Δx = 1 mm (δ = W/20) it is not "
                             "met (table 03c): the all-PD plate's free edges and grips stiffen it against the "
                             "continuum by more than the coupling errs, and that share halves with δ",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
  test::record_data(
      kProblem, "03c_load_displacement",
      {{"kind", "table"},
       {"title", "Edge crack: grip load against the all-PD run's (grips of PD particles, expand_shrink)"},
       {"columns", kLoadColumns},
       {"rows", rows},
       {"caption",
        "Deviations relative to the all-PD run's largest grip load; both runs pull the same grips of PD "
        "particles at 0.3 m/s. Gate hybrid.agreement.load_before_growth is the Δx = 0.5 mm full_state row, "
        "hybrid.agreement.load_before_growth_blended the blended rows (its band reaches two bond reaches and 2δ "
        "beyond every PD particle, so on this small plate it covers most of the body). "
        "The last row is the all-PD run against itself with its grips 0.016 % faster: once the crack runs, "
        "the load is defined only to this (gate hybrid.agreement.load_whole_run_within_noise holds the blended "
        "row to it); the issue's 2 % over the whole run lies below it. Table 03d separates the two "
        "discretisations' stiffness. The paper's coupling is in table 03c_load_displacement_paper (full tier)."}});
}

// The paper's coupling on the same plate (full tier: its runs add 45 s to the fast gate above,
// which gates only the other two): a measured row, not a gate.
TEST(FullHybrid, LoadOfThePaperCouplingBesideTheAllPdRun) {
  nlohmann::json rows = nlohmann::json::array();
  for (const double dx : {1e-3, 0.5e-3}) {
    const LoadDeviation d = coupling_deviation(dx, "paper", run({.dx = dx}, "pd_beside_paper_" + resolution_tag(dx)));
    rows.push_back({dx * 1e3, "paper", d.growth_time * 1e6, d.before_growth, d.whole_run, d.rms_after_growth});
  }
  test::record_data(kProblem, "03c_load_displacement_paper",
                    {{"kind", "table"},
                     {"title", "Edge crack: grip load of the paper's coupling against the all-PD run's"},
                     {"columns", kLoadColumns},
                     {"rows", rows},
                     {"caption", "As table 03c_load_displacement, with the paper's coupling."}});
}

TEST(FastHybrid, UncrackedPlateStiffnessAgainstTheContinuum) {
  Plate hybrid{.cracked = false, .end_time = 3e-4};
  hybrid.mode = "expand_shrink";
  const double hyb = stiffness_over_continuum(run(hybrid, "stiffness_hybrid"), hybrid.width);
  test::record_gate(Gate{.id = "hybrid.agreement.bulk_stiffness",
                         .claim = "the uncracked plate with grips of PD particles (full_state, the body MPM) shall "
                                  "carry the continuum's load at the strain an extensometer in its bulk reads "
                                  "(load / extension over E t W / gauge, time-averaged from 150 to 300 µs)",
                         .measured = std::abs(hyb - 1.0),
                         .expected = 0.01,
                         .compare = Compare::at_most,
                         .tolerance_reason = "the run is dynamic: averaging ten reverberations leaves ≈ 0.5 % (an "
                                             "all-MPM plate gripped by node rows reads +0.35 % the same way); 1 % is "
                                             "what the PD share of the deviation must be told apart from",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
  test::record_data(kProblem, "03d_plate_stiffness",
                    {{"kind", "table"},
                     {"title", "Uncracked plate: load over the extensometer's extension against the continuum"},
                     {"columns", {"run", "plate width (mm)", "load / extension over E t W / gauge"}},
                     {"rows", {{"hybrid (grips PD, body MPM), full_state", 60, hyb}}},
                     {"caption",
                      "Δx = 1 mm, δ = 3.015 mm, gauge 15 mm at mid-width, grips of PD particles pulled at 0.3 m/s. "
                      "Gate hybrid.agreement.bulk_stiffness is this row. The all-PD plates beside it are in table "
                      "03d_plate_stiffness_all_pd (full tier: 90 s of runs)."}});
}

// The all-PD plates of the same pull (full tier): how the PD discretisation's own stiffness
// differs from the continuum's, the share of the edge crack's load gap that is not the coupling's.
TEST(FullHybrid, UncrackedAllPdPlateStiffness) {
  const Plate narrow{.cracked = false, .end_time = 3e-4};
  Plate wide = narrow;
  wide.width = 0.12;
  const double pd_narrow = stiffness_over_continuum(run(narrow, "stiffness_pd"), narrow.width);
  const double pd_wide = stiffness_over_continuum(run(wide, "stiffness_pd_wide"), wide.width);
  test::record_data(kProblem, "03d_plate_stiffness_all_pd",
                    {{"kind", "table"},
                     {"title", "Uncracked all-PD plates: load over the extensometer's extension against the continuum"},
                     {"columns", {"run", "plate width (mm)", "load / extension over E t W / gauge"}},
                     {"rows", {{"all PD", 60, pd_narrow}, {"all PD", 120, pd_wide}}},
                     {"caption",
                      "The pull of table 03d_plate_stiffness. "
                      "The all-PD plate is stiffer than the continuum, more so when narrower: particles within δ "
                      "of a free edge, whose families lack the bonds across it, read more dilatation in a pull "
                      "along the edge. That share falls as δ/W; the grid has none."}});
}

}  // namespace
}  // namespace pdmpm
