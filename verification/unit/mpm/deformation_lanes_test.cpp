// The eight-lane deformation update is cayley_increment<2>(L, Δt) F bit for bit, in
// every instruction set's version: random velocity gradients from rest to strain
// increments of 10 % per step, random F around a rotation, signed zeros. The velocity
// gradient gathered into the lanes is Σ v_I ⊗ ∇S_I summed node by node, bit for bit,
// for uGIMP and B-spline stencils and a last group of fewer than eight particles.
#include "solver/mpm/deformation_lanes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "solver/mpm/kinematics.hpp"
#include "solver/mpm/shape_function.hpp"
#include "verification/support/same_bits.hpp"

namespace pdmpm::mpm {
namespace {

using test::same_bits;

TEST(DeformationLanes, EqualTheScalarCayleyUpdateBitForBit) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double dt = 12e-9;
  int differing = 0, compared = 0;
  for (const double rate : {0.0, 1e3, 1e6, 1e7})  // |L| Δt up to 0.1
    for (int group = 0; group < 500; ++group) {
      DeformationLanes in;
      Mat<2> L[kDeformationLanes], F[kDeformationLanes];
      for (int l = 0; l < kDeformationLanes; ++l) {
        L[l] << rate * u(rng), rate * u(rng), rate * u(rng), rate * u(rng);
        const double th = 3.0 * u(rng);
        F[l] << std::cos(th) + 0.1 * u(rng), -std::sin(th), std::sin(th), std::cos(th) + 0.1 * u(rng);
        if (group == 0 && l == 0) L[l] << -0.0, -0.0, -0.0, -0.0;
        in.l00[l] = L[l](0, 0), in.l01[l] = L[l](0, 1), in.l10[l] = L[l](1, 0), in.l11[l] = L[l](1, 1);
        in.f00[l] = F[l](0, 0), in.f01[l] = F[l](0, 1), in.f10[l] = F[l](1, 0), in.f11[l] = F[l](1, 1);
      }
      for (const auto& variant : deformation_lanes_variants()) {
        DeformationLanes out = in;
        variant.function(out, dt);
        for (int l = 0; l < kDeformationLanes; ++l) {
          const Mat<2> expected = cayley_increment<2>(L[l], dt) * F[l];
          differing += !(same_bits(expected(0, 0), out.f00[l]) && same_bits(expected(0, 1), out.f01[l]) &&
                         same_bits(expected(1, 0), out.f10[l]) && same_bits(expected(1, 1), out.f11[l]));
          ++compared;
        }
      }
    }
  EXPECT_EQ(differing, 0) << "of " << compared;
}

TEST(DeformationLanes, VelocityGradientIsTheNodeByNodeSumBitForBit) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0), inside(2.0, 9.0);
  const int nodes = 12;
  std::vector<Vec<2>> vg;
  for (int i = 0; i < nodes * nodes; ++i) vg.emplace_back(u(rng), u(rng));
  vg[30] = Vec<2>(-0.0, 0.0);
  const IVec<2> stride(1, nodes);
  int differing = 0, compared = 0;
  for (const ShapeFunction shape : {ShapeFunction::gimp, ShapeFunction::bspline2})
    for (int group = 0; group < 200; ++group) {
      std::vector<Stencil<2>> st;
      for (int l = 0; l < kDeformationLanes; ++l)
        st.push_back(make_stencil<2>(shape, Vec<2>(inside(rng), inside(rng)), 1.0, Vec<2>::Constant(0.25)));
      const int n = group % 3 == 0 ? 1 + group % kDeformationLanes : kDeformationLanes;
      for (const auto& variant : velocity_gradient_lanes_variants()) {
        DeformationLanes out;
        variant.function(out, st.data(), n, vg.data(), nodes);
        for (int l = 0; l < kDeformationLanes; ++l) {
          Mat<2> L = Mat<2>::Zero();  // Simulation<2>::velocity_gradient's sum
          for_each_grid_node<2, 3>(st[std::min(l, n - 1)], stride,
                                   [&](Index node, double, const Vec<2>& g) { L += vg[node] * g.transpose(); });
          differing += !(same_bits(L(0, 0), out.l00[l]) && same_bits(L(0, 1), out.l01[l]) &&
                         same_bits(L(1, 0), out.l10[l]) && same_bits(L(1, 1), out.l11[l]));
          ++compared;
        }
      }
    }
  EXPECT_EQ(differing, 0) << "of " << compared;
  EXPECT_EQ(compared, 2 * 200 * kDeformationLanes * static_cast<int>(velocity_gradient_lanes_variants().size()));
}

// The 3D rows against the scalar sum: random uGIMP stencils in a cube of 8³ nodes,
// random grid velocities, every version the reference's bits in all nine entries.
TEST(DeformationLanes, VelocityGradient3dIsTheNodeByNodeSumBitForBit) {
  const int nodes = 8;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0), inside(2.0, nodes - 3.0);
  std::vector<Vec<3>> vg;
  for (int i = 0; i < nodes * nodes * nodes; ++i) vg.emplace_back(u(rng), u(rng), u(rng));
  const IVec<3> stride(1, nodes, nodes * nodes);
  const auto variants = velocity_gradient_rows3_variants();
  for (int t = 0; t < 300; ++t) {
    const Vec<3> x(inside(rng), inside(rng), inside(rng));
    const Stencil<3> st = make_stencil<3>(ShapeFunction::gimp, x, 1.0, Vec<3>::Constant(0.25));
    const Mat<3> reference = variants.front().function(st, vg.data(), stride);
    EXPECT_GT(reference.norm(), 0.0);
    for (const auto& v : variants) {
      const Mat<3> L = v.function(st, vg.data(), stride);
      for (int e = 0; e < 9; ++e) EXPECT_TRUE(test::same_bits(L(e), reference(e))) << v.name << ", entry " << e;
    }
  }
}

}  // namespace
}  // namespace pdmpm::mpm
