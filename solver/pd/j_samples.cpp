#include "solver/pd/j_samples.hpp"

#include "solver/pd/stress.hpp"

namespace pdmpm::pd {

std::vector<core::JSample> elastic_j_samples(const System<2>& sys, const Vec<2>& centre, double radius) {
  const auto& p = sys.particles;
  std::vector<core::JSample> out;
  for (Index i = 0; i < p.n_real; ++i) {
    if ((p.x0[i] - centre).norm() >= radius) continue;
    const ParticleStrain<2> s = particle_strain(sys, i);
    core::JSample o;
    o.X = p.x0[i];
    o.volume = p.volume[i];
    o.grad_u = s.grad_u;
    o.stress << s.stress[0], s.stress[3], s.stress[3], s.stress[1];
    o.energy = s.energy;
    out.push_back(o);
  }
  return out;
}

}  // namespace pdmpm::pd
