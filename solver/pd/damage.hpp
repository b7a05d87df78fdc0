#pragma once
// Local damage φ_i = 1 − Σ_j μ_ij V_j / Σ_j V_j over the family (Deryugin et al. 2023 eq 10.2).
#include <vector>

#include "solver/pd/system.hpp"

namespace pdmpm::pd {

template <int D>
double particle_damage(const System<D>& sys, Index i) {
  const auto& fam = sys.families;
  double all = 0.0, intact = 0.0;
  for (BondIndex b = fam.begin(i); b < fam.end(i); ++b) {
    const double V = sys.particles.volume[fam.neighbor[b]];
    all += V;
    if (!sys.bonds.broken(b)) intact += V;
  }
  return all > 0.0 ? 1.0 - intact / all : 0.0;
}

template <int D>
std::vector<double> local_damage(const System<D>& sys) {
  std::vector<double> phi(sys.particles.n_real, 0.0);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < sys.particles.n_real; ++i) phi[i] = particle_damage(sys, i);
  return phi;
}

}  // namespace pdmpm::pd
