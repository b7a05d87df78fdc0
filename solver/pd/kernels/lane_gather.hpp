#pragma once
// Gathering eight short rows (up to four doubles each, e.g. a displacement or a
// bond-table row) into lane vectors: out[c][l] = base[S idx[l] + c].
//
// With AVX-512 each row is read as one four-double load and the 8 × 4 block is
// transposed with eight shuffles, instead of building every lane vector from
// eight scalars (about seven shuffles each). The result is the same bits either
// way: only data moves.
#include <cstdint>

#include "solver/pd/kernels/bond_kernels.hpp"
#include "solver/pd/kernels/lane_vector.hpp"

#ifndef PDMPM_SIMD_NS
#error "included by a bond_kernels_<isa>.cpp only: its inline functions differ per instruction set"
#endif

// One namespace per instruction set: an inline function compiled with AVX-512
// and the same one compiled for SSE2 must not be merged by the linker.
namespace pdmpm::pd::kernels::PDMPM_SIMD_NS {

// Reads exactly C doubles of each row.
template <int C, int S, typename I>
__attribute__((always_inline)) inline void gather_rows_narrow(const double* base, const I* idx, d8 out[C]) {
  for (int c = 0; c < C; ++c)
    out[c] = d8{base[S * idx[0] + c], base[S * idx[1] + c], base[S * idx[2] + c], base[S * idx[3] + c],
                base[S * idx[4] + c], base[S * idx[5] + c], base[S * idx[6] + c], base[S * idx[7] + c]};
}

// Reads four doubles of each row (with AVX-512, and with AVX2 for C > 2; two for C ≤ 2):
// base + S idx[l] + 3 must be readable even when C < 4.
template <int C, int S, typename I>
__attribute__((always_inline)) inline void gather_rows_wide(const double* base, const I* idx, d8 out[C]) {
  static_assert(C >= 1 && C <= 4, "rows of at most four doubles");
#if defined(__AVX512F__)
  auto row = [&](int l) { return _mm256_loadu_pd(base + S * idx[l]); };
  auto pair = [&](int l) {  // rows l and l + 4 in one register: (a₀ a₁ a₂ a₃ | b₀ b₁ b₂ b₃)
    return _mm512_insertf64x4(_mm512_castpd256_pd512(row(l)), row(l + 4), 1);
  };
  const __m512d z0 = pair(0), z1 = pair(1), z2 = pair(2), z3 = pair(3);
  const __m512d t0 = _mm512_unpacklo_pd(z0, z1), t1 = _mm512_unpackhi_pd(z0, z1);  // columns 0,2 / 1,3 of rows 0,1,4,5
  const __m512d t2 = _mm512_unpacklo_pd(z2, z3), t3 = _mm512_unpackhi_pd(z2, z3);  // the same of rows 2,3,6,7
  const __m512i even = _mm512_setr_epi64(0, 1, 8, 9, 4, 5, 12, 13), odd = _mm512_setr_epi64(2, 3, 10, 11, 6, 7, 14, 15);
  out[0] = reinterpret_cast<d8>(_mm512_permutex2var_pd(t0, even, t2));
  if constexpr (C > 1) out[1] = reinterpret_cast<d8>(_mm512_permutex2var_pd(t1, even, t3));
  if constexpr (C > 2) out[2] = reinterpret_cast<d8>(_mm512_permutex2var_pd(t0, odd, t2));
  if constexpr (C > 3) out[3] = reinterpret_cast<d8>(_mm512_permutex2var_pd(t1, odd, t3));
#elif defined(__AVX2__)
  // Four rows at a time: each row one load, the 4 × 4 (or 4 × 2) block transposed with
  // unpacks and lane swaps, each lane vector written as two whole 256-bit halves.
  union Lanes8 {
    d8 v;
    __m256d h[2];
  };
  Lanes8 col[C];
  for (int half = 0; half < 2; ++half) {
    const I* q = idx + 4 * half;
    if constexpr (C <= 2) {  // (x y) rows: (x₀ y₀ x₂ y₂) and (x₁ y₁ x₃ y₃), then unpacked
      auto row = [&](int l) { return _mm_loadu_pd(base + S * q[l]); };
      const __m256d a = _mm256_insertf128_pd(_mm256_castpd128_pd256(row(0)), row(2), 1);
      const __m256d b = _mm256_insertf128_pd(_mm256_castpd128_pd256(row(1)), row(3), 1);
      col[0].h[half] = _mm256_unpacklo_pd(a, b);
      if constexpr (C > 1) col[1].h[half] = _mm256_unpackhi_pd(a, b);
    } else {
      auto row = [&](int l) { return _mm256_loadu_pd(base + S * q[l]); };
      const __m256d r0 = row(0), r1 = row(1), r2 = row(2), r3 = row(3);
      const __m256d t0 = _mm256_unpacklo_pd(r0, r1), t1 = _mm256_unpackhi_pd(r0, r1);  // columns 0,2 / 1,3 of rows 0,1
      const __m256d t2 = _mm256_unpacklo_pd(r2, r3), t3 = _mm256_unpackhi_pd(r2, r3);  // the same of rows 2,3
      col[0].h[half] = _mm256_permute2f128_pd(t0, t2, 0x20);
      col[1].h[half] = _mm256_permute2f128_pd(t1, t3, 0x20);
      col[2].h[half] = _mm256_permute2f128_pd(t0, t2, 0x31);
      if constexpr (C > 3) col[3].h[half] = _mm256_permute2f128_pd(t1, t3, 0x31);
    }
  }
  for (int c = 0; c < C; ++c) out[c] = col[c].v;
#else
  gather_rows_narrow<C, S>(base, idx, out);
#endif
}

// The lanes whose byte (of the eight low bytes) is 0, as lane masks. Below AVX-512 GCC 12
// compares eight 64-bit lanes one by one (compare_greater says why); there the bytes are
// compared in one register and their results widened.
inline m8 zero_bytes_to_lanes(__m128i bytes) {
#if defined(__AVX512F__)  // (the maskz form: GCC 12's unmasked one warns on its undefined source)
  return reinterpret_cast<m8>(_mm512_maskz_cvtepu8_epi64(0xFF, bytes)) == 0;
#else
  const __m128i z = _mm_cmpeq_epi8(bytes, _mm_setzero_si128());  // 0xFF where a byte is 0
#if defined(__AVX2__)
  // Written as two whole 256-bit halves: written in 128-bit quarters, the 256-bit reads
  // that follow could not be forwarded from the stores (a stall per block on AMD Zen 3).
  union {
    m8 v;
    __m256i h[2];
  } r{};
  r.h[0] = _mm256_cvtepi8_epi64(z), r.h[1] = _mm256_cvtepi8_epi64(_mm_srli_si128(z, 4));
#else
  union {
    m8 v;
    __m128i q[4];
  } r{};
  const __m128i w = _mm_unpacklo_epi8(z, z), d0 = _mm_unpacklo_epi16(w, w), d1 = _mm_unpackhi_epi16(w, w);
  r.q[0] = _mm_unpacklo_epi32(d0, d0), r.q[1] = _mm_unpackhi_epi32(d0, d0);
  r.q[2] = _mm_unpacklo_epi32(d1, d1), r.q[3] = _mm_unpackhi_epi32(d1, d1);
#endif
  return r.v;
#endif
}
// Eight bytes (0 or not) widened to lane masks of the lanes that are 0.
inline m8 lanes_zero(const std::uint8_t* bytes) {
  return zero_bytes_to_lanes(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(bytes)));
}

// Eight bytes with the bits of `ignored` cleared.
inline __m128i kept_bytes(const std::uint8_t* bytes, std::uint8_t ignored) {
  const __m128i kept = _mm_set1_epi8(static_cast<char>(static_cast<std::uint8_t>(~ignored)));
  return _mm_and_si128(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(bytes)), kept);
}

// The same for the bytes with the bits of `ignored` cleared.
inline m8 lanes_zero_ignoring(const std::uint8_t* bytes, std::uint8_t ignored) {
  return zero_bytes_to_lanes(kept_bytes(bytes, ignored));
}

// Whether any of the first `count` bytes, with the bits of `ignored` cleared, is 0: the
// same answer as any(lanes_zero_ignoring(…) & first_lanes(count)) from one byte compare,
// without building lane masks (below AVX-512 those go through the stack).
inline bool any_zero_byte(const std::uint8_t* bytes, int count, std::uint8_t ignored = 0) {
  const int zero = _mm_movemask_epi8(_mm_cmpeq_epi8(kept_bytes(bytes, ignored), _mm_setzero_si128()));
  return (zero & ((1 << count) - 1)) != 0;
}

}  // namespace pdmpm::pd::kernels::PDMPM_SIMD_NS
