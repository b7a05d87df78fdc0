// regold: rewrites the gold files of reference_data/ — the only program that
// writes them. CI never runs it; the gates only read. Usage:
//
//   build/verification/tools/regold [--out DIR] [paper] [regression]
//
// With no selection both files are written. DIR defaults to the source tree's
// reference_data/. Every file carries root attributes git_sha, tree, date,
// command, compiler and flags; every dataset carries `source` (where the number
// comes from) and, where it has one, `unit` and `note`. reference_data/README.md
// lists the numbers again for readers, with the same sources.
#include <cmath>
#include <cstring>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include "verification/support/hdf5_gold.hpp"
#include "verification/support/regression_cases.hpp"

namespace {

using namespace pdmpm::test;

struct Number {
  std::string path;
  double value;
  std::string unit, source, note;
};

// Numbers from the source papers (docs/verification/) and standard benchmarks. Typed once,
// here; gates read them from reference_data/paper_numbers.h5.
std::vector<Number> paper_numbers() {
  const double e = std::numbers::e;
  const std::string t42 = "Deryugin et al. 2023 (Russian PD influence functions) §4, table 4.2, c column (3D)";
  const std::string c42 = "coefficient k of c = k E / ((1 - 2 nu) pi delta^4)";
  const std::string s004a = "Gu & Zhou 2017 (Chinese plane-strain state-based PD) §5.1, text and fig. 3";
  const std::string s004b = "Gu & Zhou 2017 §5.2, text and fig. 5";
  const std::string s000 = "Noorian et al. (Persian adaptive SBPD-MPM) §3-2, table 1 (same machine: Intel 7th generation, 2.7 GHz)";
  return {
      {"/seed001_table42/constant", 6.0, "", t42, c42 + "; printed 6E/((1-2nu) pi delta^4)"},
      {"/seed001_table42/triangular", 30.0, "", t42, c42 + "; printed 30E/((1-2nu) pi delta^4)"},
      {"/seed001_table42/quadratic", 36.0, "", t42, c42 + "; printed 36E/((1-2nu) pi delta^4)"},
      {"/seed001_table42/semi_elliptical", 18.0, "", t42, c42 + "; printed 18E/((1-2nu) pi delta^4)"},
      {"/seed001_table42/exponential", 3.0 * e / (4.0 * (3.0 * e - 8.0)), "", t42,
       c42 + "; printed 3eE/(4(1-2nu) pi delta^4 (3e-8)), the parentheses around 3e-8 lost in print"},
      {"/seed001_table42/gaussian", 3.0 * e / (e - 2.0), "", t42,
       c42 + "; printed 3eE/((1-2nu) pi delta^4 (e-2)), the parentheses around e-2 lost in print"},
      {"/spherical_wave/time", 3e-5, "s", "Deryugin et al. 2023 §9, text after fig. 9.4", "time at which the errors below are quoted"},
      {"/spherical_wave/lps_inverse_distance_error", 0.0336, "", "Deryugin et al. 2023 §9, text after fig. 9.4",
       "relative error of the LPS run with omega = 1/|xi| (3.36 %)"},
      {"/spherical_wave/lps_constant_error", 0.0405, "", "Deryugin et al. 2023 §9, text after fig. 9.4",
       "relative error of the LPS run with omega = 1 (4.05 %)"},
      {"/hole_plate/no_crack", 0.0133e-6, "s", s004a,
       "plate not yet cracked; fig. 3(a) caption says 0.0133 us, the text 0.013 us"},
      {"/hole_plate/crack_initiation", 11.97e-6, "s", s004a, "cracks start at the hole, perpendicular to the load"},
      {"/hole_plate/crack_growing", 13.3e-6, "s", s004a, "cracks still growing perpendicular to the load"},
      {"/hole_plate/fully_broken", 15.96e-6, "s", s004a, "plate completely broken"},
      {"/inclined_crack/initiation", 3.99e-6, "s", s004b, "crack initiation"},
      {"/inclined_crack/branching", 9.31e-6, "s", s004b, "crack still growing, the lower wing starts to branch"},
      {"/inclined_crack/through_crack", 10.64e-6, "s", s004b, "through-crack, roughly along 45 degrees"},
      {"/central_crack/time_pure_sbpd", 15520.0, "s", s000, "wall time, pure state-based PD (Madenci)"},
      {"/central_crack/time_expand_only", 10210.0, "s", s000, "wall time, adaptive SBPD-MPM, expansion only"},
      {"/central_crack/time_expand_shrink", 8890.0, "s", s000, "wall time, adaptive SBPD-MPM, expansion and shrinking"},
      {"/central_crack/saving_expand_only", 1.0 - 10210.0 / 15520.0, "", s000,
       "1 - 10210/15520 = 0.342 (computed from the table)"},
      {"/central_crack/saving_expand_shrink", 1.0 - 8890.0 / 15520.0, "", s000,
       "1 - 8890/15520 = 0.427; the text rounds to 43 %"},
      {"/cooks_membrane/tip_displacement", 23.9, "",
       "Bergan & Felippa 1985, Comput. Meth. Appl. Mech. Eng. 50:25-69 (best value quoted for Cook's membrane, "
       "Cook 1974)",
       "vertical displacement of the top-right corner (48, 60) of the tapered panel (0,0)-(48,44)-(48,60)-(0,44), "
       "clamped at x = 0, total shear load 1 on x = 48, E = 1, nu = 1/3, thickness 1, plane stress; consistent "
       "units. Fine-mesh FE values converge to 23.96 (Cook 1989)"},
  };
}

void write_paper(const std::string& dir, const std::string& command) {
  gold::Writer w(dir + "/paper_numbers.h5");
  gold::write_provenance(w, command);
  w.attribute("/", "kind", "reference numbers from papers (not produced by this code)");
  for (const auto& n : paper_numbers()) {
    w.scalar(n.path, n.value);
    w.attribute(n.path, "source", n.source);
    if (!n.unit.empty()) w.attribute(n.path, "unit", n.unit);
    if (!n.note.empty()) w.attribute(n.path, "note", n.note);
  }
  w.commit();
  std::cout << "regold: wrote " << dir << "/paper_numbers.h5 (" << paper_numbers().size() << " numbers)\n";
}

void write_regression(const std::string& dir, const std::string& command) {
  gold::Writer w(dir + "/regression_forces.h5");
  gold::write_provenance(w, command);
  w.attribute("/", "kind", "regression gold: output of this code for fixed inputs");
  w.attribute("/", "configuration", regression::describe());
  const auto cases = regression::cases();
  for (const auto& c : cases) {
    const auto r = regression::compute(c);
    const hsize_t n = static_cast<hsize_t>(r.particles), d = static_cast<hsize_t>(r.dimension);
    w.dataset(c.group() + "/force", r.force, {n, d});
    w.dataset(c.group() + "/energy", r.energy, {n});
    w.dataset(c.group() + "/dilatation", r.dilatation, {n});
    w.attribute(c.group() + "/force", "unit", "N/m^3");
    w.attribute(c.group() + "/energy", "unit", "J/m^3");
    w.attribute(c.group(), "broken_bond_sides", static_cast<double>(r.broken_bond_sides));
    w.attribute(c.group(), "source", "pdmpm, verification/support/regression_cases.cpp");
  }
  w.commit();
  std::cout << "regold: wrote " << dir << "/regression_forces.h5 (" << cases.size() << " cases)\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::string dir = gold::reference_data_dir(), command = "regold";
  bool paper = false, regression = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    command += " " + a;
    if (a == "--out" && i + 1 < argc) {
      dir = argv[++i];
      command += " " + dir;
    } else if (a == "paper") {
      paper = true;
    } else if (a == "regression") {
      regression = true;
    } else {
      std::cerr << "usage: regold [--out DIR] [paper] [regression]\n";
      return 2;
    }
  }
  if (!paper && !regression) paper = regression = true;
  try {
    if (paper) write_paper(dir, command);
    if (regression) write_regression(dir, command);
  } catch (const std::exception& e) {
    std::cerr << "regold: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
