#include "benchmarks/perf/perf_problem.hpp"

#include <stdexcept>

namespace pdmpm::perf {

io::Scene perf_scene(const std::string& model, int refine) {
  if (refine < 1) throw std::invalid_argument("perf_scene: refine must be a positive integer");
  auto s = io::parse_scene(std::string(PDMPM_SOURCE_DIR) + "/verification/scenes/disk_impact_elastic.toml");
  s.id = "perf_" + model + "_r" + std::to_string(refine);
  const double ratio = s.delta / s.spacing;  // 3.0002: LAMMPS' example horizon
  s.spacing /= refine;
  s.delta = ratio * s.spacing;
  s.indenter->center[1] = -0.0001 + s.indenter->radius;  // 0.1 mm deep into the top face (y = 0)
  s.time.dt = perf_dt(refine);
  if (model == "lps") {
    s.model = "lps";
    s.influence = pd::Influence::inverse_distance;  // peri/lps' ω
  } else if (model != "pmb") {
    throw std::invalid_argument("perf_scene: model must be pmb or lps");
  }
  return s;
}

double perf_dt(int refine) { return 1e-7 / refine; }

}  // namespace pdmpm::perf
