#include "solver/hybrid/j_samples.hpp"

#include "solver/core/error.hpp"

#include "solver/hybrid/conversion.hpp"
#include "solver/hybrid/plastic_state_transfer.hpp"
#include "solver/mpm/constitutive.hpp"
#include "solver/mpm/j_samples.hpp"
#include "solver/pd/lps_plastic.hpp"

namespace pdmpm::hybrid {

std::vector<core::JSample> j_samples(const Simulation<2>& h, const Vec<2>& centre, double radius) {
  const core::Particles<2>& p = h.particles();
  const mpm::Simulation<2>& mpm = h.mpm();
  const pd::System<2>& sys = h.pd().system();
  const auto* plastic = dynamic_cast<const pd::LpsPlastic<2>*>(&h.pd().model());
  const mpm::Constitutive<2> law(mpm.settings().material, mpm.settings().setting);
  std::vector<core::JSample> out;
  for (Index i = 0; i < p.n_real; ++i) {
    if ((p.x0[i] - centre).norm() >= radius) continue;
    if (p.kind[i] == core::ParticleKind::removed) continue;
    if (p.kind[i] != core::ParticleKind::pd) {
      if (const auto s = mpm::j_sample(mpm, i)) out.push_back(*s);
      continue;
    }
    if (mpm.failed(i)) continue;
    const auto F = bond_deformation_gradient<2>(sys, i);
    if (!F) continue;
    mpm::PointHistory history = mpm.state().history(i);
    if (plastic)
      if (const auto fitted = plastic_state_from_pd<2>(sys, *plastic, i)) history = *fitted;
    mpm::StressResult r;
    try {
      r = law.update(*F, history);
    } catch (const RunError&) {  // an inverted F (a particle crushed into the crack): no sample, as without F
      continue;
    }
    core::JSample s;
    s.X = p.x0[i];
    s.volume = p.volume[i];
    s.grad_u = *F - Mat<2>::Identity();
    s.stress = r.kirchhoff.topLeftCorner<2, 2>() * F->inverse().transpose();
    s.energy = r.energy + mpm::monotonic_plastic_work(mpm.settings().material, history.eq_plastic_strain);
    out.push_back(s);
  }
  return out;
}

}  // namespace pdmpm::hybrid
