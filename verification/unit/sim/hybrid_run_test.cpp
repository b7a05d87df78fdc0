// `pdmpm run` on adaptive SBPD–MPM scenes ([hybrid]): the scene keys, and a tiny
// plate end to end in each mode — outputs present, the per-particle `method`
// field, history columns, and the particle counts each mode implies.
#include "solver/sim/hybrid_run.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "solver/core/error.hpp"
#include "solver/io/scene.hpp"
#include "solver/pd/stress.hpp"
#include "solver/sim/hybrid_setup.hpp"
#include "solver/sim/run.hpp"
#include "verification/support/fields_reader.hpp"
#include "verification/support/hybrid_body.hpp"
#include "verification/support/scene_text.hpp"
#include "verification/support/scratch_dir.hpp"
#include "verification/support/output_files.hpp"

namespace pdmpm::sim {
namespace {

namespace fs = std::filesystem;

TEST(HybridScene, DefaultsAndKeys) {
  const auto s = test::hybrid_plate_scene("").parse();
  ASSERT_EQ(s.method, io::Method::hybrid);
  ASSERT_TRUE(s.hybrid && s.mpm);
  EXPECT_EQ(s.hybrid->mode, hybrid::Mode::expand_shrink);
  EXPECT_EQ(s.hybrid->radii.pd_radius, 7.0);
  EXPECT_EQ(s.hybrid->radii.expand_trigger, 3.0);
  EXPECT_EQ(s.hybrid->shrink_every, 1);
  EXPECT_TRUE(s.hybrid->precrack_starts_pd);
  EXPECT_FALSE(s.hybrid->audit_conversions);
  EXPECT_EQ(s.mpm->constitutive, mpm::MaterialModel::j2);

  const auto k = test::hybrid_plate_scene(
                     "mode = \"expand\"\npd_radius = 5\nexpand_trigger = 2\nexpand_radius = 6\nkeep_radius = 4\n"
                     "shrink_every = 3\nprecrack_starts_pd = false\naudit_conversions = "
                     "true\n[hybrid.tips]\ndamage_threshold = 0.3\n"
                     "match_radius = 2.5\n")
                     .parse();
  EXPECT_EQ(k.hybrid->mode, hybrid::Mode::expand);
  EXPECT_EQ(k.hybrid->radii.pd_radius, 5.0);
  EXPECT_EQ(k.hybrid->radii.expand_trigger, 2.0);
  EXPECT_EQ(k.hybrid->radii.expand_radius, 6.0);
  EXPECT_EQ(k.hybrid->radii.keep_radius, 4.0);
  EXPECT_EQ(k.hybrid->shrink_every, 3);
  EXPECT_FALSE(k.hybrid->precrack_starts_pd);
  EXPECT_TRUE(k.hybrid->audit_conversions);
  EXPECT_EQ(k.hybrid->tips.damage_threshold, 0.3);
  EXPECT_EQ(k.hybrid->tips.match_radius, 2.5);
  EXPECT_EQ(k.output.fields,
            (std::vector<std::string>{"method", "displacement", "velocity", "damage", "stress", "von_mises",
                                      "triaxiality", "eq_plastic_strain"}));

  // lps goes with MPM's linear elastic law.
  auto elastic = test::hybrid_plate_scene("");
  elastic.model = "lps";
  elastic.material_keys = "critical_stretch = 0.01";
  EXPECT_EQ(elastic.parse().mpm->constitutive, mpm::MaterialModel::linear_elastic);
}

TEST(HybridScene, RefusesWhatTheRegionsCannotCarry) {
  auto with_tables = [](const std::string& extra) {
    auto t = test::hybrid_plate_scene("");
    t.tables += extra;
    return t;
  };
  EXPECT_THROW(with_tables("\n[indenter]\nradius = 0.002\ncenter = [0.01, 0.03]\nvelocity = [0.0, -1.0]\n"
                           "stiffness = 1e17\n")
                   .parse(),
               InputError);
  EXPECT_THROW(with_tables("\n[crack]\nthreshold = 0.5\n").parse(), InputError);
  auto adr = test::hybrid_plate_scene("", "integrator = \"adr\"");
  EXPECT_THROW(adr.parse(), InputError);
}

struct Outcome {
  RunResult result;
  std::map<std::string, double> last;
  std::vector<double> method;  // last frame
  std::vector<double> speed;   // last frame: |v| per particle
  Index particles = 0;
};

Outcome run_plate(const std::string& hybrid_keys, const std::string& name) {
  const test::ScratchDir scratch("hybrid_run_" + name);
  const fs::path out = scratch.fresh("out");
  const auto scene = test::hybrid_plate_scene(hybrid_keys).parse(name + ".toml");
  RunOptions opt;
  opt.out_dir = out;
  opt.progress = false;
  Outcome o;
  o.result = run_scene(scene, opt);
  for (const char* f : {"fields.h5", "fields.xdmf", "history.csv", "summary.json"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  o.last = test::last_history_row(out / "history.csv");
  const test::FieldsReader fields((out / "fields.h5").string());
  EXPECT_EQ(fields.frames().size(), 3u);
  o.method = fields.read(fields.frames().back(), "method");
  const std::vector<double> v = fields.read(fields.frames().back(), "velocity");  // 3 per particle
  for (std::size_t i = 0; i + 2 < v.size(); i += 3) o.speed.push_back(std::hypot(v[i], v[i + 1], v[i + 2]));
  EXPECT_EQ(fields.read(fields.frames().back(), "von_mises").size(), o.method.size());
  EXPECT_EQ(fields.read(fields.frames().back(), "damage").size(), o.method.size());
  o.particles = static_cast<Index>(o.method.size());
  return o;
}

TEST(HybridRun, ExpandShrinkPlateWritesEveryOutput) {
  // Radii of 1.5–2 δ keep the pre-crack's region inside the plate (7 δ = 21 mm would cover it).
  const auto o = run_plate(
      "mode = \"expand_shrink\"\npd_radius = 1.5\nexpand_trigger = 1\nexpand_radius = 2\nkeep_radius = 2\n"
      "audit_conversions = true\n",
      "expand_shrink");
  ASSERT_EQ(o.result.exit_code, 0) << o.result.message;
  const auto& j = o.result.summary;
  EXPECT_EQ(j["solver"], "hybrid");
  EXPECT_EQ(j["mode"], "expand_shrink");
  EXPECT_EQ(j["status"], "completed");
  EXPECT_EQ(j["steps"], 200);
  EXPECT_GT(j["particle_steps"]["pd"].get<double>(), 0.0);   // the pre-crack starts PD
  EXPECT_GT(j["particle_steps"]["mpm"].get<double>(), 0.0);  // the rest is on the grid
  for (const char* phase : {"pd", "mpm", "coupling", "regions"})
    EXPECT_GE(j["wall_time_phases"][phase].get<double>(), 0.0) << phase;
  EXPECT_TRUE(j["wall_time_phases"].contains("mpm_phases"));

  for (const char* col : {"step",
                          "time",
                          "pd_particles",
                          "transition_particles",
                          "mpm_particles",
                          "removed_particles",
                          "to_pd",
                          "to_mpm",
                          "expansions",
                          "shrinks",
                          "onsets",
                          "tips",
                          "tip0_x",
                          "tip3_y",
                          "kinetic_energy",
                          "internal_energy",
                          "momentum_x",
                          "momentum_y",
                          "max_damage",
                          "max_speed",
                          "probe_mid_uy",
                          "probe_mid_vx",
                          "conversion_energy",
                          "reaction_top_x",
                          "reaction_top_y",
                          "reaction_bottom_y"})
    EXPECT_TRUE(o.last.count(col)) << col;
  EXPECT_TRUE(std::isfinite(o.last.at("conversion_energy")));
  const double pd = o.last.at("pd_particles"), tr = o.last.at("transition_particles"), mp = o.last.at("mpm_particles"),
               rm = o.last.at("removed_particles");
  EXPECT_EQ(pd + tr + mp + rm, static_cast<double>(o.particles));
  EXPECT_GT(pd, 0.0);
  EXPECT_GT(mp, 0.0);
  EXPECT_GT(o.last.at("kinetic_energy"), 0.0);
  // The field agrees with the counts.
  double pd_field = 0.0;
  for (double m : o.method) {
    EXPECT_TRUE(m == 0.0 || m == 1.0 || m == 2.0 || m == 3.0) << m;
    pd_field += m == 0.0;
  }
  EXPECT_EQ(pd_field, pd);
  // max_speed is the fastest particle not removed (kind 3), the same step as the last frame;
  // both files hold every digit, so equal to within the rounding of |v| (4 ulp). The grips
  // pull at 2 m/s, so it is at least near that.
  ASSERT_EQ(o.speed.size(), o.method.size());
  double fastest = 0.0;
  for (std::size_t i = 0; i < o.speed.size(); ++i)
    if (o.method[i] != 3.0) fastest = std::max(fastest, o.speed[i]);
  EXPECT_DOUBLE_EQ(o.last.at("max_speed"), fastest);
  EXPECT_DOUBLE_EQ(o.result.summary["metrics"]["max_speed"].get<double>(), fastest);
  EXPECT_GT(fastest, 1.0);
}

// [hybrid] initial_pd: the grips' rows start PD (that held ones stay PD through shrinks is
// checked by the hybrid gates' edge crack with PD grips).
TEST(HybridRun, InitialPdRegionsStartPd) {
  const std::string keys =
      "pd_radius = 1.5\nexpand_trigger = 1\nexpand_radius = 2\nkeep_radius = 2\n"
      "initial_pd = [{ type = \"box\", min = [0.0, 0.0], max = [0.03, 0.002] },\n"
      "              { type = \"box\", min = [0.0, 0.018], max = [0.03, 0.02] }]\n";
  const auto scene = test::hybrid_plate_scene(keys).parse("initial_pd.toml");
  EXPECT_EQ(scene.initial_pd.size(), 2u);
  const auto setup = build_hybrid<2>(scene);
  EXPECT_EQ(setup->initial_pd.size(), 120u);  // two rows of 30 at each edge
  setup->hybrid_simulation->start(setup->initial_pd);
  for (const Index i : setup->initial_pd) EXPECT_EQ(setup->pd.system.particles.kind[i], core::ParticleKind::pd);
  const auto o = run_plate(keys, "initial_pd");
  ASSERT_EQ(o.result.exit_code, 0) << o.result.message;
  EXPECT_GE(o.last.at("pd_particles"), 120.0);
}

TEST(HybridRun, ModePdIsAllPeridynamics) {
  const auto o = run_plate("mode = \"pd\"\n", "pd");
  ASSERT_EQ(o.result.exit_code, 0) << o.result.message;
  EXPECT_EQ(o.result.summary["mode"], "pd");
  EXPECT_EQ(o.result.summary["particle_steps"]["mpm"].get<double>(), 0.0);
  EXPECT_EQ(o.last.at("pd_particles"), static_cast<double>(o.particles));
  EXPECT_EQ(o.last.at("mpm_particles"), 0.0);
  for (double m : o.method) EXPECT_EQ(m, 0.0);
  // All PD: the reactions come from the held PD particles alone (−Σ V (f + b)); the grips
  // pull the plate apart, so the top support pulls up and the bottom one down.
  EXPECT_GT(o.last.at("reaction_top_y"), 0.0);
  EXPECT_LT(o.last.at("reaction_bottom_y"), 0.0);
}

// The plate of test::hybrid_plate_scene() with no grips: PD around its pre-crack, the grid elsewhere
// (expand_shrink, radii of 1.5–2 δ), given [[initial]] tables; 100 steps, each in history.csv.
RunResult run_free_plate(const std::string& initial, const fs::path& out) {
  auto t = test::hybrid_plate_scene("");
  t.time = "steps = 100";
  t.tables =
      "[mpm]\n\n[hybrid]\npd_radius = 1.5\nexpand_trigger = 1\nexpand_radius = 2\nkeep_radius = 2\n"
      "\n[[precrack]]\nfrom = [0.0, 0.0100]\nto = [0.008, 0.0100]\n"
      "\n[output]\nhistory_every = 1\nframes = 2\n" +
      initial;
  RunOptions opt;
  opt.out_dir = out;
  opt.progress = false;
  return run_scene(t.parse("hybrid_initial.toml"), opt);
}

TEST(HybridRun, UniformInitialVelocityMovesTheMixedBodyRigidly) {
  const test::ScratchDir scratch("hybrid_run_initial_velocity");
  const fs::path out = scratch.fresh("out");
  const auto r = run_free_plate("[[initial]]\nvelocity = [3.0, -2.0]\n", out);
  ASSERT_EQ(r.exit_code, 0) << r.message;
  const double mass = 7850.0 * 0.03 * 0.02 * 1e-3;
  const Vec<2> v0(3.0, -2.0), expected = mass * v0;
  std::ifstream in(out / "history.csv");
  std::string header, line;
  std::getline(in, header);
  std::vector<std::string> names;
  std::stringstream h(header);
  for (std::string n; std::getline(h, n, ',');) names.push_back(n);
  auto column = [&](const std::string& n) {
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), n) - names.begin());
  };
  const std::size_t mx = column("momentum_x"), my = column("momentum_y"), pd = column("pd_particles"),
                    mp = column("mpm_particles"), ke = column("kinetic_energy"), ie = column("internal_energy");
  ASSERT_LT(std::max({mx, my, pd, mp, ke, ie}), names.size());
  int rows = 0;
  double worst_momentum = 0.0, worst_energy = 0.0;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::stringstream s(line);
    for (std::string x; std::getline(s, x, ',');) v.push_back(std::stod(x));
    ++rows;
    EXPECT_GT(v[pd], 0.0);  // both methods carry the body throughout
    EXPECT_GT(v[mp], 0.0);
    worst_momentum = std::max(worst_momentum, (Vec<2>(v[mx], v[my]) - expected).norm() / expected.norm());
    worst_energy = std::max(worst_energy, std::abs(v[ie]) / v[ke]);
  }
  EXPECT_EQ(rows, 101);
  // Momentum of PD and grid particles together: the rounding of the sums and of the grid's
  // p_I/m_I = v0, ~1e-16 per step; PD particles drift by u += Δt v, grid particles by the
  // grid velocity, so bonds across the interface stretch by rounding only. 1e-13 after 100
  // steps leaves a margin; a body part left at rest would be off by its mass fraction.
  EXPECT_LT(worst_momentum, 1e-13);
  // Strain energy against kinetic: rounding (a real strain of 1e-6 would give ~1e-7).
  EXPECT_LT(worst_energy, 1e-12);
  RecordProperty("worst_momentum", fmt::format("{:.3e}", worst_momentum));
  RecordProperty("worst_energy", fmt::format("{:.3e}", worst_energy));
}

// u = H X strains both methods from t = 0: the grid particles' von Mises stress is that of
// Hooke's law of ε = sym(H) (plane strain), the PD particles' is not zero.
TEST(HybridRun, AffineInitialDisplacementStrainsBothMethods) {
  Mat<2> H;
  H << 1e-6, 3e-7, -2e-7, -5e-7;
  const test::ScratchDir scratch("hybrid_run_initial_displacement");
  const fs::path out = scratch.fresh("out");
  const auto r =
      run_free_plate("[[initial]]\ndisplacement = [\"1e-6 * x + 3e-7 * y\", \"-2e-7 * x - 5e-7 * y\"]\n", out);
  ASSERT_EQ(r.exit_code, 0) << r.message;
  const double E = 200e9, nu = 0.3, lam = E * nu / ((1 + nu) * (1 - 2 * nu)), G = E / (2 * (1 + nu));
  const Mat<2> eps = 0.5 * (H + H.transpose());
  const double tr = eps.trace();
  const pd::Tensor6 hooke{
      lam * tr + 2 * G * eps(0, 0), lam * tr + 2 * G * eps(1, 1), lam * tr, 2 * G * eps(0, 1), 0.0, 0.0};
  const double vm = pd::von_mises(hooke);
  const test::FieldsReader fields((out / "fields.h5").string());
  const auto& first = fields.frames().front();
  ASSERT_EQ(first.step, 0);
  const auto method = fields.read(first, "method"), von_mises = fields.read(first, "von_mises");
  double worst_grid = 0.0, smallest_pd = 1e300;
  int grid = 0, pd = 0;
  for (std::size_t i = 0; i < method.size(); ++i) {
    if (method[i] == 1.0) ++grid, worst_grid = std::max(worst_grid, std::abs(von_mises[i] / vm - 1.0));
    if (method[i] == 0.0) ++pd, smallest_pd = std::min(smallest_pd, von_mises[i]);
  }
  ASSERT_GT(grid, 0);
  ASSERT_GT(pd, 0);
  // 1e-5: as for the MPM scene, the linear law on the log strain of F = I + H, rotated
  // and divided by J, differs from small-strain Hooke by O(|H|) = 1e-6 relative.
  EXPECT_LT(worst_grid, 1e-5);
  EXPECT_GT(smallest_pd, 0.1 * vm);  // strained (an unstrained particle would show 0)
  // The stress field is the one von Mises is taken of, by method: the grid's Cauchy stress on
  // grid particles (Hooke's, to the same 1e-5), the PD model's on PD particles; no yield yet.
  const auto stress = fields.read(first, "stress"), eps_p = fields.read(first, "eq_plastic_strain");
  const auto triaxiality = fields.read(first, "triaxiality");
  ASSERT_EQ(stress.size(), 6 * method.size());
  ASSERT_EQ(eps_p.size(), method.size());
  ASSERT_EQ(triaxiality.size(), method.size());
  double worst_hooke = 0.0, worst_measure = 0.0;
  for (std::size_t i = 0; i < method.size(); ++i) {
    pd::Tensor6 s6;
    std::copy(stress.begin() + 6 * i, stress.begin() + 6 * i + 6, s6.begin());
    if (method[i] == 1.0)
      for (int c = 0; c < 6; ++c) worst_hooke = std::max(worst_hooke, std::abs(s6[c] - hooke[c]) / vm);
    // The written measures are of the written tensor (the PD model's or the grid's alike).
    worst_measure = std::max({worst_measure, std::abs(pd::von_mises(s6) - von_mises[i]) / vm,
                              std::abs(pd::triaxiality(s6) - triaxiality[i])});
    EXPECT_EQ(eps_p[i], 0.0) << i;
  }
  EXPECT_LT(worst_hooke, 1e-5);
  // The grid's von Mises and triaxiality come from its Kirchhoff stress, the tensor from τ/J:
  // the same stress through other roundings.
  EXPECT_LT(worst_measure, 1e-12);
  RecordProperty("worst_grid_von_mises", fmt::format("{:.3e}", worst_grid));
  RecordProperty("smallest_pd_von_mises_over_hooke", fmt::format("{:.3e}", smallest_pd / vm));
}

// 3D goes through the same adaptor: a small block with a pre-crack runs in every mode.
TEST(HybridRun, SmallBlockRunsIn3D) {
  for (const char* mode : {"pd", "expand", "expand_shrink"}) {
    test::SceneText t;
    t.id = std::string("hybrid_block_") + mode;
    t.dimension = 3;
    t.min = {0.0, 0.0, 0.0};
    t.max = {0.010, 0.008, 0.008};
    t.model = "lps_plastic";
    t.material_keys = "yield_stress = 4e8\ntangent_modulus = 2e9\ncritical_stretch = 0.01";
    t.time = "steps = 20";
    t.tables = std::string("[mpm]\n\n[hybrid]\nmode = \"") + mode +
        "\"\npd_radius = 1\nexpand_trigger = 1\nexpand_radius = 1.5\nkeep_radius = 1.5\n"
        "\n[[precrack]]\ncorner0 = [0.0, 0.004, 0.0]\ncorner1 = [0.003, 0.004, 0.0]\n"
        "corner2 = [0.0, 0.004, 0.008]\n"
        "\n[[boundary]]\nname = \"top\"\nkind = \"velocity\"\nvalue = [\"0\", \"1.0\", \"0\"]\n"
        "region = { type = \"box\", min = [0.0, 0.007, 0.0], max = [0.010, 0.008, 0.008] }\n";
    const test::ScratchDir scratch(std::string("hybrid_run_3d_") + mode);
    RunOptions opt;
    opt.out_dir = scratch.fresh("out");
    opt.progress = false;
    const auto r = run_scene(t.parse(), opt);
    ASSERT_EQ(r.exit_code, 0) << mode << ": " << r.message;
    EXPECT_EQ(r.summary["dimension"], 3);
    EXPECT_EQ(r.summary["mode"], mode);
    EXPECT_GT(r.summary["particle_steps"]["pd"].get<double>(), 0.0) << mode;
    if (std::string(mode) != "pd") {
      EXPECT_GT(r.summary["particle_steps"]["mpm"].get<double>(), 0.0) << mode;
    }
  }
}

}  // namespace
}  // namespace pdmpm::sim
