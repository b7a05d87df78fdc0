#include "solver/hybrid/crack_tips.hpp"
#include "solver/core/error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

namespace pdmpm::hybrid {
namespace {

// Synthetic PD damage: φ_i is the share of the bonds of i (all lattice
// neighbours within δ = 3.015 Δx present in the body, equal volumes) cut by a
// crack, the shape a PD crack leaves (≈ 0.39 on the faces, fading over ~δ
// beyond the end). Cracks are given in lattice units; ends off the lattice
// sites so that no bond merely touches a crack.
constexpr double kHorizon = 3.015;

template <int D>
struct Field {
  core::Lattice<D> lattice;
  std::vector<IVec<D>> sites;
  std::vector<double> phi;
};

template <int D>
core::Lattice<D> test_lattice() {
  core::Lattice<D> l;  // spacing and origin away from 1 and 0 so that units are exercised
  l.spacing = 2.5e-3;
  l.origin = Vec<D>::Constant(-0.1);
  return l;
}

// Damage of the box [0, n)^D with the bonds crossing any crack removed.
template <int D, class Cut>
Field<D> damage_of(const IVec<D>& n, Cut&& cut) {
  Field<D> f;
  f.lattice = test_lattice<D>();
  const int r = static_cast<int>(kHorizon);
  IVec<D> s = IVec<D>::Zero();
  while (true) {
    int bonds = 0, broken = 0;
    IVec<D> o = IVec<D>::Constant(-r);
    while (true) {
      const IVec<D> q = s + o;
      const bool inside = (q.array() >= 0).all() && (q.array() < n.array()).all();
      if (inside && !o.isZero() && o.template cast<double>().norm() <= kHorizon) {
        ++bonds;
        if (cut(s.template cast<double>(), q.template cast<double>())) ++broken;
      }
      int a = 0;
      for (; a < D && ++o[a] > r; ++a) o[a] = -r;
      if (a == D) break;
    }
    f.sites.push_back(s);
    f.phi.push_back(static_cast<double>(broken) / bonds);
    int a = 0;
    for (; a < D && ++s[a] >= n[a]; ++a) s[a] = 0;
    if (a == D) break;
  }
  return f;
}

using Segment = std::pair<Vec<2>, Vec<2>>;

double cross(const Vec<2>& u, const Vec<2>& v) { return u.x() * v.y() - u.y() * v.x(); }

bool crosses(const Vec<2>& p, const Vec<2>& q, const Segment& c) {
  const auto& [a, b] = c;
  return cross(b - a, p - a) * cross(b - a, q - a) < 0.0 && cross(q - p, a - p) * cross(q - p, b - p) < 0.0;
}

Field<2> damage_2d(const std::vector<Segment>& cracks, int n = 80) {
  return damage_of<2>(IVec<2>(n, n), [&](const Vec<2>& p, const Vec<2>& q) {
    for (const auto& c : cracks)
      if (crosses(p, q, c)) return true;
    return false;
  });
}

Segment segment(const Vec<2>& centre, double length, double angle_deg) {
  const double t = angle_deg * std::numbers::pi / 180.0;
  const Vec<2> half = 0.5 * length * Vec<2>(std::cos(t), std::sin(t));
  return {centre - half, centre + half};
}

// Largest distance (Δx) from an expected end to its nearest tip; fails if the
// number of tips differs from the number of ends or a tip is near no end.
template <int D>
double tip_error(const Field<D>& f, const std::vector<CrackTip<D>>& tips, const std::vector<Vec<D>>& ends) {
  EXPECT_EQ(tips.size(), ends.size());
  auto dist = [&](const CrackTip<D>& t, const Vec<D>& e) {
    return (t.position - f.lattice.origin) / f.lattice.spacing - e;
  };
  double worst = 0.0;
  for (const auto& e : ends) {
    double best = 1e9;
    for (const auto& t : tips) best = std::min(best, dist(t, e).norm());
    worst = std::max(worst, best);
  }
  for (const auto& t : tips) {
    double best = 1e9;
    for (const auto& e : ends) best = std::min(best, dist(t, e).norm());
    EXPECT_LE(best, 1.0) << "tip at site " << t.site.transpose() << " near no crack end";
  }
  ::testing::Test::RecordProperty("max_tip_error_dx", std::to_string(worst));
  return worst;
}

std::vector<Vec<2>> ends_of(const std::vector<Segment>& cracks) {
  std::vector<Vec<2>> e;
  for (const auto& [a, b] : cracks) e.insert(e.end(), {a, b});
  return e;
}

// A tip is a lattice site, so it can be up to √2/2 Δx from the true end; and
// a PD crack's damage fades over δ around its end, so the minimum of ∇²φ sits
// within about one spacing of it: Δx is the tolerance the tracker promises.
constexpr double kTipTolerance = 1.0;

TEST(CrackTips, HorizontalCrackInsideTheBodyHasTwoTips) {
  const std::vector<Segment> cracks{{Vec<2>(20.3, 40.5), Vec<2>(59.6, 40.5)}};
  const auto f = damage_2d(cracks);
  const auto tips = find_crack_tips(f.lattice, f.sites, f.phi, CrackTipSettings{});
  EXPECT_LE(tip_error(f, tips, ends_of(cracks)), kTipTolerance);
  for (const auto& t : tips) EXPECT_EQ(t.id, -1);
}

TEST(CrackTips, InclinedCrackHasTwoTips) {
  const std::vector<Segment> cracks{segment(Vec<2>(40.2, 39.7), 40.0, 30.0)};
  const auto f = damage_2d(cracks);
  const auto tips = find_crack_tips(f.lattice, f.sites, f.phi, CrackTipSettings{});
  EXPECT_LE(tip_error(f, tips, ends_of(cracks)), kTipTolerance);
}

TEST(CrackTips, EdgeCrackHasOneTip) {
  // Starts outside the body: its mouth on the edge is not an end.
  const auto f = damage_2d({{Vec<2>(-5.0, 40.5), Vec<2>(35.4, 40.5)}});
  const auto tips = find_crack_tips(f.lattice, f.sites, f.phi, CrackTipSettings{});
  EXPECT_LE(tip_error(f, tips, {Vec<2>(35.4, 40.5)}), kTipTolerance);
}

TEST(CrackTips, TwoSeparateCracks) {
  const std::vector<Segment> cracks{segment(Vec<2>(25.3, 25.6), 24.0, 0.0), segment(Vec<2>(50.7, 55.2), 26.0, 60.0)};
  const auto f = damage_2d(cracks);
  const auto tips = find_crack_tips(f.lattice, f.sites, f.phi, CrackTipSettings{});
  EXPECT_LE(tip_error(f, tips, ends_of(cracks)), kTipTolerance);
}

TEST(CrackTips, FourSeparateCracks) {
  const std::vector<Segment> cracks{segment(Vec<2>(20.3, 20.6), 20.0, 0.0), segment(Vec<2>(58.7, 21.2), 20.0, 90.0),
                                    segment(Vec<2>(21.4, 58.1), 22.0, 45.0), segment(Vec<2>(57.9, 59.3), 18.0, -20.0)};
  const auto f = damage_2d(cracks);
  const auto tips = find_crack_tips(f.lattice, f.sites, f.phi, CrackTipSettings{});
  EXPECT_LE(tip_error(f, tips, ends_of(cracks)), kTipTolerance);
}

TEST(CrackTips, BranchingCrackHasTipsAtItsEndsOnly) {
  const Vec<2> start(10.3, 40.5), fork(40.3, 40.5);
  const Vec<2> up = fork + segment(Vec<2>::Zero(), 40.0, 30.0).second;
  const Vec<2> down = fork + segment(Vec<2>::Zero(), 40.0, -30.0).second;
  const auto f = damage_2d({{start, fork}, {fork, up}, {fork, down}});
  const auto tips = find_crack_tips(f.lattice, f.sites, f.phi, CrackTipSettings{});
  EXPECT_LE(tip_error(f, tips, {start, up, down}), kTipTolerance);
}

// The damage band a running crack leaves is wider than a clean cut's, and its flanks
// vary from particle to particle along it (a bond more or less broken). A flank site
// then sees the band on one side along the crack and passed the one-sidedness test.
// The field: a 26 × 14 patch of the central-crack plate's PD region (Δx = 0.5 mm,
// mode expand_shrink, t = 0.13 ms, broken bonds of 28 per particle, top row first),
// behind both tips — 3 false tips here without the ridge test, 18 along the whole crack.
TEST(CrackTips, RaggedFlanksOfARunningCrackAddNoTips) {
  const char* broken[] = {"00000000000000000000000000", "00000000000000000000000000", "00000000000000000000000000",
                          "00000000000000000000000000", "11111111111111111010001000", "54544645644443533223212312",
                          "99999a89a88888a88878877877", "ihgjjjjgjjiggggigcgfccgdcd", "ceegfccefgcfgeeifcggccgdcd",
                          "77888877888788988878877877", "11233211332233233223212312", "00010000010010010011001000",
                          "00000000000000000000000000", "00000000000000000000000000"};
  Field<2> f;
  f.lattice = test_lattice<2>();
  const int rows = 14;
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < 26; ++x) {
      const char c = broken[rows - 1 - y][x];
      f.sites.emplace_back(x, y);
      f.phi.push_back((c <= '9' ? c - '0' : c - 'a' + 10) / 28.0);
    }
  CrackTipSettings without_ridge;
  without_ridge.ridge_fraction = 0.0;
  EXPECT_EQ(find_crack_tips(f.lattice, f.sites, f.phi, without_ridge).size(), 3u) << "the field must be a hard case";
  EXPECT_TRUE(find_crack_tips(f.lattice, f.sites, f.phi, CrackTipSettings{}).empty());
}

TEST(CrackTips, NoTipsWithoutDamageOrWithUniformDamage) {
  auto f = damage_2d({});
  EXPECT_TRUE(find_crack_tips(f.lattice, f.sites, f.phi, CrackTipSettings{}).empty());
  for (auto& p : f.phi) p = 0.6;
  EXPECT_TRUE(find_crack_tips(f.lattice, f.sites, f.phi, CrackTipSettings{}).empty());
}

TEST(CrackTips, RejectsBadInput) {
  const auto f = damage_2d({}, 8);
  CrackTipSettings s;
  s.laplacian_threshold = 0.1;
  EXPECT_THROW(find_crack_tips(f.lattice, f.sites, f.phi, s), InputError);
  auto phi = f.phi;
  phi.pop_back();
  EXPECT_THROW(find_crack_tips(f.lattice, f.sites, phi, CrackTipSettings{}), RunError);
}

// Ids of the tips, in the returned order.
template <int D>
std::vector<int> ids(const std::vector<CrackTip<D>>& tips) {
  std::vector<int> v;
  for (const auto& t : tips) v.push_back(t.id);
  return v;
}

TEST(CrackTips, MatchingKeepsIdsOfMovingTipsAndNumbersBranches) {
  // A crack grows 1 Δx per step, then forks at ±30° and both branches grow.
  const Vec<2> start(10.3, 40.5);
  const CrackTipSettings s;
  int next_id = 0;
  std::vector<CrackTip<2>> tips;
  Vec<2> end = Vec<2>(30.4, 40.5);
  for (int step = 0; step < 6; ++step, end.x() += 1.0) {
    const auto f = damage_2d({{start, end}});
    tips = match_crack_tips(tips, find_crack_tips(f.lattice, f.sites, f.phi, s), s, next_id);
    ASSERT_EQ(ids(tips), (std::vector<int>{0, 1})) << "step " << step;
  }
  const Vec<2> fork = end;
  const int growing = tips[0].site.x() > tips[1].site.x() ? tips[0].id : tips[1].id;
  for (double length = 1.0; length <= 10.0; length += 1.0) {
    const Vec<2> up = fork + segment(Vec<2>::Zero(), 2.0 * length, 30.0).second;
    const Vec<2> down = fork + segment(Vec<2>::Zero(), 2.0 * length, -30.0).second;
    const auto f = damage_2d({{start, fork}, {fork, up}, {fork, down}});
    tips = match_crack_tips(tips, find_crack_tips(f.lattice, f.sites, f.phi, s), s, next_id);
    // The fork's tips separate: the two close ends read as one until they are merge_radius apart.
    const auto expected = tips.size() == 2 ? std::vector<int>{0, 1} : std::vector<int>{0, 1, 2};
    ASSERT_EQ(ids(tips), expected) << "branch length " << length;
  }
  EXPECT_EQ(next_id, 3);  // one new id, for one branch; the growing end's id went on with the other
  for (const auto& t : tips) EXPECT_TRUE((t.id != growing && t.id != 2) || t.site.x() > fork.x()) << t.id;
}

TEST(CrackTips, MatchingDropsVanishedTipsAndIsDeterministic) {
  const CrackTipSettings s;
  auto tip = [](int x, int y, int id = -1) { return CrackTip<2>{id, IVec<2>(x, y), Vec<2>(x, y), -1.0}; };
  const std::vector<CrackTip<2>> previous{tip(10, 10, 4), tip(30, 10, 7)};
  int next_id = 8;
  // The tip at (30, 10) has vanished, the one at (10, 10) moved by (1, 1).
  auto now = match_crack_tips(previous, {tip(11, 11)}, s, next_id);
  ASSERT_EQ(now.size(), 1u);
  EXPECT_EQ(now[0].id, 4);
  EXPECT_EQ(next_id, 8);
  // Two tips equally close to one previous tip: the first of `found` inherits
  // its id, the other one is new; the result is sorted by id.
  now = match_crack_tips(previous, {tip(11, 12), tip(11, 8), tip(50, 50)}, s, next_id);
  EXPECT_EQ(ids(now), (std::vector<int>{4, 8, 9}));
  EXPECT_EQ(now[0].site, IVec<2>(11, 12));
  EXPECT_EQ(now[1].site, IVec<2>(11, 8));
  EXPECT_EQ(now[2].site, IVec<2>(50, 50));
  // Nothing found: every id is dropped.
  EXPECT_TRUE(match_crack_tips(previous, {}, s, next_id).empty());
  EXPECT_EQ(next_id, 10);
}

// 3D: the tips of a planar crack are points along its front, about
// merge_radius apart. A through crack in a slab, open at the face x = 0: every
// tip lies within Δx of the straight front and the front is covered end to end.
TEST(CrackTips, ThroughCrackInASlabHasTipsAlongItsFront) {
  const double plane = 7.5, front = 11.4;
  const auto f = damage_of<3>(IVec<3>(24, 16, 10), [&](const Vec<3>& p, const Vec<3>& q) {
    if ((p.y() - plane) * (q.y() - plane) >= 0.0) return false;
    const double t = (plane - p.y()) / (q.y() - p.y());
    return p.x() + t * (q.x() - p.x()) < front;
  });
  const CrackTipSettings s;
  const auto tips = find_crack_tips(f.lattice, f.sites, f.phi, s);
  ASSERT_GE(tips.size(), 2u);
  double worst = 0.0;
  std::vector<double> along;
  for (const auto& t : tips) {
    const Vec<3> x = (t.position - f.lattice.origin) / f.lattice.spacing;
    worst = std::max(worst, std::hypot(x.x() - front, x.y() - plane));
    along.push_back(x.z());
  }
  std::sort(along.begin(), along.end());
  ::testing::Test::RecordProperty("max_tip_error_dx", std::to_string(worst));
  EXPECT_LE(worst, kTipTolerance);
  // Gaps along the front: no wider than two merge radii plus the site rounding on either side.
  EXPECT_LE(along.front(), s.merge_radius + 1.0);
  EXPECT_GE(along.back(), 9.0 - s.merge_radius - 1.0);
  for (std::size_t k = 1; k < along.size(); ++k) EXPECT_LE(along[k] - along[k - 1], 2.0 * s.merge_radius + 1.0);
}

}  // namespace
}  // namespace pdmpm::hybrid
