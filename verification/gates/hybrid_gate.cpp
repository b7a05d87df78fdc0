// Gates of the adaptive SBPD–MPM hybrid (Noorian et al., adaptive SBPD–MPM §2):
// interface consistency under affine motion (ghost forces), …
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <iostream>

#include "verification/support/gate.hpp"
#include "solver/pd/damage.hpp"
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
GhostForces ghost_forces(const Mat<2>& H, hybrid::Coupling coupling) {
  GhostForces g;
  const Vec<2> size(0.04, 0.03), centre = 0.5 * size;
  auto measure = [&](hybrid::Mode mode, bool with_pd, double& pd, double& tr, double& mp) {
    hybrid::Settings s;
    s.mode = mode;
    s.coupling = coupling;
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
  for (auto coupling : {hybrid::Coupling::paper, hybrid::Coupling::consistent})
  for (const auto& [label, H] : {std::pair{"stretch", stretch}, std::pair{"shear", shear}}) {
    const GhostForces g = ghost_forces(H, coupling);
    std::cout << name(coupling) << " " << label << ": PD " << g.pd << " transition " << g.transition << " MPM " << g.mpm << " | all PD "
              << g.pd_only << " all MPM " << g.mpm_only << "\n";
  }
}


// A brittle edge crack (critical stretch) in a plate pulled at both edges: the same
// scene in the three modes. The crack runs through PD in every mode; in expand and
// expand_shrink the PD region has to follow it.
struct CrackRun {
  std::vector<double> t, tip_x;  // the furthest tip's x (m) against time
  std::vector<double> damage;    // per particle at the end
  hybrid::Events events;
  hybrid::KindCounts counts;
  double pd_steps = 0.0, mpm_steps = 0.0, seconds = 0.0;
};

CrackRun run_edge_crack(hybrid::Mode mode, hybrid::Coupling coupling) {
  hybrid::Settings s;
  s.mode = mode;
  s.coupling = coupling;
  s.radii = {.pd_radius = 2.0, .expand_trigger = 1.0, .expand_radius = 2.0, .keep_radius = 2.0};
  auto env = [](const char* k, const char* d) { return std::string(std::getenv(k) ? std::getenv(k) : d); };
  const std::string v = env("HYBRID_V", "2*min(t/1e-5, 1)"), sc = env("HYBRID_SC", "0.003");
  const int steps = std::stoi(env("HYBRID_STEPS", "2500"));
  const std::string pull = R"(
[[boundary]]
name = "bottom"
kind = "velocity"
region = { type = "box", min = [-1, -1], max = [1, 1.5e-3] }
value = ["free", "-)" + v + R"("]
[[boundary]]
name = "top"
kind = "velocity"
region = { type = "box", min = [-1, 28.5e-3], max = [1, 1] }
value = ["free", ")" + v + R"("]
)";
  test::HybridBody body(s, {.size = {0.06, 0.03},
                            .tables = pull,
                            .pd_tables = "[[precrack]]\nfrom = [-1e-3, 0.0155]\nto = [0.015, 0.0155]\n",
                            .pd_material_keys = "critical_stretch = " + sc,
                            .hardening = "yield_stress = 1e12\ntangent_modulus = 0"});
  body.hybrid->start();
  CrackRun r;
  const double dt = 2e-8;
  for (int n = 1; n <= steps; ++n) {
    body.hybrid->step(dt);
    if (std::getenv("HYBRID_DUMP") && n % 250 == 0) {
      const auto phi = pd::local_damage(body.pd_setup.system);
      auto& p = body.particles();
      std::cout << "step " << n << " " << name(mode) << "\n";
      std::vector<char> grid(60 * 30, ' ');
      for (Index k = 0; k < p.n_real; ++k) {
        const int i = p.site[k][0], j = p.site[k][1];
        if (i < 0 || i >= 60 || j < 0 || j >= 30) continue;
        grid[j * 60 + i] = p.kind[k] == ParticleKind::pd ? (phi[k] > 0.35 ? '#' : phi[k] > 0.05 ? '+' : 'o')
                         : p.kind[k] == ParticleKind::transition ? 't' : '.';
      }
      for (int j = 29; j >= 0; --j) {
        for (int i = 0; i < 60; ++i) {
          const char c = grid[j * 60 + i];
          std::cout << c;
        }
        std::cout << "\n";
      }
    }
    if (n % 50 == 0) {
      double x = 0.0;
      for (const auto& tip : body.hybrid->track_tips()) x = std::max(x, tip.position[0]);
      r.t.push_back(body.hybrid->time());
      r.tip_x.push_back(x);
    }
  }
  r.damage = pd::local_damage(body.pd_setup.system);
  r.events = body.hybrid->events();
  r.counts = body.hybrid->counts();
  r.pd_steps = static_cast<double>(body.hybrid->pd_particle_steps());
  r.mpm_steps = static_cast<double>(body.hybrid->mpm_particle_steps());
  r.seconds = body.hybrid->phase_seconds().total();
  return r;
}

TEST(FastHybrid, EdgeCrackFollowsTheAllPdRun) {
  const CrackRun pd = run_edge_crack(hybrid::Mode::pd, hybrid::Coupling::consistent);
  for (auto coupling : {hybrid::Coupling::paper, hybrid::Coupling::consistent})
  for (auto mode : {hybrid::Mode::expand, hybrid::Mode::expand_shrink}) {
    const CrackRun h = run_edge_crack(mode, coupling);
    std::cout << name(coupling) << " ";
    double worst = 0.0;
    for (std::size_t k = 0; k < pd.t.size(); ++k) worst = std::max(worst, std::abs(h.tip_x[k] - pd.tip_x[k]));
    std::cout << name(mode) << ": tip deviation " << worst / kDx << " dx; to_pd " << h.events.to_pd << " to_mpm "
              << h.events.to_mpm << " expansions " << h.events.expansions << " shrinks " << h.events.shrinks
              << " pd " << h.counts.pd << " tr " << h.counts.transition << " mpm " << h.counts.mpm << " | pd steps "
              << h.pd_steps << " mpm steps " << h.mpm_steps << " seconds " << h.seconds << " (all PD " << pd.seconds
              << ")\n";
    for (std::size_t k = 0; k < pd.t.size(); k += 5) std::cout << "  t " << pd.t[k] << " pd " << pd.tip_x[k] << " hybrid " << h.tip_x[k] << "\n";
  }
}
}  // namespace
}  // namespace pdmpm
namespace pdmpm {
TEST(DebugHybrid, BondStretchNoise) {
  for (auto mode : {hybrid::Mode::expand, hybrid::Mode::pd}) {
    hybrid::Settings s;
    s.mode = mode;
    const std::string pull = R"X(
[[boundary]]
name = "bottom"
kind = "velocity"
region = { type = "box", min = [-1, -1], max = [1, 1.5e-3] }
value = ["free", "-0.3*min(t/1e-5, 1)"]
[[boundary]]
name = "top"
kind = "velocity"
region = { type = "box", min = [-1, 28.5e-3], max = [1, 1] }
value = ["free", "0.3*min(t/1e-5, 1)"]
)X";
    test::HybridBody body(s, {.size = {0.06, 0.03}, .tables = pull, .hardening = "yield_stress = 1e12\ntangent_modulus = 0"});
    body.hybrid->start();
    for (int n = 1; n <= 3000; ++n) body.hybrid->step(2e-8);
    const auto& sys = body.pd_setup.system;
    const auto& p = sys.particles;
    std::vector<double> st;
    for (Index i = 0; i < p.n_real; ++i) {
      if (p.x0[i][1] < 5e-3 || p.x0[i][1] > 25e-3) continue;
      for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b) {
        const Index j = sys.families.neighbor[b];
        const Vec<2> xi = p.x0[j] - p.x0[i];
        const double s = std::getenv("RATE") ? (p.v[j] - p.v[i]).dot(xi) / xi.squaredNorm() : ((p.position(j) - p.position(i)).norm() - xi.norm()) / xi.norm();
        st.push_back(s);
      }
    }
    std::sort(st.begin(), st.end());
    std::cout << name(mode) << " stretch: median " << st[st.size() / 2] << " 99% " << st[st.size() * 99 / 100] << " max "
              << st.back() << "\n";
  }
}
}  // namespace pdmpm
namespace pdmpm {
TEST(DebugHybrid, Stability) {
  for (auto coupling : {hybrid::Coupling::paper, hybrid::Coupling::consistent}) {
    hybrid::Settings s;
    s.mode = hybrid::Mode::expand;
    s.coupling = coupling;
    test::HybridBody body(s, {.size = {0.04, 0.03}, .hardening = "yield_stress = 1e12\ntangent_modulus = 0"});
    auto& p = body.particles();
    std::vector<Index> disc;
    for (Index i = 0; i < p.n_real; ++i) {
      p.v[i] = Vec<2>(std::sin(1e3 * p.x0[i][0] * p.x0[i][1] * 1e3), std::cos(7e5 * p.x0[i][0] * p.x0[i][0]));
      if ((p.x0[i] - Vec<2>(0.02, 0.015)).norm() < 7e-3) disc.push_back(i);
    }
    body.hybrid->start(disc);
    for (int n = 1; n <= 8000; ++n) {
      body.hybrid->step(2e-8, n % 1000 == 0);
      if (n % 1000 == 0) std::cout << name(coupling) << " step " << n << " KE " << body.hybrid->kinetic_energy() << " IE " << body.hybrid->internal_energy() << "\n";
    }
  }
}
}  // namespace pdmpm
