#include "solver/hybrid/j_samples.hpp"

#include "solver/hybrid/conversion.hpp"
#include "solver/hybrid/plastic_state_transfer.hpp"
#include "solver/mpm/constitutive.hpp"
#include "solver/pd/lps_plastic.hpp"

namespace pdmpm::hybrid {

std::vector<core::JSample> j_samples(const Simulation<2>& h, const Vec<2>& centre, double radius) {
  const core::Particles<2>& p = h.particles();
  const mpm::Simulation<2>& mpm = h.mpm();
  const pd::System<2>& sys = h.pd().system();
  const auto* plastic = dynamic_cast<const pd::LpsPlastic<2>*>(&h.pd().model());
  const mpm::Constitutive<2> law(mpm.settings().material, mpm.settings().setting);
  const core::J2Hardening& j2 = mpm.settings().material.j2;
  const bool hardens = mpm.settings().material.model == mpm::MaterialModel::j2;
  const double H = hardens ? j2.hardening_modulus(mpm.settings().material.elastic.E) : 0.0;
  auto plastic_work = [&](double eq) { return hardens ? eq * (j2.yield_stress + 0.5 * H * eq) : 0.0; };
  std::vector<core::JSample> out;
  for (Index i = 0; i < p.n_real; ++i) {
    if ((p.x0[i] - centre).norm() >= radius) continue;
    if (p.kind[i] == core::ParticleKind::removed || mpm.failed(i)) continue;
    Mat<2> F;
    Mat<3> tau;
    double W = 0.0;
    if (p.kind[i] == core::ParticleKind::pd) {
      const auto bond_F = bond_deformation_gradient<2>(sys, i);
      if (!bond_F) continue;
      F = *bond_F;
      mpm::PointHistory history = mpm.state().history[i];
      if (plastic)
        if (const auto fitted = plastic_state_from_pd<2>(sys, *plastic, i)) history = *fitted;
      const mpm::StressResult r = law.update(F, history);
      tau = r.kirchhoff;
      W = r.energy + plastic_work(history.eq_plastic_strain);
    } else {
      F = mpm.state().F[i];
      tau = mpm.state().kirchhoff[i];
      W = mpm.state().energy[i] + plastic_work(mpm.eq_plastic_strain(i));
    }
    core::JSample s;
    s.X = p.x0[i];
    s.volume = p.volume[i];
    s.grad_u = F - Mat<2>::Identity();
    s.stress = tau.topLeftCorner<2, 2>() * F.inverse().transpose();
    s.energy = W;
    out.push_back(s);
  }
  return out;
}

}  // namespace pdmpm::hybrid
