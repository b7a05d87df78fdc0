#pragma once
// A 2D 3 × 3 stencil's row of three nodes held in one AVX-512 register, node i's x, y
// in lanes 2i, 2i + 1 (the layout of Vec<2> arrays: one masked load reads a row). The
// row passes (g2p_rows, the velocity gradient's lanes) add the nodes' pairs one by one,
// in the scalar sum's order.
#include <immintrin.h>

#include <array>

#include "solver/core/types.hpp"
#include "solver/mpm/shape_function.hpp"

namespace pdmpm::mpm {

// Node i's x, y of two rows' products side by side, (a's x, y, b's x, y): one add takes
// node i into two sums of pairs at once, each lane still summed node by node.
__attribute__((target("avx512f"), always_inline)) inline __m256d node_pairs(__m512d a, __m512d b, int i) {
  const __m512i pick = _mm512_set_epi64(0, 0, 0, 0, 9 + 2 * i, 8 + 2 * i, 1 + 2 * i, 2 * i);
  return _mm512_castpd512_pd256(_mm512_permutex2var_pd(a, pick, b));
}

// Below AVX-512 a 2D row's six doubles are nodes 0 and 1's x, y in one 256-bit register
// and node 2's in a 128-bit one (two unmasked loads: AVX2's masked stores are slow on AMD).
struct Row2 {
  __m256d nodes01;
  __m128d node2;
};

__attribute__((target("avx2"), always_inline)) inline Row2 load_row(const double* at) {
  return {_mm256_loadu_pd(at), _mm_loadu_pd(at + 4)};
}
__attribute__((target("avx2"), always_inline)) inline void store_row(double* at, Row2 r) {
  _mm256_storeu_pd(at, r.nodes01);
  _mm_storeu_pd(at + 4, r.node2);
}
__attribute__((target("avx2"), always_inline)) inline Row2 add(Row2 a, Row2 b) {
  return {_mm256_add_pd(a.nodes01, b.nodes01), _mm_add_pd(a.node2, b.node2)};
}
__attribute__((target("avx2"), always_inline)) inline Row2 sub(Row2 a, Row2 b) {
  return {_mm256_sub_pd(a.nodes01, b.nodes01), _mm_sub_pd(a.node2, b.node2)};
}
__attribute__((target("avx2"), always_inline)) inline Row2 mul(Row2 a, Row2 b) {
  return {_mm256_mul_pd(a.nodes01, b.nodes01), _mm_mul_pd(a.node2, b.node2)};
}
// The row's three per-node values (a weight) each in its node's x and y lanes.
__attribute__((target("avx2"), always_inline)) inline Row2 per_node(const std::array<double, 3>& w) {
  return {_mm256_set_pd(w[1], w[1], w[0], w[0]), _mm_set1_pd(w[2])};
}
// One x, y pair in every node's lanes.
__attribute__((target("avx2"), always_inline)) inline Row2 every_node(double x, double y) {
  return {_mm256_set_pd(y, x, y, x), _mm_set_pd(y, x)};
}
__attribute__((target("avx2"), always_inline)) inline Row2 times(Row2 a, double s) {
  return {_mm256_mul_pd(a.nodes01, _mm256_set1_pd(s)), _mm_mul_pd(a.node2, _mm_set1_pd(s))};
}
// Node i's x, y of two rows side by side, (a's x, y, b's x, y), as node_pairs above.
__attribute__((target("avx2"), always_inline)) inline __m256d node_pairs(Row2 a, Row2 b, int i) {
  switch (i) {
    case 0:
      return _mm256_permute2f128_pd(a.nodes01, b.nodes01, 0x20);
    case 1:
      return _mm256_permute2f128_pd(a.nodes01, b.nodes01, 0x31);
    default:
      return _mm256_insertf128_pd(_mm256_castpd128_pd256(a.node2), b.node2, 1);
  }
}

// A 3D 3 × 3 × 3 stencil's row of three nodes: their x, y, z are nine doubles; lanes 0–7
// hold node 0's x, y, z, node 1's x, y, z and node 2's x, y (one unaligned load of a
// Vec<3> array reads them), the ninth double (node 2's z) goes apart in scalars.

// a's x, y, z in the lanes of every node of a row.
__attribute__((target("avx512f"), always_inline)) inline __m512d row_lanes(const Vec<3>& a) {
  return _mm512_set_pd(a[1], a[0], a[2], a[1], a[0], a[2], a[1], a[0]);
}

// Node i's x, y, z of a row (ninth: its ninth double) in lanes 0–2, the other lanes zero.
__attribute__((target("avx512f"), always_inline)) inline __m512d row_node(__m512d row, double ninth, int i) {
  switch (i) {
    case 0:
      return _mm512_maskz_mov_pd(0x07, row);
    case 1:
      return _mm512_maskz_permutexvar_pd(0x07, _mm512_set_epi64(0, 0, 0, 0, 0, 5, 4, 3), row);
    default:
      return _mm512_mask_broadcastsd_pd(
          _mm512_maskz_permutexvar_pd(0x03, _mm512_set_epi64(0, 0, 0, 0, 0, 0, 7, 6), row), 0x04, _mm_set_sd(ninth));
  }
}

// S and ∇S of a 3D row's nodes per lane as for_each_grid_node forms them — S = (Sx Sy) Sz,
// ∇S = ((∂Sx Sy) Sz, (∂Sy Sx) Sz, (∂Sz Sx) Sy) — and node 2's in scalars for the ninth double.
struct Row3Shape {
  __m512d w, gx, gy, gz;
  double w2, gx2, gy2, gz2;
};

__attribute__((target("avx512f"), always_inline)) inline Row3Shape row3_shape(const Stencil<3>& st, int j, int l,
                                                                              bool gradient) {
  const std::array<double, 3>&x = st.w[0], &dx = st.dw[0];
  const double wy = st.w[1][j], wz = st.w[2][l], dwy = st.dw[1][j], dwz = st.dw[2][l];
  const __m512d wx = _mm512_set_pd(x[2], x[2], x[1], x[1], x[1], x[0], x[0], x[0]);
  const __m512d wyv = _mm512_set1_pd(wy), wzv = _mm512_set1_pd(wz);
  Row3Shape r{};
  r.w = _mm512_mul_pd(_mm512_mul_pd(wx, wyv), wzv);
  r.w2 = x[2] * wy * wz;
  if (gradient) {
    const __m512d dwx = _mm512_set_pd(dx[2], dx[2], dx[1], dx[1], dx[1], dx[0], dx[0], dx[0]);
    r.gx = _mm512_mul_pd(_mm512_mul_pd(dwx, wyv), wzv);
    r.gy = _mm512_mul_pd(_mm512_mul_pd(_mm512_set1_pd(dwy), wx), wzv);
    r.gz = _mm512_mul_pd(_mm512_mul_pd(_mm512_set1_pd(dwz), wx), wyv);
    r.gx2 = dx[2] * wy * wz, r.gy2 = dwy * x[2] * wz, r.gz2 = dwz * x[2] * wy;
  }
  return r;
}

}  // namespace pdmpm::mpm
