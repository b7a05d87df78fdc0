#pragma once
// Lanes of doubles at an instruction set's native vector width (2 SSE2, 4 AVX2,
// 8 AVX-512) for the MPM's per-particle arithmetic done several particles at a
// time. Wider generic vectors than the hardware's make GCC 12 compare lane by lane.
// Every operation is the IEEE one per lane and the files using these compile
// without FMA contraction, so each version gives the scalar code's bits.
// Included only by the lane templates (*_impl.hpp), which lanes_<isa>.cpp compile once
// per instruction set (lane_set.hpp).
#ifndef PDMPM_LANES_WIDTH
#error "included by a lanes_<isa>.cpp only (lane_set.hpp): compiled once per instruction set"
#endif
#include <immintrin.h>

#include <cmath>
#include <cstring>

namespace pdmpm::mpm {

template <int W>
struct Lanes {
  typedef double d __attribute__((vector_size(8 * W)));
  typedef long long m __attribute__((vector_size(8 * W)));  // masks: all ones or zero per lane
  // a where the mask is set, else b: bitwise.
  __attribute__((always_inline)) static d select(m mask, d a, d b) { return mask ? a : b; }
  __attribute__((always_inline)) static d load(const double* p) {
    d v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  // Per lane by the correctly rounded square root; the lane files compile with
  // -fno-math-errno, so the loop becomes the vector instruction (same values).
  __attribute__((always_inline)) static d sqrt(d x) {
    double v[W];
    std::memcpy(v, &x, sizeof x);
    for (double& e : v) e = std::sqrt(e);
    return load(v);
  }
  // Per lane std::floor (exact, so any instruction gives the same bits): one rounding
  // instruction with AVX-512 or AVX2; SSE2 has none, and there GCC 12 keeps the lanes in
  // registers (a scalar floor per lane, then shuffles).
  __attribute__((always_inline)) static d floor(d x) {
    if constexpr (W == 8) {
      return reinterpret_cast<d>(_mm512_roundscale_pd(reinterpret_cast<__m512d>(x), _MM_FROUND_TO_NEG_INF));
    } else if constexpr (W == 4) {
      return reinterpret_cast<d>(_mm256_floor_pd(reinterpret_cast<__m256d>(x)));
    } else {
      double v[W];
      std::memcpy(v, &x, sizeof x);
      for (double& e : v) e = std::floor(e);
      return load(v);
    }
  }
  __attribute__((always_inline)) static void store(double* p, d v) { std::memcpy(p, &v, sizeof v); }
  // v with fn(x) in the lanes whose bit is set: a library function where a lane's series
  // does not hold (one call per such lane).
  template <class Fn>
  __attribute__((always_inline)) static d per_lane_where(unsigned lanes, d v, d x, Fn fn) {
    if (lanes == 0) return v;
    double out[W], in[W];
    store(out, v), store(in, x);
    for (int i = 0; i < W; ++i)
      if (lanes >> i & 1u) out[i] = fn(in[i]);
    return load(out);
  }
  // Bit i set where lane i of the mask is: the lanes' sign bits in one instruction (each
  // width's file compiles with its instruction set, lane_set.hpp; AVX512DQ for eight).
  __attribute__((always_inline)) static unsigned bits(m mask) {
    if constexpr (W == 8)
      return _mm512_movepi64_mask(reinterpret_cast<__m512i>(mask));
    else if constexpr (W == 4)
      return static_cast<unsigned>(_mm256_movemask_pd(reinterpret_cast<__m256d>(mask)));
    else
      return static_cast<unsigned>(_mm_movemask_pd(reinterpret_cast<__m128d>(mask)));
  }
};

}  // namespace pdmpm::mpm
