#pragma once
// Grid interpolation weights S_Ip and gradients ∇S_Ip, as tensor products of 1D
// weights. A particle touches at most 3 nodes per axis for every kind here
// (linear 2; uGIMP 3 when the half-width lp ≤ h/2; quadratic B-spline 3).
#include <array>
#include <cmath>

#include "solver/core/types.hpp"
#include "solver/mpm/settings.hpp"

namespace pdmpm::mpm {

inline constexpr int kMaxNodesPerAxis = 3;

inline int nodes_per_axis(ShapeFunction s) { return s == ShapeFunction::linear ? 2 : 3; }

// Weights of nodes first, first+1, … for a particle at grid coordinate g = (x − origin)/h.
struct Weights1D {
  int first = 0;
  std::array<double, kMaxNodesPerAxis> w{}, dw{};  // dw = ∂S/∂x (1/m)
};

// The cell size h and half-width lp of a particle's uGIMP weights along one axis, with
// the reciprocals the weights multiply by: two divisions per particle and axis instead
// of one per node and term (gimp_lanes_impl.hpp does the same operations in lanes).
struct GimpScale {
  double h, lp, inv_h, inv_h_lp;  // 1/h, 1/(h lp)
  GimpScale(double h_, double lp_) : h(h_), lp(lp_), inv_h(1.0 / h_), inv_h_lp(inv_h * (1.0 / lp_)) {}
};

// uGIMP weight and its slope ∂S/∂x_p for a node at signed distance r = x_p − x_I
// (Bardenhagen & Kober 2004, piecewise-constant particle characteristic of half-width lp,
// linear grid functions).
inline double gimp_weight(double r, const GimpScale& s) {
  const double a = std::abs(r), h = s.h, lp = s.lp;
  if (a < lp) return 1.0 - (r * r + lp * lp) * (0.5 * s.inv_h_lp);
  if (a < h - lp) return 1.0 - a * s.inv_h;
  if (a < h + lp) {
    const double d = h + lp - a;
    return d * d * (0.25 * s.inv_h_lp);
  }
  return 0.0;
}
inline double gimp_gradient(double r, const GimpScale& s) {
  const double a = std::abs(r), sign = r < 0.0 ? -1.0 : 1.0, h = s.h, lp = s.lp;
  if (a < lp) return -r * s.inv_h_lp;
  if (a < h - lp) return -sign * s.inv_h;
  if (a < h + lp) return -sign * (h + lp - a) * (0.5 * s.inv_h_lp);
  return 0.0;
}

// x_rel = x − origin along one axis; h = cell size; lp = GIMP half-width.
inline Weights1D weights_1d(ShapeFunction s, double x_rel, double h, double lp) {
  Weights1D r;
  const double g = x_rel / h;
  switch (s) {
    case ShapeFunction::linear: {
      r.first = static_cast<int>(std::floor(g));
      const double f = g - r.first;
      r.w = {1.0 - f, f, 0.0};
      r.dw = {-1.0 / h, 1.0 / h, 0.0};
      break;
    }
    case ShapeFunction::gimp: {
      const GimpScale scale(h, lp);
      const double gg = x_rel * scale.inv_h;
      // First node strictly inside the support (x_I > x − h − lp).
      r.first = static_cast<int>(std::floor(gg - 1.0 - lp * scale.inv_h)) + 1;
      for (int k = 0; k < 3; ++k) {
        const double dist = (gg - (r.first + k)) * h;
        r.w[k] = gimp_weight(dist, scale);
        r.dw[k] = gimp_gradient(dist, scale);  // ∂S/∂x_p at r = x_p − x_I
      }
      break;
    }
    case ShapeFunction::bspline2: {
      r.first = static_cast<int>(std::floor(g - 0.5));
      const double f = g - r.first;  // ∈ [0.5, 1.5)
      r.w = {0.5 * (1.5 - f) * (1.5 - f), 0.75 - (f - 1.0) * (f - 1.0), 0.5 * (f - 0.5) * (f - 0.5)};
      r.dw = {-(1.5 - f) / h, -2.0 * (f - 1.0) / h, (f - 0.5) / h};
      break;
    }
  }
  return r;
}

template <int D>
struct Stencil {
  IVec<D> first;
  std::array<std::array<double, kMaxNodesPerAxis>, D> w{}, dw{};
};

template <int D>
inline Stencil<D> make_stencil(ShapeFunction s, const Vec<D>& x_rel, double h, const Vec<D>& half_width) {
  Stencil<D> st;
  for (int a = 0; a < D; ++a) {
    const Weights1D w = weights_1d(s, x_rel[a], h, half_width[a]);
    st.first[a] = w.first;
    st.w[a] = w.w;
    st.dw[a] = w.dw;
  }
  return st;
}

// Calls f(grid index of the node, weight S, gradient ∇S) for each of the K^D stencil
// nodes, K fixed at compile time, axis 0 fastest. S and each component of ∇S are
// products of the 1D factors in axis order.
template <int D, int K, class F>
inline void for_each_grid_node(const Stencil<D>& st, const IVec<D>& stride, F&& f) {
  const Index base = st.first.dot(stride);
  if constexpr (D == 1) {
    for (int i = 0; i < K; ++i) f(base + i * stride[0], st.w[0][i], Vec<1>(st.dw[0][i]));
  } else if constexpr (D == 2) {
    for (int j = 0; j < K; ++j)
      for (int i = 0; i < K; ++i) {
        const double w = st.w[0][i] * st.w[1][j];
        f(base + i * stride[0] + j * stride[1], w, Vec<2>(st.dw[0][i] * st.w[1][j], st.dw[1][j] * st.w[0][i]));
      }
  } else {
    for (int l = 0; l < K; ++l)
      for (int j = 0; j < K; ++j)
        for (int i = 0; i < K; ++i) {
          const double w = st.w[0][i] * st.w[1][j] * st.w[2][l];
          f(base + i * stride[0] + j * stride[1] + l * stride[2], w,
            Vec<3>(st.dw[0][i] * st.w[1][j] * st.w[2][l], st.dw[1][j] * st.w[0][i] * st.w[2][l],
                   st.dw[2][l] * st.w[0][i] * st.w[1][j]));
        }
  }
}

// for_each_grid_node with the stencil size chosen at run time (2 or 3 nodes per axis).
template <int D, class F>
inline void for_each_grid_node(const Stencil<D>& st, int K, const IVec<D>& stride, F&& f) {
  if (K == 3)
    for_each_grid_node<D, 3>(st, stride, f);
  else
    for_each_grid_node<D, 2>(st, stride, f);
}

}  // namespace pdmpm::mpm
