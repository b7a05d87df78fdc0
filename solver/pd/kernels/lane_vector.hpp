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

// Lane-wise a where mask is set, else +0.0: a bitwise and, since mask lanes are
// all ones or all zeros (the vector ?: of GCC 12 is lowered lane by lane).
inline d8 keep(m8 mask, d8 a) { return reinterpret_cast<d8>(reinterpret_cast<m8>(a) & mask); }

inline constexpr m8 lane_ids = {0, 1, 2, 3, 4, 5, 6, 7};

// Whether any lane of a mask is set.
inline bool any(m8 mask) {
#if defined(__AVX512F__)
  return _mm512_test_epi64_mask(reinterpret_cast<__m512i>(mask), reinterpret_cast<__m512i>(mask)) != 0;
#else
  return ((mask[0] | mask[1]) | (mask[2] | mask[3])) | ((mask[4] | mask[5]) | (mask[6] | mask[7]));
#endif
}

}  // namespace pdmpm::pd::kernels::PDMPM_SIMD_NS
