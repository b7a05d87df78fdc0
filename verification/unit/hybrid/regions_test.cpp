#include "solver/hybrid/regions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>

#include "solver/bc/symmetry.hpp"
#include "solver/core/error.hpp"
#include "solver/core/particle_builder.hpp"

namespace pdmpm::hybrid {
namespace {

using core::ParticleKind;

// Horizon of the paper's discretisation. No lattice distance² (an integer, in
// Δx²) lies within 0.1 of (r·3.015)² for any radius r used here, so the brute
// force below compares physical distances with no slack and still agrees with
// the lattice stencils' exact integer test.
constexpr double kRatio = 3.015;

// A body on a lattice that is not the unit one (spacing 0.5 mm, shifted
// origin), so that conversions between metres and lattice units are exercised.
template <int D>
struct Body {
  core::Particles<D> p;
  double delta;
  RegionMap<D> map;
  std::vector<ParticleKind> kind;
  std::vector<std::uint8_t> removed;

  Body(const IVec<D>& n, const RegionRadii& radii)
      : p(fill(n)),
        delta(kRatio * p.lattice.spacing),
        map(p, kRatio, kRatio, radii),
        kind(p.size(), ParticleKind::mpm),
        removed(p.n_real, 0) {}

  static core::Particles<D> fill(const IVec<D>& n) {
    core::Lattice<D> lat;
    lat.spacing = 5e-4;
    lat.origin = Vec<D>::Constant(0.01);
    core::Geometry<D> g;
    g.add(std::make_unique<core::Box<D>>(lat.position(IVec<D>::Zero()), lat.position(n - IVec<D>::Ones())));
    return core::fill_lattice<D>(g, lat, std::pow(lat.spacing, D));
  }
  Index at(const IVec<D>& s) const { return map.find(s); }
  Vec<D> point(const Vec<D>& lattice_coords) const { return p.lattice.origin + p.lattice.spacing * lattice_coords; }
  // Brute force: every real particle j ≠ i within r (metres) of x.
  std::vector<Index> within(const Vec<D>& x, double r, Index except = -1) const {
    std::vector<Index> out;
    for (Index j = 0; j < p.n_real; ++j)
      if (j != except && (p.x0[j] - x).norm() <= r) out.push_back(j);
    return out;
  }
  std::vector<Index> of_kind(ParticleKind k) const {
    std::vector<Index> out;
    for (Index i = 0; i < p.n_real; ++i)
      if (!removed[i] && kind[i] == k) out.push_back(i);
    return out;
  }
  // Brute force over all pairs: non-removed, non-PD particles within δ of a PD particle.
  std::vector<Index> expected_transition() const {
    const auto pd = of_kind(ParticleKind::pd);
    std::vector<Index> out;
    for (Index j = 0; j < p.n_real; ++j) {
      if (removed[j] || kind[j] == ParticleKind::pd) continue;
      if (std::any_of(pd.begin(), pd.end(), [&](Index i) { return (p.x0[i] - p.x0[j]).norm() <= delta; }))
        out.push_back(j);
    }
    return out;
  }
  void expect_invariants() const {
    EXPECT_EQ(of_kind(ParticleKind::transition), expected_transition());
    for (Index i = 0; i < p.n_real; ++i)
      if (removed[i]) {
        EXPECT_EQ(kind[i], ParticleKind::removed) << "removed particle " << i;
      }
  }
};

std::vector<Index> minus(const std::vector<Index>& a, const std::vector<Index>& b) {
  std::vector<Index> out;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

template <int D>
void onset_makes_the_brute_force_ball(const IVec<D>& n, const IVec<D>& failed_site, const RegionRadii& radii) {
  Body<D> b(n, radii);
  const Index f = b.at(failed_site);
  const auto made = onset<D>(b.map, std::vector<Index>{f}, b.kind, b.removed);
  const auto ball = b.within(b.p.x0[f], radii.pd_radius * b.delta, f);
  EXPECT_EQ(made, ball);
  EXPECT_EQ(b.of_kind(ParticleKind::pd), ball);
  EXPECT_TRUE(b.removed[f]);
  EXPECT_EQ(b.kind[f], ParticleKind::removed);
  EXPECT_FALSE(b.expected_transition().empty());
  b.expect_invariants();
}

TEST(HybridRegions, OnsetMakesExactlyTheParticlesWithinRpdPd2D) {
  onset_makes_the_brute_force_ball<2>(IVec<2>(60, 40), IVec<2>(30, 20), RegionRadii{});
}

// A 3D block smaller than the paper's 7δ region, so the radii shrink with it.
TEST(HybridRegions, OnsetMakesExactlyTheParticlesWithinRpdPd3D) {
  onset_makes_the_brute_force_ball<3>(IVec<3>(20, 18, 16), IVec<3>(9, 8, 7), RegionRadii{2.0, 1.0, 2.0, 2.0});
}

TEST(HybridRegions, OnsetOfARemovedParticleThrows) {
  Body<2> b(IVec<2>(20, 20), RegionRadii{});
  const std::vector<Index> f{b.at(IVec<2>(10, 10))};
  onset<2>(b.map, f, b.kind, b.removed);
  EXPECT_THROW(onset<2>(b.map, f, b.kind, b.removed), RunError);
}

TEST(HybridRegions, ExpansionNearTheEdgeConvertsTheBruteForceBallAndDeepTriggersNothing) {
  Body<2> b(IVec<2>(60, 40), RegionRadii{});
  const Index failed = b.at(IVec<2>(30, 20));
  onset<2>(b.map, std::vector<Index>{failed}, b.kind, b.removed);

  // 1Δx from the failed particle: 20Δx from the nearest transition particle > l_crit = 9.045Δx.
  const Index deep = b.at(IVec<2>(31, 20));
  const auto transition = b.of_kind(ParticleKind::transition);
  for (Index t : transition) ASSERT_GT((b.p.x0[t] - b.p.x0[deep]).norm(), 3.0 * b.delta);
  const auto before = b.kind;
  EXPECT_TRUE(expand<2>(b.map, std::vector<Index>{deep}, b.kind, b.removed).empty());
  EXPECT_EQ(b.kind, before);

  // An MPM particle with a broken bond is no trigger (eq 11 concerns PD particles).
  EXPECT_TRUE(expand<2>(b.map, std::vector<Index>{b.at(IVec<2>(58, 20))}, b.kind, b.removed).empty());

  // 20Δx from the failed particle, 2Δx from the transition particle at (52, 20).
  const Index edge = b.at(IVec<2>(50, 20));
  ASSERT_EQ(b.kind[edge], ParticleKind::pd);
  const auto pd_before = b.of_kind(ParticleKind::pd);
  const auto made = expand<2>(b.map, std::vector<Index>{edge}, b.kind, b.removed);
  // The failed particle is 20Δx < l_ext away: removed, it must stay so.
  const auto expected = minus(minus(b.within(b.p.x0[edge], 7.0 * b.delta, edge), pd_before), {failed});
  EXPECT_FALSE(expected.empty());
  EXPECT_EQ(made, expected);
  std::vector<Index> pd_after;
  std::set_union(pd_before.begin(), pd_before.end(), made.begin(), made.end(), std::back_inserter(pd_after));
  EXPECT_EQ(b.of_kind(ParticleKind::pd), pd_after);
  EXPECT_TRUE(b.removed[failed]);
  b.expect_invariants();
}

// l_con = 3δ so that a region of radius 7δ is wider than what one tip keeps.
TEST(HybridRegions, ShrinkKeepsThePdParticlesNearEveryTipAndTheKeptOnes) {
  const RegionRadii radii{7.0, 3.0, 7.0, 3.0};
  const double l_con = 3.0;
  for (const int n_tips : {1, 2}) {
    Body<2> b(IVec<2>(60, 40), radii);
    onset<2>(b.map, std::vector<Index>{b.at(IVec<2>(30, 20))}, b.kind, b.removed);
    const auto pd_before = b.of_kind(ParticleKind::pd);
    // Tips off the lattice, as a crack tip is.
    std::vector<Vec<2>> tips{b.point(Vec<2>(36.3, 20.4))};
    if (n_tips == 2) tips.push_back(b.point(Vec<2>(22.7, 17.1)));
    // "Damaged" particles: a row through the region, far from both tips on its left end.
    std::vector<std::uint8_t> keep(b.p.n_real, 0);
    std::vector<Index> kept;
    for (Index i : pd_before)
      if (b.p.site[i][1] == 30) {
        keep[i] = 1;
        kept.push_back(i);
      }
    std::vector<Index> near;
    for (const auto& tip : tips) {
      const auto w = b.within(tip, l_con * b.delta);
      std::vector<Index> u;
      std::set_union(near.begin(), near.end(), w.begin(), w.end(), std::back_inserter(u));
      near = u;
    }
    std::vector<Index> stay;
    std::set_intersection(pd_before.begin(), pd_before.end(), near.begin(), near.end(), std::back_inserter(stay));
    std::vector<Index> expected_pd;
    std::set_union(stay.begin(), stay.end(), kept.begin(), kept.end(), std::back_inserter(expected_pd));

    const auto reverted = shrink<2>(b.map, tips, keep, b.kind, b.removed);
    EXPECT_EQ(b.of_kind(ParticleKind::pd), expected_pd) << n_tips << " tip(s)";
    EXPECT_EQ(reverted, minus(pd_before, expected_pd));
    for (Index i : kept) EXPECT_EQ(b.kind[i], ParticleKind::pd);
    b.expect_invariants();
  }
}

template <int D>
void random_sequence_keeps_the_invariants(const IVec<D>& n, const RegionRadii& radii, int operations) {
  Body<D> b(n, radii);
  std::mt19937 rng(20240611);  // fixed: the sequence is part of the test
  std::uniform_int_distribution<Index> any(0, b.p.n_real - 1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::uint8_t> removed_before = b.removed;
  std::array<int, 3> effective{};  // operations of each kind that changed a region
  for (int op = 0; op < operations; ++op) {
    const auto kind_before = b.kind;
    const int what = static_cast<int>(rng() % 3);
    std::vector<Index> changed;
    if (what == 0) {
      // A failing particle is an MPM (or transition) particle that is not removed.
      std::vector<Index> pool = b.of_kind(ParticleKind::mpm);
      const auto tr = b.of_kind(ParticleKind::transition);
      pool.insert(pool.end(), tr.begin(), tr.end());
      if (pool.empty()) continue;
      changed = onset<D>(b.map, std::vector<Index>{pool[rng() % pool.size()]}, b.kind, b.removed);
    } else if (what == 1) {
      // Any particle may be passed: non-PD and removed ones must be ignored.
      std::vector<Index> triggers;
      for (int k = 0; k < 5; ++k) triggers.push_back(any(rng));
      changed = expand<D>(b.map, triggers, b.kind, b.removed);
    } else {
      std::vector<Vec<D>> tips;
      const int n_tips = static_cast<int>(rng() % 3);  // 0 tips reverts all but the kept
      for (int k = 0; k < n_tips; ++k) tips.push_back(b.p.x0[any(rng)] + Vec<D>::Constant(0.3 * b.p.lattice.spacing));
      std::vector<std::uint8_t> keep(b.p.n_real, 0);
      for (auto& k : keep) k = unit(rng) < 0.1;
      changed = shrink<D>(b.map, tips, keep, b.kind, b.removed);
      for (Index i = 0; i < b.p.n_real; ++i)
        if (keep[i] && kind_before[i] == ParticleKind::pd) {
          EXPECT_EQ(b.kind[i], ParticleKind::pd);
        }
    }
    SCOPED_TRACE("operation " + std::to_string(op) + " (kind " + std::to_string(what) + ")");
    // The returned list is exactly who crossed the PD boundary, ascending.
    std::vector<Index> crossed;
    for (Index i = 0; i < b.p.n_real; ++i)
      if ((kind_before[i] == ParticleKind::pd) != (b.kind[i] == ParticleKind::pd) && !b.removed[i])
        crossed.push_back(i);
    EXPECT_EQ(changed, crossed);
    effective[what] += !changed.empty();
    for (Index i = 0; i < b.p.n_real; ++i)
      if (removed_before[i]) {
        EXPECT_TRUE(b.removed[i]) << "particle " << i << " came back";
      }
    removed_before = b.removed;
    b.expect_invariants();
  }
  // The sequence is only a test if every rule acted in it.
  for (int what = 0; what < 3; ++what) EXPECT_GT(effective[what], 0) << "operation kind " << what;
}

TEST(HybridRegions, RandomSequenceKeepsTheInvariants2D) {
  random_sequence_keeps_the_invariants<2>(IVec<2>(60, 40), RegionRadii{3.0, 1.0, 3.0, 2.0}, 50);
}

TEST(HybridRegions, RandomSequenceKeepsTheInvariants3D) {
  random_sequence_keeps_the_invariants<3>(IVec<3>(14, 12, 10), RegionRadii{1.5, 0.5, 1.5, 1.0}, 30);
}

// Transition as the bond kernels see it with symmetry ghosts: within δ of a PD
// particle or of its mirror image (brute force on reflected positions); every
// ghost carries its owner's kind.
TEST(HybridRegions, ClassifySeesPdParticlesThroughSymmetryGhosts) {
  auto p = Body<2>::fill(IVec<2>(20, 10));
  const double dx = p.lattice.spacing, delta = kRatio * dx;
  const double plane = p.lattice.origin[0] - 0.5 * dx;
  bc::add_symmetry_ghosts<2>(p, {bc::SymmetryPlane{"symmetry[0]", 0, plane}}, delta, "scene.toml");
  ASSERT_GT(p.n_ghost(), 0);
  const RegionMap<2> map(p, kRatio, kRatio, RegionRadii{});
  std::vector<ParticleKind> kind(p.size(), ParticleKind::mpm);
  std::vector<std::uint8_t> removed(p.n_real, 0);
  std::vector<Index> pd;
  for (Index i = 0; i < p.n_real; ++i)
    if (p.site[i][0] == 0 && p.site[i][1] >= 3 && p.site[i][1] <= 6) {
      kind[i] = ParticleKind::pd;
      pd.push_back(i);
    }
  classify<2>(map, kind, removed);
  for (Index j = 0; j < p.n_real; ++j) {
    if (kind[j] == ParticleKind::pd) continue;
    bool direct = false, mirrored = false;
    for (Index i : pd) {
      Vec<2> image = p.x0[i];
      image[0] = 2.0 * plane - image[0];
      direct = direct || (p.x0[i] - p.x0[j]).norm() <= delta;
      mirrored = mirrored || (image - p.x0[j]).norm() <= delta;
    }
    EXPECT_EQ(kind[j], direct || mirrored ? ParticleKind::transition : ParticleKind::mpm) << "particle " << j;
  }
  for (Index g = p.n_real; g < p.size(); ++g) EXPECT_EQ(kind[g], kind[p.ghost_owner[g - p.n_real]]);
}

TEST(HybridRegions, BadRadiiNameTheirKey) {
  const auto expect_key = [](const RegionRadii& r, const std::string& key) {
    try {
      r.validate("scene.toml");
      ADD_FAILURE() << "no error for " << key;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), key);
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  expect_key(RegionRadii{0.0, 3.0, 7.0, 7.0}, "hybrid.pd_radius");
  expect_key(RegionRadii{7.0, -1.0, 7.0, 7.0}, "hybrid.expand_trigger");
  expect_key(RegionRadii{7.0, 3.0, std::nan(""), 7.0}, "hybrid.expand_radius");
  expect_key(RegionRadii{7.0, 3.0, 7.0, 0.0}, "hybrid.keep_radius");
  expect_key(RegionRadii{7.0, 7.0, 7.0, 7.0}, "hybrid.expand_trigger");
  expect_key(RegionRadii{7.0, 8.0, 7.0, 7.0}, "hybrid.expand_trigger");
  EXPECT_THROW(Body<2>(IVec<2>(10, 10), RegionRadii{7.0, 7.0, 7.0, 7.0}), InputError);
}

}  // namespace
}  // namespace pdmpm::hybrid
