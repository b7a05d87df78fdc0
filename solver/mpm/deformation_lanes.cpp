#include "solver/mpm/deformation_lanes.hpp"

#include <immintrin.h>

#include <algorithm>

#include "solver/mpm/stencil_row.hpp"

namespace pdmpm::mpm {

namespace {

// The reference: Simulation<2>::velocity_gradient's sum, L += v_I ∇S_Iᵀ node by node.
void velocity_gradient_scalar(DeformationLanes& out, const Stencil<2>* stencil, int n, const Vec<2>* vg,
                              Index row_stride) {
  const IVec<2> stride(1, row_stride);
  for (int l = 0; l < kDeformationLanes; ++l) {
    Mat<2> L = Mat<2>::Zero();
    for_each_grid_node<2, 3>(stencil[std::min(l, n - 1)], stride,
                             [&](Index node, double, const Vec<2>& g) { L += vg[node] * g.transpose(); });
    out.l00[l] = L(0, 0), out.l01[l] = L(0, 1), out.l10[l] = L(1, 0), out.l11[l] = L(1, 1);
  }
}

// A short group's lanes past n repeat its last particle's L.
void repeat_last_particle(DeformationLanes& out, int n) {
  for (int l = n; l < kDeformationLanes; ++l)
    out.l00[l] = out.l00[n - 1], out.l10[l] = out.l10[n - 1], out.l01[l] = out.l01[n - 1], out.l11[l] = out.l11[n - 1];
}

// Per node ∇S = (∂S₀ᵢ S₁ⱼ, ∂S₁ⱼ S₀ᵢ); v_I ∇S_Iᵀ's column 0 is v_I ∂S/∂x (its x, y in a
// pair), column 1 v_I ∂S/∂y; each pair is added node by node as the scalar sum adds.
__attribute__((target("avx512f"))) void velocity_gradient_avx512(DeformationLanes& out, const Stencil<2>* stencil,
                                                                 int n, const Vec<2>* vg, Index row_stride) {
  const __mmask8 six = 0x3f;
  for (int l = 0; l < n; ++l) {
    const Stencil<2>& st = stencil[l];
    const std::array<double, 3>&w0 = st.w[0], &d0 = st.dw[0];
    const __m512d w0x2 = _mm512_set_pd(0.0, 0.0, w0[2], w0[2], w0[1], w0[1], w0[0], w0[0]);
    const __m512d d0x2 = _mm512_set_pd(0.0, 0.0, d0[2], d0[2], d0[1], d0[1], d0[0], d0[0]);
    const Index base = st.first[0] + st.first[1] * row_stride;
    __m256d cols = _mm256_setzero_pd();  // L's columns 0 and 1: L00, L10, L01, L11
    for (int j = 0; j < 3; ++j) {
      const __m512d v = _mm512_maskz_loadu_pd(six, vg[base + j * row_stride].data());
      const __m512d gx = _mm512_mul_pd(d0x2, _mm512_set1_pd(st.w[1][j]));
      const __m512d gy = _mm512_mul_pd(_mm512_set1_pd(st.dw[1][j]), w0x2);
      const __m512d c0 = _mm512_mul_pd(v, gx), c1 = _mm512_mul_pd(v, gy);
      for (int i = 0; i < 3; ++i) cols = _mm256_add_pd(cols, node_pairs(c0, c1, i));
    }
    out.l00[l] = cols[0], out.l10[l] = cols[1], out.l01[l] = cols[2], out.l11[l] = cols[3];
  }
  repeat_last_particle(out, n);
}

// The same below AVX-512, a row as a 256-bit and a 128-bit register (Row2, stencil_row.hpp).
__attribute__((target("avx2"))) void velocity_gradient_avx2(DeformationLanes& out, const Stencil<2>* stencil, int n,
                                                            const Vec<2>* vg, Index row_stride) {
  for (int l = 0; l < n; ++l) {
    const Stencil<2>& st = stencil[l];
    const Row2 w0 = per_node(st.w[0]), d0 = per_node(st.dw[0]);
    const Index base = st.first[0] + st.first[1] * row_stride;
    __m256d cols = _mm256_setzero_pd();  // L's columns 0 and 1: L00, L10, L01, L11
    for (int j = 0; j < 3; ++j) {
      const Row2 v = load_row(vg[base + j * row_stride].data());
      const Row2 c0 = mul(v, times(d0, st.w[1][j])), c1 = mul(v, times(w0, st.dw[1][j]));
      for (int i = 0; i < 3; ++i) cols = _mm256_add_pd(cols, node_pairs(c0, c1, i));
    }
    out.l00[l] = cols[0], out.l10[l] = cols[1], out.l01[l] = cols[2], out.l11[l] = cols[3];
  }
  repeat_last_particle(out, n);
}

// The reference: Simulation<3>::velocity_gradient's sum, L(a, b) += v_a g_b node by node.
Mat<3> velocity_gradient_rows3_scalar(const Stencil<3>& stencil, const Vec<3>* vg, const IVec<3>& stride) {
  double L[3][3] = {};
  for_each_grid_node<3, 3>(stencil, stride, [&](Index node, double, const Vec<3>& g) {
    const Vec<3>& v = vg[node];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) L[a][b] += v[a] * g[b];
  });
  Mat<3> out;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) out(a, b) = L[a][b];
  return out;
}

// Column b of L is Σ v_I ∂S_I/∂x_b: per row, the nodes' velocities times ∂S/∂x_b lane by
// lane, then node by node into the column (lanes 0–2).
__attribute__((target("avx512f"))) Mat<3> velocity_gradient_rows3_avx512(const Stencil<3>& st, const Vec<3>* vg,
                                                                         const IVec<3>& stride) {
  __m512d col0 = _mm512_setzero_pd(), col1 = col0, col2 = col0;
  const Index base = st.first[0] + st.first[1] * stride[1] + st.first[2] * stride[2];
  for (int l = 0; l < 3; ++l)
    for (int j = 0; j < 3; ++j) {
      const double* v_at = vg[base + j * stride[1] + l * stride[2]].data();
      const Row3Shape shape = row3_shape(st, j, l, true);
      const __m512d v = _mm512_loadu_pd(v_at);
      const __m512d c0 = _mm512_mul_pd(v, shape.gx), c1 = _mm512_mul_pd(v, shape.gy), c2 = _mm512_mul_pd(v, shape.gz);
      const double n0 = v_at[8] * shape.gx2, n1 = v_at[8] * shape.gy2, n2 = v_at[8] * shape.gz2;
      for (int i = 0; i < 3; ++i) {
        col0 = _mm512_add_pd(col0, row_node(c0, n0, i));
        col1 = _mm512_add_pd(col1, row_node(c1, n1, i));
        col2 = _mm512_add_pd(col2, row_node(c2, n2, i));
      }
    }
  alignas(64) double c[3][8];
  _mm512_store_pd(c[0], col0), _mm512_store_pd(c[1], col1), _mm512_store_pd(c[2], col2);
  Mat<3> out;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) out(a, b) = c[b][a];
  return out;
}

// The same below AVX-512 (Row3, stencil_row.hpp).
__attribute__((target("avx2"))) Mat<3> velocity_gradient_rows3_avx2(const Stencil<3>& st, const Vec<3>* vg,
                                                                    const IVec<3>& stride) {
  __m256d col0 = _mm256_setzero_pd(), col1 = col0, col2 = col0;
  const Index base = st.first[0] + st.first[1] * stride[1] + st.first[2] * stride[2];
  for (int l = 0; l < 3; ++l)
    for (int j = 0; j < 3; ++j) {
      const double* v_at = vg[base + j * stride[1] + l * stride[2]].data();
      const Row3ShapeAvx2 shape = row3_shape_avx2(st, j, l, true);
      const Row3 v = load_row3(v_at);
      const Row3 c0 = mul(v, shape.gx), c1 = mul(v, shape.gy), c2 = mul(v, shape.gz);
      const double n0 = v_at[8] * shape.gx2, n1 = v_at[8] * shape.gy2, n2 = v_at[8] * shape.gz2;
      for (int i = 0; i < 3; ++i) {
        col0 = _mm256_add_pd(col0, row3_node(c0, n0, i));
        col1 = _mm256_add_pd(col1, row3_node(c1, n1, i));
        col2 = _mm256_add_pd(col2, row3_node(c2, n2, i));
      }
    }
  alignas(32) double c[3][4];
  _mm256_store_pd(c[0], col0), _mm256_store_pd(c[1], col1), _mm256_store_pd(c[2], col2);
  Mat<3> out;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) out(a, b) = c[b][a];
  return out;
}

}  // namespace

std::vector<LaneVariant<VelocityGradientRows3Function>> velocity_gradient_rows3_variants() {
  // No SSE2 rows: that machine runs the scalar reference.
  return lane_variants<VelocityGradientRows3Function>(velocity_gradient_rows3_scalar, velocity_gradient_rows3_avx2,
                                                      velocity_gradient_rows3_avx512);
}

Mat<3> velocity_gradient_rows3(const Stencil<3>& stencil, const Vec<3>* grid_velocity, const IVec<3>& stride) {
  static const VelocityGradientRows3Function chosen = choose_lane_variant(velocity_gradient_rows3_variants());
  return chosen(stencil, grid_velocity, stride);
}

std::vector<LaneVariant<VelocityGradientLanesFunction>> velocity_gradient_lanes_variants() {
  // No SSE2 rows: that machine runs the scalar reference.
  return lane_variants<VelocityGradientLanesFunction>(velocity_gradient_scalar, velocity_gradient_avx2,
                                                      velocity_gradient_avx512);
}

void velocity_gradient_lanes(DeformationLanes& lanes, const Stencil<2>* stencil, int n, const Vec<2>* grid_velocity,
                             Index row_stride) {
  static const VelocityGradientLanesFunction chosen = choose_lane_variant(velocity_gradient_lanes_variants());
  chosen(lanes, stencil, n, grid_velocity, row_stride);
}

}  // namespace pdmpm::mpm
