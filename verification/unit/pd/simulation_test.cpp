// One body, two methods: a particle store whose particles are partly PD and
// partly MPM. PD advances only its own particles, MPM only its own, each counts
// a particle's energy once, and changing kinds never heals a broken bond.
#include "solver/pd/simulation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include <fmt/format.h>

#include "solver/io/scene.hpp"
#include "solver/mpm/simulation.hpp"
#include "solver/sim/mpm_setup.hpp"
#include "solver/sim/pd_setup.hpp"
#include "solver/time/velocity_verlet.hpp"
#include "verification/support/scene_text.hpp"

namespace pdmpm::pd {
namespace {

using core::ParticleKind;

// ν for a plane-stress plate: a pair potential's fixed value, else 0.3 (MPM too).
std::string poisson_text(const std::string& model) {
  const auto* info = find_model(model);
  const auto nu = info ? info->fixed_poisson(core::Setting::plane_stress) : std::nullopt;
  return nu ? fmt::format("{}", *nu) : "0.3";
}

// The same free 2D steel plate for both methods; `model` is "lps", "pmb" or "mpm";
// `material_keys` go into [material].
io::Scene plate(const std::string& model, const std::string& material_keys = "", double length = 0.03) {
  return test::SceneText{.id = "mixed",
                         .max = {length, 0.012},
                         .poissons_ratio = poisson_text(model),
                         .material_keys = material_keys,
                         .model = model}
      .parse("mixed.toml");
}

// A smooth stretch and velocity field, so every particle feels a force.
void perturb(core::Particles<2>& p) {
  for (Index i = 0; i < p.n_real; ++i) {
    const Vec<2> x = p.x0[i];
    p.u[i] = Vec<2>(2e-4 * x[0] + 1e-3 * x[1] * x[1], -1e-4 * x[1]);
    p.v[i] = Vec<2>(std::sin(200 * x[1]), std::cos(150 * x[0])) * 0.1;
  }
  p.update_ghosts();
}

// Left third PD, the rest MPM.
void split(core::Particles<2>& p) {
  for (Index i = 0; i < p.n_real; ++i) p.kind[i] = p.x0[i][0] < 0.01 ? ParticleKind::pd : ParticleKind::mpm;
}

double kinetic(const core::Particles<2>& p, double rho, ParticleKind k) {
  double e = 0.0;
  for (Index i = 0; i < p.n_real; ++i)
    if (p.kind[i] == k) e += 0.5 * rho * p.volume[i] * p.v[i].squaredNorm();
  return e;
}

TEST(MixedBody, EachMethodAdvancesOnlyItsOwnParticles) {
  for (const std::string model : {"lps", "pmb"}) {
    SCOPED_TRACE(model);
    auto setup = sim::build_pd<2>(plate(model));
    auto& p = setup.system.particles;
    split(p);
    perturb(p);
    // Whatever MPM left in f of its particles must not reach a PD kick.
    for (Index i = 0; i < p.n_real; ++i) p.f[i] = Vec<2>(1e9, -1e9);
    auto pd_sim = sim::make_simulation(setup);
    const auto mpm_setup = sim::build_mpm<2>(plate("mpm"));
    ASSERT_EQ(mpm_setup.particles.n_real, p.n_real);
    mpm::Simulation<2> mpm_sim(mpm_setup.settings, p);

    Index n_pd = 0;
    for (Index i = 0; i < p.n_real; ++i) n_pd += p.kind[i] == ParticleKind::pd;
    ASSERT_GT(n_pd, 0);
    ASSERT_LT(n_pd, p.n_real);
    EXPECT_EQ(static_cast<Index>(pd_sim.movers().size()), n_pd);
    EXPECT_EQ(static_cast<Index>(mpm_sim.active().size()), p.n_real - n_pd);

    // Bonds across the interface are inactive; bonds inside the PD part are live.
    const auto& sys = setup.system;
    Index across = 0;
    for (Index i = 0; i < p.n_real; ++i)
      for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b) {
        const bool both_pd = p.kind[i] == ParticleKind::pd && sys.kind(sys.families.neighbor[b]) == ParticleKind::pd;
        EXPECT_EQ(sys.bonds.live(b), both_pd);
        across += p.kind[i] == ParticleKind::pd && !both_pd;
      }
    EXPECT_GT(across, 0) << "the split must cut bonds, or the interface is not tested";

    // PD forces of the PD part equal those of a body made of the PD part alone:
    // the MPM particles are not there for PD. (Tolerance: masked bonds shift
    // the lane order of the sums, so equal to round-off, not bitwise.)
    pd_sim.internal_forces(false);
    auto alone = sim::build_pd<2>(plate(model, "", 0.01));
    auto& q = alone.system.particles;
    ASSERT_EQ(q.n_real, n_pd);
    {
      Index k = 0;
      for (Index i = 0; i < p.n_real; ++i)
        if (p.kind[i] == ParticleKind::pd) {
          ASSERT_EQ(q.site[k], p.site[i]);
          q.u[k++] = p.u[i];
        }
    }
    q.update_ghosts();
    auto alone_sim = sim::make_simulation(alone);
    alone_sim.internal_forces(false);
    double fmax = 0.0;
    for (Index i = 0; i < q.n_real; ++i) fmax = std::max(fmax, q.f[i].norm());
    ASSERT_GT(fmax, 0.0);
    for (Index i = 0, k = 0; i < p.n_real; ++i)
      if (p.kind[i] == ParticleKind::pd) {
        EXPECT_LE((p.f[i] - q.f[k++]).norm(), 1e-12 * fmax) << i;
      }

    // A PD step moves PD particles only.
    const auto u0 = p.u, v0 = p.v;
    time::VelocityVerlet<2> verlet(pd_sim, 1e-8);
    verlet.start();
    verlet.step(true);
    for (Index i = 0; i < p.n_real; ++i) {
      const bool pd = p.kind[i] == ParticleKind::pd;
      if (pd) {
        EXPECT_NE(p.v[i], v0[i]) << i;
      } else {
        EXPECT_EQ(p.u[i], u0[i]) << i;
        EXPECT_EQ(p.v[i], v0[i]) << i;
      }
    }
    // An MPM step moves MPM particles only.
    const auto u1 = p.u, v1 = p.v;
    mpm_sim.step(1e-8);
    for (Index i = 0; i < p.n_real; ++i) {
      const bool pd = p.kind[i] == ParticleKind::pd;
      if (pd) {
        EXPECT_EQ(p.u[i], u1[i]) << i;
        EXPECT_EQ(p.v[i], v1[i]) << i;
      } else {
        EXPECT_NE(p.u[i], u1[i]) << i;
      }
    }

    // Each particle's kinetic energy is counted once: by PD or by MPM.
    const double rho = pd_sim.density();
    const double all = kinetic(p, rho, ParticleKind::pd) + kinetic(p, rho, ParticleKind::mpm);
    EXPECT_DOUBLE_EQ(pd_sim.kinetic_energy(), kinetic(p, rho, ParticleKind::pd));
    // Tolerance: the MPM sum uses m_p = ρ V_p per particle, a different rounding order.
    EXPECT_NEAR(pd_sim.kinetic_energy() + mpm_sim.energies().kinetic, all, 1e-12 * all);
    // PD strain energy comes from PD particles only: with no PD particle there is none.
    EXPECT_GT(pd_sim.internal_energy(), 0.0);
    for (Index i = 0; i < p.n_real; ++i) p.kind[i] = ParticleKind::mpm;
    pd_sim.refresh_kinds();
    pd_sim.internal_forces(true);
    EXPECT_EQ(pd_sim.internal_energy(), 0.0);
    EXPECT_EQ(pd_sim.kinetic_energy(), 0.0);
    EXPECT_TRUE(pd_sim.movers().empty());
  }
}

// A body torn by its own stretch, then its particles sent back and forth between
// PD, transition and MPM: every broken bond stays broken, and the PD step of the
// all-PD body afterwards gives the same forces as a body that never changed kind.
TEST(MixedBody, KindChangesNeverHealBrokenBonds) {
  const auto scene = plate("lps", "critical_stretch = 2e-4\n");
  auto setup = sim::build_pd<2>(scene);
  auto twin = sim::build_pd<2>(scene);
  for (auto* s : {&setup, &twin}) {
    auto& p = s->system.particles;
    for (Index i = 0; i < p.n_real; ++i) p.u[i] = Vec<2>(4e-4 * p.x0[i][0] * (p.x0[i][0] > 0.015 ? 2.0 : 0.0), 0.0);
    p.update_ghosts();
  }
  auto sim = sim::make_simulation(setup);
  auto twin_sim = sim::make_simulation(twin);
  sim.internal_forces(false);
  sim.accept();
  twin_sim.internal_forces(false);
  twin_sim.accept();
  auto& sys = setup.system;
  std::vector<BondIndex> broken;
  for (BondIndex b = 0; b < sys.families.n_bonds(); ++b)
    if (sys.bonds.broken(b)) broken.push_back(b);
  ASSERT_GT(broken.size(), 10u) << "the stretch must break bonds, or healing is not tested";

  auto& p = sys.particles;
  for (const auto kind : {ParticleKind::mpm, ParticleKind::transition, ParticleKind::pd, ParticleKind::mpm}) {
    for (Index i = 0; i < p.n_real; i += 2) p.kind[i] = kind;  // half the body, interleaved
    sim.refresh_kinds();
    for (BondIndex b : broken) EXPECT_TRUE(sys.bonds.broken(b)) << "bond " << b << " healed";
    for (Index i = 0; i < p.n_real; ++i) p.kind[i] = kind;  // then all of it
    sim.refresh_kinds();
    for (BondIndex b : broken) EXPECT_TRUE(sys.bonds.broken(b)) << "bond " << b << " healed";
  }
  for (Index i = 0; i < p.n_real; ++i) p.kind[i] = ParticleKind::pd;
  sim.refresh_kinds();
  sim.internal_forces(false);
  twin_sim.internal_forces(false);
  for (Index i = 0; i < p.n_real; ++i) EXPECT_EQ(p.f[i], twin.system.particles.f[i]) << i;
  EXPECT_EQ(sys.bonds.flags.trial, twin.system.bonds.flags.trial);
}

// Bonds broken by an evaluation are a trial until accepted: reject() restores
// the committed state, accept() keeps them.
TEST(BondState, RejectRestoresAndAcceptKeeps) {
  auto setup = sim::build_pd<2>(plate("pmb", "critical_stretch = 2e-4\n"));
  auto& p = setup.system.particles;
  for (Index i = 0; i < p.n_real; ++i) p.u[i] = Vec<2>(1e-3 * p.x0[i][0] * (p.x0[i][0] > 0.015), 0.0);
  p.update_ghosts();
  auto sim = sim::make_simulation(setup);
  const auto before = setup.system.bonds.flags.trial;
  sim.internal_forces(false);
  ASSERT_NE(setup.system.bonds.flags.trial, before);
  sim.reject();
  EXPECT_EQ(setup.system.bonds.flags.trial, before);
  sim.internal_forces(false);
  const auto after = setup.system.bonds.flags.trial;
  sim.accept();
  sim.reject();
  EXPECT_EQ(setup.system.bonds.flags.trial, after);
}

// Re-deriving only the bonds of the particles whose kind changed, and their neighbours',
// gives what the full pass gives — the bond flags, the particles whose active bonds
// changed, the owner list — over a sequence of random kind changes (PD, transition,
// MPM, removed), as a hybrid makes them at every conversion.
class MixedBodyRefresh : public ::testing::TestWithParam<bool> {};

TEST_P(MixedBodyRefresh, OfTheChangedKindsEqualsTheFullPass) {
  const auto scene = plate("lps");
  auto full = sim::build_pd<2>(scene);
  auto part = sim::build_pd<2>(scene);
  full.system.transition_full_state = part.system.transition_full_state = GetParam();
  const Index n = full.system.particles.n_real;
  ASSERT_EQ(full.system.particles.n_ghost(), 0);
  std::mt19937 rng(3);
  std::uniform_int_distribution<Index> pick(0, n - 1);
  std::uniform_int_distribution<int> kind(0, 3);
  const ParticleKind kinds[] = {ParticleKind::pd, ParticleKind::transition, ParticleKind::mpm, ParticleKind::removed};
  std::size_t refreshed = 0;
  for (int round = 0; round < 40; ++round) {
    std::vector<Index> changed;
    const int count = 1 + round % 7;
    for (int c = 0; c < count; ++c) {
      const Index i = pick(rng);
      const ParticleKind k = kinds[kind(rng)];
      if (full.system.particles.kind[i] == k || std::find(changed.begin(), changed.end(), i) != changed.end()) continue;
      full.system.particles.kind[i] = part.system.particles.kind[i] = k;
      changed.push_back(i);
    }
    std::sort(changed.begin(), changed.end());
    const auto a = full.system.refresh_activity();
    const auto b = part.system.refresh_activity(changed);
    EXPECT_EQ(a, b) << "round " << round;
    EXPECT_EQ(full.system.owners, part.system.owners) << "round " << round;
    EXPECT_TRUE(full.system.bonds.flags.trial == part.system.bonds.flags.trial) << "round " << round;
    refreshed += a.size();
  }
  EXPECT_GT(refreshed, 100u) << "the changes must change bonds, or nothing is compared";
}

// With and without state-only bonds (transition particles keeping whole families).
INSTANTIATE_TEST_SUITE_P(MixedBody, MixedBodyRefresh, ::testing::Bool());

// Kinds in bands along x: PD, then transition (a bond reach wide), then MPM.
void bands(core::Particles<2>& p, double pd_to, double transition_to) {
  for (Index i = 0; i < p.n_real; ++i) {
    const double x = p.x0[i][0];
    p.kind[i] = x < pd_to ? ParticleKind::pd : x < transition_to ? ParticleKind::transition : ParticleKind::mpm;
  }
}

// Under an affine motion, transition particles that measure their state over their whole
// family (pd::System::transition_full_state) have the interior force state, so every PD
// particle is in equilibrium, the one next to the transition band too; measured over
// their bonds to PD particles alone (the paper's coupling), the PD particles next to the
// band feel a force of the order of a free face's. State-only bonds exist only when asked for.
TEST(MixedBody, FullStateTransitionParticlesLeaveNoGhostForceOnPd) {
  const double height = 0.03;
  const auto scene = test::SceneText{.id = "mixed",
                                     .max = {0.04, height},
                                     .poissons_ratio = poisson_text("lps_plastic"),
                                     .material_keys = "yield_stress = 1e12\ntangent_modulus = 0\n",
                                     .model = "lps_plastic"}
                         .parse("mixed.toml");
  for (const bool full_state : {false, true}) {
    auto setup = sim::build_pd<2>(scene);
    auto& sys = setup.system;
    auto& p = sys.particles;
    sys.transition_full_state = full_state;
    const double dx = sys.spacing(), reach = 3.5 * dx, pd_to = 0.02;
    bands(p, pd_to, pd_to + reach);
    Mat<2> H;
    H << 1e-4, 0.3e-4, 0.3e-4, -0.5e-4;
    for (Index i = 0; i < p.n_real; ++i) p.u[i] = H * p.x0[i];
    auto sim = sim::make_simulation(setup);
    sim.refresh_kinds();
    sim.internal_forces(false);
    // Away from the top and bottom edges (two bond reaches: a free face disturbs the states
    // of the particles within one reach, and the forces of those within two): the largest
    // force on the PD particles at the left edge (the scale: a free face) and on those
    // within a reach of the transition band.
    double edge = 0.0, interface = 0.0;
    for (Index i = 0; i < p.n_real; ++i) {
      const Vec<2> x = p.x0[i];
      if (p.kind[i] != ParticleKind::pd || x[1] < 2 * reach || x[1] > height - 2 * reach) continue;
      if (x[0] < dx) edge = std::max(edge, p.f[i].norm());
      if (x[0] > pd_to - reach) interface = std::max(interface, p.f[i].norm());
    }
    ASSERT_GT(edge, 0.0);
    if (full_state) {
      EXPECT_LT(interface, 1e-11 * edge) << "round-off of sums of ~30 bonds";
    } else {
      EXPECT_GT(interface, 0.1 * edge) << "the paper's coupling leaves a ghost force at the interface";
    }
    // Bonds to grid particles count in the state only when asked for.
    Index state_only = 0;
    for (Index i = 0; i < p.n_real; ++i)
      for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b)
        state_only += sys.bonds.role(b) == BondRole::state_only;
    if (full_state) {
      EXPECT_GT(state_only, 0);
    } else {
      EXPECT_EQ(state_only, 0);
    }
  }
}

}  // namespace
}  // namespace pdmpm::pd
