#include "solver/sim/probes.hpp"

#include <cmath>

#include "solver/core/error.hpp"
#include "solver/sim/geometry_from_scene.hpp"

namespace pdmpm::sim {

template <int D>
std::vector<Probe> locate_probes(const io::Scene& s, const std::vector<Vec<D>>& x0, Index n_real) {
  std::vector<Probe> probes;
  for (std::size_t k = 0; k < s.probes.size(); ++k) {
    const Vec<D> x = to_vec<D>(s.probes[k].point);
    Index best = -1;
    double dist = 1e300;
    for (Index i = 0; i < n_real; ++i) {
      const double d = (x0[i] - x).norm();
      if (d < dist) dist = d, best = i;
    }
    if (dist > s.spacing * std::sqrt(static_cast<double>(D)))
      throw InputError(s.file, "probe[" + std::to_string(k) + "].point", "is not inside the body (no particle within √D Δx)");
    probes.push_back({s.probes[k].name, best});
  }
  return probes;
}

template std::vector<Probe> locate_probes<1>(const io::Scene&, const std::vector<Vec<1>>&, Index);
template std::vector<Probe> locate_probes<2>(const io::Scene&, const std::vector<Vec<2>>&, Index);
template std::vector<Probe> locate_probes<3>(const io::Scene&, const std::vector<Vec<3>>&, Index);

}  // namespace pdmpm::sim
