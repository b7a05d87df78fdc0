#pragma once
// Eight double lanes as one value (GCC vector extensions). The compiler maps the
// arithmetic to whatever the translation unit's instruction set offers: one
// AVX-512 register, two AVX2 or four SSE2 registers. Every operation is the
// IEEE operation per lane, so all instruction sets give the same bits.
// GCC 12's _mm512_undefined_pd() self-initialises and trips -Wmaybe-uninitialized.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop

#ifndef PDMPM_SIMD_NS
#error "included by a bond_kernels_<isa>.cpp only: its inline functions differ per instruction set"
#endif

// One namespace per instruction set: an inline function compiled with AVX-512
// and the same one compiled for SSE2 must not be merged by the linker.
namespace pdmpm::pd::kernels::PDMPM_SIMD_NS {

typedef double d8 __attribute__((vector_size(64)));
typedef long long m8 __attribute__((vector_size(64)));  // lane masks: all ones or zero

inline d8 splat(double x) { return d8{x, x, x, x, x, x, x, x}; }

inline d8 sqrt8(d8 x) {
#if defined(__AVX512F__)
  return reinterpret_cast<d8>(_mm512_sqrt_pd(reinterpret_cast<__m512d>(x)));
#elif defined(__AVX__)
  typedef double d4 __attribute__((vector_size(32)));
  union {
    d8 v;
    d4 h[2];
  } u{x};
  u.h[0] = reinterpret_cast<d4>(_mm256_sqrt_pd(reinterpret_cast<__m256d>(u.h[0])));
  u.h[1] = reinterpret_cast<d4>(_mm256_sqrt_pd(reinterpret_cast<__m256d>(u.h[1])));
  return u.v;
#else
  typedef double d2 __attribute__((vector_size(16)));
  union {
    d8 v;
    d2 q[4];
  } u{x};
  for (auto& q : u.q) q = reinterpret_cast<d2>(_mm_sqrt_pd(reinterpret_cast<__m128d>(q)));
  return u.v;
#endif
}

// a > b (or a ≥ b with OrEqual) per lane as a mask. With AVX-512 the vector operator; below
// it, GCC 12 lowers an eight-lane comparison lane by lane (scalar compares, sets and
// inserts: the AVX2 and SSE2 LPS kernels ran 5–6× slower than the AVX-512 one), so the
// lanes are compared a native register at a time. The same lanes either way.
template <bool OrEqual>
inline m8 compare_greater(d8 a, d8 b) {
#if defined(__AVX512F__)
  return OrEqual ? a >= b : a > b;
#elif defined(__AVX__)
  typedef double d4 __attribute__((vector_size(32)));
  union {
    d8 v;
    d4 h[2];
  } ua{a}, ub{b}, r{};
  for (int h = 0; h < 2; ++h)
    r.h[h] = reinterpret_cast<d4>(_mm256_cmp_pd(reinterpret_cast<__m256d>(ua.h[h]), reinterpret_cast<__m256d>(ub.h[h]),
                                                OrEqual ? _CMP_GE_OQ : _CMP_GT_OQ));
  return reinterpret_cast<m8>(r.v);
#else
  typedef double d2 __attribute__((vector_size(16)));
  union {
    d8 v;
    d2 q[4];
  } ua{a}, ub{b}, r{};
  for (int q = 0; q < 4; ++q) {
    const __m128d x = reinterpret_cast<__m128d>(ua.q[q]), y = reinterpret_cast<__m128d>(ub.q[q]);
    r.q[q] = reinterpret_cast<d2>(OrEqual ? _mm_cmpge_pd(x, y) : _mm_cmpgt_pd(x, y));
  }
  return reinterpret_cast<m8>(r.v);
#endif
}
inline m8 greater(d8 a, d8 b) { return compare_greater<false>(a, b); }
inline m8 greater_equal(d8 a, d8 b) { return compare_greater<true>(a, b); }

// acc += x, lane by lane. Below AVX-512 an eight-lane accumulator that a bond loop's
// lambda updates was written back piecewise (8- and 16-byte moves) and read whole by the
// next block's add, a store the load cannot be forwarded from (on AMD Zen 3 the AVX2 LPS
// kernels' largest stall); here each register-wide part is added in place.
inline void add_to(d8& acc, d8 x) {
#if defined(__AVX512F__)
  acc += x;
#else
#if defined(__AVX__)
  constexpr int register_bytes = 32;
#else
  constexpr int register_bytes = 16;
#endif
  typedef double part __attribute__((vector_size(register_bytes), may_alias));
  constexpr int parts = 64 / register_bytes;
  part* a = reinterpret_cast<part*>(&acc);
  const part* b = reinterpret_cast<const part*>(&x);
  for (int k = 0; k < parts; ++k) a[k] += b[k];
#endif
}

// Lane-wise a where mask is set, else +0.0: a bitwise and, since mask lanes are
// all ones or all zeros (the vector ?: of GCC 12 is lowered lane by lane).
inline d8 keep(m8 mask, d8 a) { return reinterpret_cast<d8>(reinterpret_cast<m8>(a) & mask); }

// The lanes below count (0 ≤ count ≤ 8), from a table: the mask {0, …, 7} < count, which
// below AVX-512 GCC 12 would compare lane by lane.
inline m8 first_lanes(int count) {
  static constexpr m8 table[9] = {
      {0, 0, 0, 0, 0, 0, 0, 0},       {-1, 0, 0, 0, 0, 0, 0, 0},       {-1, -1, 0, 0, 0, 0, 0, 0},
      {-1, -1, -1, 0, 0, 0, 0, 0},    {-1, -1, -1, -1, 0, 0, 0, 0},    {-1, -1, -1, -1, -1, 0, 0, 0},
      {-1, -1, -1, -1, -1, -1, 0, 0}, {-1, -1, -1, -1, -1, -1, -1, 0}, {-1, -1, -1, -1, -1, -1, -1, -1}};
  return table[count];
}

// Whether any lane of a mask is set.
inline bool any(m8 mask) {
#if defined(__AVX512F__)
  return _mm512_test_epi64_mask(reinterpret_cast<__m512i>(mask), reinterpret_cast<__m512i>(mask)) != 0;
#elif defined(__AVX2__)
  // In registers: read lane by lane, the mask went through the stack into eight scalar loads.
  union {
    m8 v;
    __m256i h[2];
  } u{mask};
  const __m256i o = _mm256_or_si256(u.h[0], u.h[1]);
  return !_mm256_testz_si256(o, o);
#else
  union {
    m8 v;
    __m128i q[4];
  } u{mask};
  const __m128i o = _mm_or_si128(_mm_or_si128(u.q[0], u.q[1]), _mm_or_si128(u.q[2], u.q[3]));
  return _mm_movemask_epi8(_mm_cmpeq_epi32(o, _mm_setzero_si128())) != 0xFFFF;
#endif
}

}  // namespace pdmpm::pd::kernels::PDMPM_SIMD_NS
