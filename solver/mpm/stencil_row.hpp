#pragma once
// A 2D 3 × 3 stencil's row of three nodes held in one AVX-512 register, node i's x, y
// in lanes 2i, 2i + 1 (the layout of Vec<2> arrays: one masked load reads a row). The
// row passes (g2p_rows, the velocity gradient's lanes) add the nodes' pairs one by one,
// in the scalar sum's order.
#include <immintrin.h>

namespace pdmpm::mpm {

// Node i's x, y of a stencil row.
__attribute__((target("avx512f"), always_inline)) inline __m128d node_pair(__m512d row, int i) {
  switch (i) {
    case 0:
      return __builtin_shufflevector(row, row, 0, 1);
    case 1:
      return __builtin_shufflevector(row, row, 2, 3);
    default:
      return __builtin_shufflevector(row, row, 4, 5);
  }
}

}  // namespace pdmpm::mpm
