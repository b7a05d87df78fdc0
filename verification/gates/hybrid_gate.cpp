// Gates of the adaptive SBPD–MPM hybrid (Noorian et al., adaptive SBPD–MPM §2):
// interface consistency under affine motion (ghost forces), …
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "verification/support/gate.hpp"
#include "verification/support/hybrid_body.hpp"

namespace pdmpm {
namespace {

using core::ParticleKind;
using test::Compare;
using test::Gate;

const char* kProblem = "hybrid";
constexpr double kRho = 7850.0, kDx = 1e-3;

struct GhostForces {
  double pd = 0.0, transition = 0.0, mpm = 0.0;  // max |a| / a_scale over interior particles of each kind
  double pd_only = 0.0, mpm_only = 0.0;          // the same body all PD / all MPM
};

// Accelerations of an affine displacement u = H x (no velocity) after one tiny step,
// relative to a_scale = |σ|/(ρ Δx), the acceleration of a particle on a free face carrying
// the affine state's traction. Particles within 4Δx of the plate's edges are skipped (the
// free edges are not in equilibrium under an affine field).
GhostForces ghost_forces(const Mat<2>& H) {
  GhostForces g;
  const Vec<2> size(0.04, 0.03), centre = 0.5 * size;
  auto measure = [&](hybrid::Mode mode, bool with_pd, double& pd, double& tr, double& mp) {
    hybrid::Settings s;
    s.mode = mode;
    test::HybridBody body(s, {.size = {size[0], size[1]}});
    auto& p = body.particles();
    std::vector<Index> disc;
    for (Index i = 0; i < p.n_real; ++i) {
      p.u[i] = H * p.x0[i];
      body.mpm->set_deformation_gradient(i, Mat<2>::Identity() + H);
      if (with_pd && (p.x0[i] - centre).norm() < 7e-3) disc.push_back(i);
    }
    body.hybrid->start(disc);
    const double sigma = body.mpm->state().stress[0].norm();
    const double a_scale = sigma / (kRho * kDx);
    const double dt = 1e-13;
    body.hybrid->step(dt);
    for (Index i = 0; i < p.n_real; ++i) {
      const Vec<2> x = p.x0[i];
      if (x[0] < 4 * kDx || x[1] < 4 * kDx || x[0] > size[0] - 4 * kDx || x[1] > size[1] - 4 * kDx) continue;
      const double a = p.v[i].norm() / dt / a_scale;
      switch (p.kind[i]) {
        case ParticleKind::pd: pd = std::max(pd, a); break;
        case ParticleKind::transition: tr = std::max(tr, a); break;
        default: mp = std::max(mp, a);
      }
    }
  };
  double unused = 0.0;
  measure(hybrid::Mode::expand, true, g.pd, g.transition, g.mpm);
  measure(hybrid::Mode::pd, false, g.pd_only, unused, unused);
  measure(hybrid::Mode::expand, false, unused, unused, g.mpm_only);
  return g;
}

TEST(FastHybrid, InterfaceGhostForcesUnderAffineMotion) {
  Mat<2> stretch, shear;
  stretch << 1e-4, 0.0, 0.0, -0.3e-4;
  shear << 0.0, 1e-4, 1e-4, 0.0;
  for (const auto& [name, H] : {std::pair{"stretch", stretch}, std::pair{"shear", shear}}) {
    const GhostForces g = ghost_forces(H);
    std::cout << name << ": PD " << g.pd << " transition " << g.transition << " MPM " << g.mpm << " | all PD "
              << g.pd_only << " all MPM " << g.mpm_only << "\n";
  }
}

}  // namespace
}  // namespace pdmpm
