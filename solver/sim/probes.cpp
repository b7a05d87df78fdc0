#include "solver/sim/probes.hpp"

#include <cmath>

#include "solver/core/error.hpp"
#include "solver/sim/geometry_from_scene.hpp"

namespace pdmpm::sim {

template <int D>
std::vector<Probe> locate_probes(const io::Scene& s, const std::vector<Vec<D>>& x0, Index n_real,
                                 const dist::Communicator* comm, dist::OwnedRange own, Index n_body) {
  const bool distributed = comm && comm->size() > 1;
  std::vector<Probe> probes;
  for (std::size_t k = 0; k < s.probes.size(); ++k) {
    const Vec<D> x = to_vec<D>(s.probes[k].point);
    Index best = -1;
    double dist = 1e300;
    for (Index i = 0; i < n_real; ++i) {
      const double d = (x0[i] - x).norm();
      if (d < dist) dist = d, best = i;
    }
    Probe probe{s.probes[k].name, best};
    if (distributed) {
      const Index mine = best >= 0 ? own.begin + best : -1;
      const double nearest = comm->min(dist);
      const auto g = static_cast<Index>(comm->min(dist == nearest && mine >= 0 ? static_cast<double>(mine) : 1e300));
      dist = nearest;
      probe.owner = dist::owner_rank(g, n_body, comm->size());
      probe.particle = own.contains(g) ? g - own.begin : -1;
    }
    if (dist > s.spacing * std::sqrt(static_cast<double>(D)))
      throw InputError(s.file, "probe[" + std::to_string(k) + "].point",
                       "is not inside the body (no particle within √D Δx)");
    probes.push_back(probe);
  }
  return probes;
}

template std::vector<Probe> locate_probes<1>(const io::Scene&, const std::vector<Vec<1>>&, Index,
                                             const dist::Communicator*, dist::OwnedRange, Index);
template std::vector<Probe> locate_probes<2>(const io::Scene&, const std::vector<Vec<2>>&, Index,
                                             const dist::Communicator*, dist::OwnedRange, Index);
template std::vector<Probe> locate_probes<3>(const io::Scene&, const std::vector<Vec<3>>&, Index,
                                             const dist::Communicator*, dist::OwnedRange, Index);

}  // namespace pdmpm::sim
