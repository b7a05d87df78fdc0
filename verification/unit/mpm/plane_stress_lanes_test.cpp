// The eight-lane plane-stress law is Constitutive<2>::update, bit for bit, in every
// lane it does not flag — the stress, J, ε₃₃, the energy and, where the point yields,
// the dissipation and the plastic history the caller adds — and it flags only lanes
// the law must take itself (a non-finite strain; a Newton step that leaves the bracket
// before its upper end is known, which the scalar code then searches for).
#include "solver/mpm/plane_stress_lanes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "solver/mpm/constitutive.hpp"
#include "solver/mpm/kinematics.hpp"
#include "verification/support/same_bits.hpp"

namespace pdmpm::mpm {
namespace {

using test::same_bits;

struct Point {
  PolarLog<2> polar;
  PointHistory history;
  double offset = 0.0;  // non-local hardening offset ε̂_p − ε̄_p
};

struct LawTally {
  int differing = 0, flagged = 0, yielded = 0, yield_mismatch = 0;
};

bool same_history(const PointHistory& a, const PointHistory& b) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!same_bits(a.plastic_strain(i, j), b.plastic_strain(i, j))) return false;
  return same_bits(a.eq_plastic_strain, b.eq_plastic_strain);
}

// The central-crack plate's steel (the paper's material).
Material plate_steel(MaterialModel model) {
  Material m;
  m.model = model;
  m.elastic = {215e9, 0.33, 7800.0};
  m.j2 = {340e6, 1.45e9};
  return m;
}

// Runs every instruction set's version over the points, eight at a time.
LawTally compare(const Constitutive<2>& law, const std::vector<Point>& points) {
  LawTally t;
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
        if (flags >> l & 1u) {
          ++t.flagged;
          continue;
        }
        const bool yielded = h.eq_plastic_strain != q.history.eq_plastic_strain;
        const bool lane_yielded = lanes.yielded >> l & 1u;
        t.yielded += lane_yielded;
        t.yield_mismatch += yielded != lane_yielded;
        // The caller's update of the history (simulation.cpp, add_plastic_increment).
        PointHistory lane_h = q.history;
        double dissipation = 0.0;
        if (lane_yielded) {
          Mat<3> d = Mat<3>::Zero();
          d(0, 0) = lanes.d00[l], d(1, 1) = lanes.d11[l], d(2, 2) = lanes.d22[l];
          d(0, 1) = d(1, 0) = lanes.d01[l];
          lane_h.plastic_strain += d;
          lane_h.eq_plastic_strain += lanes.d_alpha[l];
          dissipation = lanes.dissipation[l];
        }
        bool same = same_bits(r.kirchhoff(0, 0), lanes.k00[l]) && same_bits(r.kirchhoff(0, 1), lanes.k01[l]) &&
            same_bits(r.kirchhoff(1, 0), lanes.k10[l]) && same_bits(r.kirchhoff(1, 1), lanes.k11[l]) &&
            same_bits(r.J, lanes.J[l]) && same_bits(r.out_of_plane_strain, lanes.out_of_plane[l]) &&
            same_bits(r.energy, lanes.energy[l]) && same_bits(r.dissipation, dissipation) && same_history(h, lane_h);
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

TEST(PlaneStressLanes, EqualTheJ2LawBitForBitOnBothPaths) {
  const Constitutive<2> law(plate_steel(MaterialModel::j2), core::Setting::plane_stress);
  // Strains and plastic strains around the yield strain σ_y/E = 1.6e-3: both paths in
  // the groups; far below it, none yields. Up to 30 % strain: returns of many yield
  // strains, where Newton takes most iterations.
  for (const double strain : {1e-6, 1e-3, 3e-3, 0.3})
    for (const double plastic : {0.0, 1e-3}) {
      const LawTally t = compare(law, points(strain, plastic, 4000, 7));
      EXPECT_EQ(t.differing, 0) << "strain " << strain << ", plastic " << plastic;
      EXPECT_EQ(t.yield_mismatch, 0) << "strain " << strain << ", plastic " << plastic;
      // Random strains start Newton where f is convex (Simo & Hughes 1998 §3.4.2): no
      // step leaves the bracket, so no lane goes to the scalar law.
      EXPECT_EQ(t.flagged, 0) << "strain " << strain << ", plastic " << plastic;
      if (strain == 1e-6 && plastic == 0.0) {
        EXPECT_EQ(t.yielded, 0);
      } else if (strain >= 1e-3) {
        EXPECT_GT(t.yielded, 0) << "strain " << strain << ", plastic " << plastic;
      }
    }
}

TEST(PlaneStressLanes, EqualLinearElasticityBitForBitAndNeverFlagIt) {
  const Constitutive<2> law(plate_steel(MaterialModel::linear_elastic), core::Setting::plane_stress);
  std::vector<Point> pts = points(1e-2, 1e-3, 4000, 8);  // histories it must ignore
  pts[5].polar.log_U.setZero();                          // a zero strain: signed zeros through ε₃₃ and J
  pts[6].polar.log_U << -0.0, -0.0, -0.0, -0.0;
  const LawTally t = compare(law, pts);
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
