// Interpolation properties every MPM shape function must have inside the grid:
// partition of unity, linear completeness (Σ S x_I = x, Σ x_I ⊗ ∇S = I), and
// gradients equal to the derivative of the weights.
#include "solver/mpm/shape_function.hpp"

#include <gtest/gtest.h>

#include <random>

namespace pdmpm::mpm {
namespace {

class ShapeFunctionTest : public ::testing::TestWithParam<ShapeFunction> {};

TEST_P(ShapeFunctionTest, PartitionOfUnityAndLinearCompleteness2D) {
  const ShapeFunction sf = GetParam();
  const double h = 0.37, lp = h / 4;  // two particles per cell per axis
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(3.0, 9.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec<2> x(u(rng) * h, u(rng) * h);
    const Stencil<2> st = make_stencil<2>(sf, x, h, Vec<2>::Constant(lp));
    double sum = 0.0;
    Vec<2> first_moment = Vec<2>::Zero(), grad_sum = Vec<2>::Zero();
    Mat<2> grad_moment = Mat<2>::Zero();
    const IVec<2> stride(1, 1000);  // node index = i + 1000 j on a grid wider than any stencil here
    for_each_grid_node<2>(st, nodes_per_axis(sf), stride, [&](Index node, double w, const Vec<2>& g) {
      const Vec<2> xi(h * static_cast<double>(node % 1000), h * static_cast<double>(node / 1000));
      sum += w;
      first_moment += w * xi;
      grad_sum += g;
      grad_moment += xi * g.transpose();
    });
    // Round-off of a handful of products of O(1) numbers.
    EXPECT_NEAR(sum, 1.0, 1e-14);
    EXPECT_LT((first_moment - x).norm(), 1e-13 * x.norm());
    EXPECT_LT(grad_sum.norm(), 1e-13 / h);
    EXPECT_LT((grad_moment - Mat<2>::Identity()).norm(), 1e-13 * x.norm() / h);
  }
}

TEST_P(ShapeFunctionTest, GradientIsDerivativeOfWeight1D) {
  const ShapeFunction sf = GetParam();
  const double h = 1.0, lp = 0.25, eps = 1e-7;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(2.0, 6.0);
  for (int trial = 0; trial < 200; ++trial) {
    const double x = u(rng);
    const Weights1D w = weights_1d(sf, x, h, lp);
    for (int k = 0; k < nodes_per_axis(sf); ++k) {
      // Weight of the same node at x ± eps (node index may shift its slot).
      auto weight_of_node = [&](double xx) {
        const Weights1D ww = weights_1d(sf, xx, h, lp);
        const int slot = w.first + k - ww.first;
        return slot >= 0 && slot < 3 ? ww.w[slot] : 0.0;
      };
      const double fd = (weight_of_node(x + eps) - weight_of_node(x - eps)) / (2 * eps);
      // Central differences of C⁰/C¹ piecewise polynomials: O(eps) away from kinks;
      // skip samples within eps of a kink (linear at the node, GIMP at |r| = lp, h ± lp).
      const double r = std::abs(x - (w.first + k) * h);
      const bool near_kink = std::abs(r) < 2 * eps || std::abs(r - lp) < 2 * eps || std::abs(r - (h - lp)) < 2 * eps ||
          std::abs(r - (h + lp)) < 2 * eps || std::abs(r - 0.5) < 2 * eps || std::abs(r - 1.5) < 2 * eps ||
          std::abs(r - 1.0) < 2 * eps;
      if (!near_kink) {
        EXPECT_NEAR(w.dw[k], fd, 1e-6) << "x=" << x << " k=" << k;
      }
    }
  }
}

TEST(ShapeFunction, GimpReducesToAveragedLinearFunction) {
  // uGIMP weight = (1/2lp) ∫ N(x) dx over the particle domain; check by quadrature.
  const double h = 1.0, lp = 0.3;
  for (double r = -1.4; r <= 1.4; r += 0.0137) {
    const int n = 20000;
    double integral = 0.0;
    for (int i = 0; i < n; ++i) {
      const double x = r - lp + (i + 0.5) * 2 * lp / n;
      integral += std::max(0.0, 1.0 - std::abs(x) / h);
    }
    integral /= n;
    EXPECT_NEAR(gimp_weight(r, GimpScale(h, lp)), integral, 1e-8) << r;
  }
}

INSTANTIATE_TEST_SUITE_P(All, ShapeFunctionTest,
                         ::testing::Values(ShapeFunction::linear, ShapeFunction::gimp, ShapeFunction::bspline2),
                         [](const auto& param_info) { return std::string(name(param_info.param)); });

}  // namespace
}  // namespace pdmpm::mpm
