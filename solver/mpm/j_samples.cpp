#include "solver/mpm/j_samples.hpp"

namespace pdmpm::mpm {

double monotonic_plastic_work(const Material& m, double eq) {
  if (m.model != MaterialModel::j2) return 0.0;
  return eq * (m.j2.yield_stress + 0.5 * m.j2.hardening_modulus(m.elastic.E) * eq);
}

std::optional<core::JSample> j_sample(const Simulation<2>& sim, Index i) {
  if (sim.failed(i)) return std::nullopt;
  const Mat<2> F = sim.state().F.get(i);
  core::JSample s;
  s.X = sim.particles().x0[i];
  s.volume = sim.particles().volume[i];
  s.grad_u = F - Mat<2>::Identity();
  s.stress = sim.state().kirchhoff.get(i).topLeftCorner<2, 2>() * F.inverse().transpose();
  s.energy = sim.state().energy[i] + monotonic_plastic_work(sim.settings().material, sim.eq_plastic_strain(i));
  return s;
}

std::vector<core::JSample> j_samples(const Simulation<2>& sim, const Vec<2>& centre, double radius) {
  std::vector<core::JSample> out;
  for (Index i : sim.active())
    if ((sim.particles().x0[i] - centre).norm() < radius)
      if (const auto s = j_sample(sim, i)) out.push_back(*s);
  return out;
}

}  // namespace pdmpm::mpm
