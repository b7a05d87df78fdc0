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

// Below AVX-512 the same row's lanes 0–7 are two 256-bit registers (lanes 0–3 and 4–7).
struct Row3 {
  __m256d lo, hi;
};

__attribute__((target("avx2"), always_inline)) inline Row3 load_row3(const double* at) {
  return {_mm256_loadu_pd(at), _mm256_loadu_pd(at + 4)};
}
__attribute__((target("avx2"), always_inline)) inline Row3 sub(Row3 a, Row3 b) {
  return {_mm256_sub_pd(a.lo, b.lo), _mm256_sub_pd(a.hi, b.hi)};
}
__attribute__((target("avx2"), always_inline)) inline Row3 mul(Row3 a, Row3 b) {
  return {_mm256_mul_pd(a.lo, b.lo), _mm256_mul_pd(a.hi, b.hi)};
}

// Node i's x, y, z of a row (ninth: its ninth double) in lanes 0–2, lane 3 zero, as row_node.
__attribute__((target("avx2"), always_inline)) inline __m256d row3_node(Row3 r, double ninth, int i) {
  const __m256d zero = _mm256_setzero_pd();
  switch (i) {
    case 0:
      return _mm256_blend_pd(r.lo, zero, 0x8);
    case 1: {  // (lo₃, hi₀, hi₁): lanes 1 and 3 of (lo₂, lo₃, hi₀, hi₁) with lane 0 of (hi₀, hi₁, 0, 0)
      const __m256d middle = _mm256_permute2f128_pd(r.lo, r.hi, 0x21);
      return _mm256_shuffle_pd(middle, _mm256_blend_pd(r.hi, zero, 0xc), 0x5);
    }
    default:
      return _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm256_extractf128_pd(r.hi, 1)), _mm_set_sd(ninth), 1);
  }
}

// Every lane times one value.
__attribute__((target("avx2"), always_inline)) inline Row3 times(Row3 a, __m256d b) {
  return {_mm256_mul_pd(a.lo, b), _mm256_mul_pd(a.hi, b)};
}

// A 3D node's x, y, z in lanes 0–2 of a 256-bit register (lane 3 zero), loaded and stored
// as a 128-bit and a 64-bit piece. The G2P remap sums into the grid node by node this way:
// a row stored as two 256-bit pieces is read back by the next particle one node on, and a
// load that spans two earlier stores cannot take its data from the store buffer but waits
// until they reach the cache (3D G2P with such rows: 370 ns per particle against the scalar
// code's 155, 3D P2G 450 against 250, on an AVX2 Zen 3).
__attribute__((target("avx2"), always_inline)) inline __m256d load_xyz(const double* at) {
  return _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(at)), _mm_load_sd(at + 2), 1);
}
__attribute__((target("avx2"), always_inline)) inline void store_xyz(double* at, __m256d v) {
  _mm_storeu_pd(at, _mm256_castpd256_pd128(v));
  _mm_store_sd(at + 2, _mm256_extractf128_pd(v, 1));
}
__attribute__((target("avx2"), always_inline)) inline void add_to_node(double* at, __m256d term) {
  store_xyz(at, _mm256_add_pd(load_xyz(at), term));
}

// row3_shape's products, lane for lane and in the same order.
struct Row3ShapeAvx2 {
  Row3 w, gx, gy, gz;
  double w2, gx2, gy2, gz2;
};

__attribute__((target("avx2"), always_inline)) inline Row3ShapeAvx2 row3_shape_avx2(const Stencil<3>& st, int j, int l,
                                                                                    bool gradient) {
  const std::array<double, 3>&x = st.w[0], &dx = st.dw[0];
  const double wy = st.w[1][j], wz = st.w[2][l], dwy = st.dw[1][j], dwz = st.dw[2][l];
  const Row3 wx{_mm256_set_pd(x[1], x[0], x[0], x[0]), _mm256_set_pd(x[2], x[2], x[1], x[1])};
  const __m256d wyv = _mm256_set1_pd(wy), wzv = _mm256_set1_pd(wz);
  Row3ShapeAvx2 r{};
  r.w = times(times(wx, wyv), wzv);
  r.w2 = x[2] * wy * wz;
  if (gradient) {
    const Row3 dwx{_mm256_set_pd(dx[1], dx[0], dx[0], dx[0]), _mm256_set_pd(dx[2], dx[2], dx[1], dx[1])};
    const __m256d dwyv = _mm256_set1_pd(dwy), dwzv = _mm256_set1_pd(dwz);
    r.gx = times(times(dwx, wyv), wzv);
    r.gy = times(times(wx, dwyv), wzv);  // (∂Sy Sx) Sz: a product commutes bit for bit
    r.gz = times(times(wx, dwzv), wyv);
    r.gx2 = dx[2] * wy * wz, r.gy2 = dwy * x[2] * wz, r.gz2 = dwz * x[2] * wy;
  }
  return r;
}

}  // namespace pdmpm::mpm
