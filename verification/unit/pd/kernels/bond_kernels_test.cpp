// The bond kernels claim bitwise identical results for every instruction set
// (bond_kernels.hpp: canonical lane order, selects instead of branches). Each
// set this CPU can run is compared with SSE2 on bodies that take every gather
// path: whole and cut families, consecutive and scattered stencil offsets, the
// last particle of u as a neighbour (narrow gather), uniform and per-particle
// volumes, pre-broken bonds and bonds breaking during the call. lps_plastic's two
// kernels are run back to back on the same bodies (the return mapping between them
// is the model's, not the kernels').
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "solver/pd/kernels/kernel_set.hpp"
#include "verification/support/pd_fixtures.hpp"

namespace pdmpm::pd::kernels {
namespace {

std::vector<const KernelSet*> runnable_sets() {
  std::vector<const KernelSet*> sets{&kernels_sse2};
  if (__builtin_cpu_supports("avx2")) sets.push_back(&kernels_avx2);
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq"))
    sets.push_back(&kernels_avx512);
  return sets;
}

// Everything a kernel call writes, compared byte by byte.
struct Outputs {
  std::vector<double> f, energy, theta, theta_c, norm2, strain;
  std::vector<std::uint8_t> broken;
  std::int64_t newly = 0;
  bool operator==(const Outputs& o) const {
    auto same = [](const auto& a, const auto& b) {
      return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof a[0]) == 0;
    };
    return newly == o.newly && same(f, o.f) && same(energy, o.energy) && same(theta, o.theta) &&
        same(theta_c, o.theta_c) && same(norm2, o.norm2) && same(strain, o.strain) && same(broken, o.broken);
  }
};

template <int D>
struct Body {
  System<D> sys;
  std::vector<double> m, alpha_beta;
  // lps_plastic's inputs: c per offset, 1/m_d, (μ, s, γθ_c, 0), the volumetric energy and r per
  // particle; p_n and the reverse bond's p per bond side.
  std::vector<double> shell, inv_md, rows, volumetric, scale, plastic, reverse_plastic;

  explicit Body(bool uniform_volume, bool state_only = false) {
    test::BlockSpec spec;
    spec.sites = D == 1 ? 40 : D == 2 ? 14 : 8;
    spec.setting = D == 1 ? core::Setting::bar1d : D == 2 ? core::Setting::plane_strain : core::Setting::solid3d;
    spec.measure = D == 3 ? 1.0 : 1e-3;
    sys = test::make_block<D>(spec);
    auto& p = sys.particles;
    const double dx = spec.spacing;
    for (Index i = 0; i < p.size(); ++i) {
      for (int a = 0; a < D; ++a) {  // non-affine, strains up to ~2 %: some bonds exceed s₀ below
        const Vec<D> y = p.x0[i] / dx;
        p.u[i][a] = 0.02 * dx * std::sin(0.9 * y[0] + 0.4 * a + (D > 1 ? 0.7 * y[D - 1] : 0.0)) * y[a] / 3.0;
      }
      if (!uniform_volume) p.volume[i] *= 1.0 + 0.01 * (i % 5);
    }
    for (BondIndex b = 0; b < sys.families.n_bonds(); b += 7) sys.bonds.cut(b);  // pre-cut bonds
    if (state_only) {  // as a hybrid's full-state transition particles have them (pd/bond_state.hpp)
      sys.transition_full_state = true;
      for (BondIndex b = 3; b < sys.families.n_bonds(); b += 5)
        if (sys.bonds.live(b)) sys.bonds.set_role(b, BondRole::state_only);
    }
    const auto n = static_cast<std::size_t>(p.size());
    m.resize(n);
    alpha_beta.resize(2 * n);
    for (std::size_t i = 0; i < n; ++i) {
      m[i] = 1e-9 * (1.0 + 0.1 * static_cast<double>(i % 3));
      alpha_beta[2 * i] = 1e3 * std::cos(0.3 * static_cast<double>(i));
      alpha_beta[2 * i + 1] = 2e3 * (1.0 + 0.05 * static_cast<double>(i % 4));
    }
    shell.assign(sys.families.stencil.size() + lanes, 0.0);
    for (int k = 0; k < sys.families.stencil.size(); ++k) shell[k] = 1.0 + 0.1 * std::sin(1.3 * k);
    inv_md.resize(n);
    rows.assign(4 * n, 0.0);
    volumetric.resize(n);
    scale.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      inv_md[i] = 1e9 / (1.0 + 0.2 * static_cast<double>(i % 4));
      rows[4 * i] = 1e12 * std::cos(0.7 * static_cast<double>(i));
      rows[4 * i + 1] = 3e12 * (1.0 + 0.03 * static_cast<double>(i % 5));
      rows[4 * i + 2] = 1e-3 * std::sin(1.1 * static_cast<double>(i));
      volumetric[i] = 1e3 * static_cast<double>(i % 7);
      scale[i] = 1.0 - 0.02 * static_cast<double>(i % 3);
    }
    const BondIndex n_bonds = sys.families.n_bonds();
    plastic.assign(static_cast<std::size_t>(n_bonds) + lanes, 0.0);
    reverse_plastic.assign(static_cast<std::size_t>(n_bonds) + lanes, 0.0);
    for (BondIndex b = 0; b < n_bonds; ++b) {
      plastic[static_cast<std::size_t>(b)] = 1e-4 * std::sin(0.37 * static_cast<double>(b));
      reverse_plastic[static_cast<std::size_t>(b)] = 1e-4 * std::cos(0.23 * static_cast<double>(b));
    }
  }

  // The fields PmbArgs and LpsArgs share, pointed at this body and at `out`.
  template <class Args>
  Args common_args(Outputs& out) {
    Args a{};
    a.fam = sys.family_view();
    a.fam.broken = out.broken.data();
    a.table = sys.table.view();
    a.u = sys.particles.u.data()->data();
    a.volume = sys.particles.volume.data();
    a.uniform_volume = sys.uniform_volume();
    a.f = out.f.data();
    a.energy = out.energy.data();
    a.breaking = true;
    a.s0 = 0.01;  // the body's strains reach ~2 %
    return a;
  }

  PmbArgs pmb_args(Outputs& out, bool breaking, bool after_force) {
    auto a = common_args<PmbArgs>(out);
    a.c = 1e12;
    a.breaking = breaking;
    a.after_force = after_force;
    return a;
  }

  LpsArgs lps_args(Outputs& out, bool after_force) {
    auto a = common_args<LpsArgs>(out);
    a.m = m.data();
    a.theta = out.theta.data();
    a.alpha_beta = alpha_beta.data();
    a.A = 3.0;
    a.B = 5.0;
    a.kappa = 7.0;
    a.gamma = 1.0 / D;
    a.d = D;
    a.after_force = after_force;
    return a;
  }

  Outputs fresh() const {
    Outputs o;
    o.f.assign(D * sys.particles.size(), 0.0);
    o.energy.assign(sys.particles.size(), 0.0);
    o.theta.assign(sys.particles.size(), 0.0);
    o.theta_c.assign(sys.particles.size(), 0.0);
    o.norm2.assign(sys.particles.size(), 0.0);
    o.strain.assign(sys.families.n_bonds() + lanes, 0.0);
    o.broken = sys.bonds.flags.trial;
    return o;
  }

  Outputs run_pmb(const KernelSet& set, bool breaking, bool after_force, bool energy) {
    Outputs out = fresh();
    PmbArgs a = pmb_args(out, breaking, after_force);
    if (!energy) a.energy = nullptr;
    out.newly = set.pmb[D - 1][energy](a);
    return out;
  }

  Outputs run_lps(const KernelSet& set, bool after_force) {
    Outputs out = fresh();
    const LpsArgs a = lps_args(out, after_force);
    out.newly = set.lps_dilatation[D - 1](a);
    out.newly += set.lps_forces[D - 1][1](a);
    return out;
  }

  Outputs run_lps_plastic(const KernelSet& set, bool after_force) {
    Outputs out = fresh();
    LpsPlasticArgs a;
    a.lps = lps_args(out, after_force);
    a.shell = shell.data();
    a.inv_md = inv_md.data();
    a.theta_c = out.theta_c.data();
    // The return mapping's stand-in records ε of every bond side handed to it.
    struct Recorder {
      double* strain;
      const FamilyView* fam;
    } recorder{out.strain.data(), &a.lps.fam};
    a.model = &recorder;
    a.return_map = [](void* r, Index i, const double* eps) {
      const auto* rec = static_cast<const Recorder*>(r);
      const BondIndex begin = rec->fam->offsets[i];
      for (BondIndex b = begin; b < rec->fam->offsets[i + 1]; ++b) rec->strain[b] = eps[b - begin];
    };
    a.plastic_extension = plastic.data();
    a.reverse_plastic = reverse_plastic.data();
    a.norm2 = out.norm2.data();
    a.particle_rows = rows.data();
    a.volumetric_energy = volumetric.data();
    a.scale = scale.data();
    a.B = 5.0;
    out.newly = set.lps_plastic_extension[D - 1](a);
    out.newly += set.lps_plastic_forces[D - 1][1](a);
    return out;
  }
};

template <int D>
void expect_every_set_matches_sse2() {
  // On a CPU with SSE2 only there is nothing to compare: the test is skipped, not passed.
  if (runnable_sets().size() == 1) GTEST_SKIP() << "only SSE2 on this CPU: nothing to compare";
  for (const bool uniform : {true, false})
    for (const bool state_only : {false, true}) {
      Body<D> body(uniform, state_only);
      ASSERT_EQ(body.sys.uniform_volume(), uniform);
      const std::string where = "D = " + std::to_string(D) + (uniform ? ", uniform volume" : ", per-particle volume") +
          (state_only ? ", state-only bonds" : "");
      const Outputs pmb_ref = body.run_pmb(kernels_sse2, true, false, true);
      const Outputs lps_ref = body.run_lps(kernels_sse2, false);
      ASSERT_GT(pmb_ref.newly, 0) << where << ": the body must break bonds during the call";
      for (const KernelSet* set : runnable_sets()) {
        const std::string what = where + ", " + set->name;
        for (const bool after : {false, true}) {
          EXPECT_TRUE(body.run_pmb(*set, true, after, true) == body.run_pmb(kernels_sse2, true, after, true))
              << what << ", PMB breaking, after_force " << after;
          EXPECT_TRUE(body.run_lps(*set, after) == body.run_lps(kernels_sse2, after))
              << what << ", LPS, after_force " << after;
          EXPECT_TRUE(body.run_lps_plastic(*set, after) == body.run_lps_plastic(kernels_sse2, after))
              << what << ", lps_plastic, after_force " << after;
        }
        EXPECT_TRUE(body.run_pmb(*set, false, false, false) == body.run_pmb(kernels_sse2, false, false, false))
            << what << ", PMB without energy or breaking";
        EXPECT_TRUE(body.run_pmb(*set, true, false, true) == pmb_ref) << what;
        EXPECT_TRUE(body.run_lps(*set, false) == lps_ref) << what;
      }
    }
}

// A state-only bond (pd/bond_state.hpp: a full-state transition particle's bond to a grid
// particle) counts in its owner's dilatation as a live bond does and exchanges no force, as an
// inactive one: LPS's θ is the all-live body's and its forces those of the body with these
// bonds inactive, bit for bit, on every instruction set (no bond breaks in these calls).
TEST(BondKernels, StateOnlyBondsCountInTheDilatationAndCarryNoForce) {
  Body<2> state(true, true), live(true), inactive(true);
  for (BondIndex b = 0; b < state.sys.families.n_bonds(); ++b)
    if (state.sys.bonds.role(b) == BondRole::state_only) inactive.sys.bonds.set_role(b, BondRole::inactive);
  auto evaluate = [](Body<2>& body, const KernelSet& set) {
    Outputs out = body.fresh();
    LpsArgs a = body.lps_args(out, false);
    a.breaking = false;
    set.lps_dilatation[1](a);
    set.lps_forces[1][1](a);
    return out;
  };
  auto same = [](const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof a[0]) == 0;
  };
  for (const KernelSet* set : runnable_sets()) {
    const Outputs s = evaluate(state, *set), l = evaluate(live, *set), i = evaluate(inactive, *set);
    EXPECT_TRUE(same(s.theta, l.theta)) << set->name;
    EXPECT_TRUE(same(s.f, i.f)) << set->name;
    EXPECT_FALSE(same(s.theta, i.theta)) << set->name << ": the state-only bonds must matter to θ";
    EXPECT_FALSE(same(s.f, l.f)) << set->name << ": and would carry force if live";
  }
}

TEST(BondKernels, EveryInstructionSetGivesTheSameBits1D) { expect_every_set_matches_sse2<1>(); }
TEST(BondKernels, EveryInstructionSetGivesTheSameBits2D) { expect_every_set_matches_sse2<2>(); }
TEST(BondKernels, EveryInstructionSetGivesTheSameBits3D) { expect_every_set_matches_sse2<3>(); }

}  // namespace
}  // namespace pdmpm::pd::kernels
