#include "solver/pd/j_samples.hpp"

#include "solver/pd/stress.hpp"

namespace pdmpm::pd {

std::vector<core::JSample> elastic_j_samples(const System<2>& sys) {
  const std::vector<ParticleStrain<2>> strain = particle_strain(sys);
  const auto& p = sys.particles;
  std::vector<core::JSample> out(strain.size());
  for (std::size_t i = 0; i < strain.size(); ++i) {
    const ParticleStrain<2>& s = strain[i];
    core::JSample& o = out[i];
    o.X = p.x0[i];
    o.volume = p.volume[i];
    o.grad_u = s.grad_u;
    o.stress << s.stress[0], s.stress[3], s.stress[3], s.stress[1];
    o.energy = s.energy;
  }
  return out;
}

}  // namespace pdmpm::pd
