// The eight-lane plane-stress law is Constitutive<2>::update, bit for bit, in every
// lane it does not flag, and it flags exactly the lanes whose trial stress yields
// (J2) — linear elasticity never — which the caller hands to the law itself.
#include "solver/mpm/plane_stress_lanes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "solver/mpm/constitutive.hpp"
#include "solver/mpm/kinematics.hpp"

namespace pdmpm::mpm {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

struct Point {
  PolarLog<2> polar;
  PointHistory history;
  double offset = 0.0;  // non-local hardening offset ε̂_p − ε̄_p
};

struct Tally {
  int differing = 0, flagged = 0, yielding_unflagged = 0, flagged_elastic = 0;
};

// The central-crack plate's steel (the paper's material).
Material plate_steel(MaterialModel model) {
  Material m;
  m.model = model;
  m.elastic = {215e9, 0.33, 7800.0};
  m.j2 = {340e6, 1.45e9};
  return m;
}

// Runs every instruction set's version over the points, eight at a time.
Tally compare(const Constitutive<2>& law, const std::vector<Point>& points) {
  Tally t;
  const PlaneStressLaw constants = *law.plane_stress_law();
  const bool elastic_only = law.material().model == MaterialModel::linear_elastic;
  for (const auto& variant : plane_stress_lanes_variants())
    for (std::size_t i0 = 0; i0 + kLawLanes <= points.size(); i0 += kLawLanes) {
      PlaneStressLanes lanes;
      for (int l = 0; l < kLawLanes; ++l) {
        const Point& q = points[i0 + l];
        lanes.l00[l] = q.polar.log_U(0, 0), lanes.l01[l] = q.polar.log_U(0, 1), lanes.l11[l] = q.polar.log_U(1, 1);
        lanes.c[l] = q.polar.R(0, 0), lanes.s[l] = q.polar.R(1, 0);
        set_plastic_lane(lanes, l, q.history.plastic_strain, elastic_only);
        lanes.alpha[l] = q.history.eq_plastic_strain + q.offset;
      }
      const unsigned flags = variant.function(constants, lanes);
      for (int l = 0; l < kLawLanes; ++l) {
        const Point& q = points[i0 + l];
        PointHistory h = q.history;
        const StressResult r = law.update(q.polar, h, q.offset);
        const bool yielded = h.eq_plastic_strain != q.history.eq_plastic_strain;
        if (flags >> l & 1u) {
          ++t.flagged;
          t.flagged_elastic += !yielded && std::isfinite(r.J);
          continue;
        }
        t.yielding_unflagged += yielded;
        bool same = same_bits(r.kirchhoff(0, 0), lanes.k00[l]) && same_bits(r.kirchhoff(0, 1), lanes.k01[l]) &&
            same_bits(r.kirchhoff(1, 0), lanes.k10[l]) && same_bits(r.kirchhoff(1, 1), lanes.k11[l]) &&
            same_bits(r.J, lanes.J[l]) && same_bits(r.out_of_plane_strain, lanes.out_of_plane[l]) &&
            same_bits(r.energy, lanes.energy[l]) && r.dissipation == 0.0;
        for (int i = 0; i < 3; ++i) same = same && r.kirchhoff(i, 2) == 0.0 && r.kirchhoff(2, i) == 0.0;
        t.differing += !same;
      }
    }
  return t;
}

// F = R(θ) (I + ε G), G's entries uniform in [−1, 1]; a plastic strain of up to
// `plastic` (traceless, with its ε₃₃) and ε̄_p up to 2·plastic, offsets of either sign.
std::vector<Point> points(double strain, double plastic, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), angle(-3.14, 3.14);
  std::vector<Point> out(n);
  for (auto& q : out) {
    Mat<2> G;
    G << u(rng), u(rng), u(rng), u(rng);
    const double th = angle(rng);
    Mat<2> R;
    R << std::cos(th), -std::sin(th), std::sin(th), std::cos(th);
    q.polar = polar_log<2>(R * (Mat<2>::Identity() + strain * G));
    Mat<3>& ep = q.history.plastic_strain;
    ep(0, 0) = plastic * u(rng), ep(1, 1) = plastic * u(rng), ep(0, 1) = ep(1, 0) = plastic * u(rng);
    ep(2, 2) = -(ep(0, 0) + ep(1, 1));
    q.history.eq_plastic_strain = plastic * (1.0 + u(rng));
    q.offset = 0.1 * plastic * u(rng);
  }
  return out;
}

TEST(PlaneStressLanes, EqualTheJ2LawBitForBitOnItsElasticPathAndFlagEveryYield) {
  const Constitutive<2> law(plate_steel(MaterialModel::j2), core::Setting::plane_stress);
  // Strains and plastic strains around the yield strain σ_y/E = 1.6e-3: both paths in
  // the groups; far below it, none yields.
  for (const double strain : {1e-6, 1e-3, 3e-3})
    for (const double plastic : {0.0, 1e-3}) {
      const Tally t = compare(law, points(strain, plastic, 4000, 7));
      EXPECT_EQ(t.differing, 0) << "strain " << strain << ", plastic " << plastic;
      EXPECT_EQ(t.yielding_unflagged, 0) << "strain " << strain << ", plastic " << plastic;
      EXPECT_EQ(t.flagged_elastic, 0) << "strain " << strain << ", plastic " << plastic;
      if (strain == 1e-6 && plastic == 0.0) {
        EXPECT_EQ(t.flagged, 0);
      } else if (strain >= 1e-3) {
        EXPECT_GT(t.flagged, 0) << "strain " << strain << ", plastic " << plastic;
      }
    }
}

TEST(PlaneStressLanes, EqualLinearElasticityBitForBitAndNeverFlagIt) {
  const Constitutive<2> law(plate_steel(MaterialModel::linear_elastic), core::Setting::plane_stress);
  std::vector<Point> pts = points(1e-2, 1e-3, 4000, 8);  // histories it must ignore
  pts[5].polar.log_U.setZero();                          // a zero strain: signed zeros through ε₃₃ and J
  pts[6].polar.log_U << -0.0, -0.0, -0.0, -0.0;
  const Tally t = compare(law, pts);
  EXPECT_EQ(t.differing, 0);
  EXPECT_EQ(t.flagged, 0);
}

TEST(PlaneStressLanes, FlagANonFiniteStrainForTheLaw) {
  const Constitutive<2> law(plate_steel(MaterialModel::j2), core::Setting::plane_stress);
  std::vector<Point> pts = points(1e-4, 0.0, 8, 9);
  pts[2].polar.log_U(0, 0) = std::nan("");
  PlaneStressLanes lanes{};
  for (int l = 0; l < kLawLanes; ++l) {
    lanes.l00[l] = pts[l].polar.log_U(0, 0), lanes.l01[l] = pts[l].polar.log_U(0, 1);
    lanes.l11[l] = pts[l].polar.log_U(1, 1), lanes.c[l] = pts[l].polar.R(0, 0), lanes.s[l] = pts[l].polar.R(1, 0);
  }
  for (const auto& variant : plane_stress_lanes_variants())
    EXPECT_EQ(variant.function(*law.plane_stress_law(), lanes), 1u << 2) << variant.name;
}

TEST(PlaneStressLanes, OnlyPlaneStressJ2AndLinearElasticityHaveThem) {
  EXPECT_TRUE(Constitutive<2>(plate_steel(MaterialModel::j2), core::Setting::plane_stress).plane_stress_law());
  EXPECT_FALSE(Constitutive<2>(plate_steel(MaterialModel::j2), core::Setting::plane_strain).plane_stress_law());
  EXPECT_FALSE(
      Constitutive<2>(plate_steel(MaterialModel::neo_hookean), core::Setting::plane_stress).plane_stress_law());
  EXPECT_FALSE(Constitutive<3>(plate_steel(MaterialModel::j2), core::Setting::solid3d).plane_stress_law());
}

}  // namespace
}  // namespace pdmpm::mpm
