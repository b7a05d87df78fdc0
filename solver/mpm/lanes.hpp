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
  // Per lane std::floor (exact, so any instruction gives the same bits). GCC 12 keeps
  // the lanes in registers here (a scalar round per lane, then shuffles), where floors
  // stored to an array and loaded back as a vector wait for the stores (no forwarding).
  __attribute__((always_inline)) static d floor(d x) {
    double v[W];
    std::memcpy(v, &x, sizeof x);
    for (double& e : v) e = std::floor(e);
    return load(v);
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
  // Bit i set where lane i of the mask is. (One instruction in intrinsics, but those do
  // not inline through these templates into the per-ISA functions, GCC 12; an OR-fold of
  // the lanes measured no faster than this loop.)
  __attribute__((always_inline)) static unsigned bits(m mask) {
    long long lanes[W];
    std::memcpy(lanes, &mask, sizeof mask);
    unsigned b = 0;
    for (int i = 0; i < W; ++i) b |= static_cast<unsigned>(lanes[i] & 1) << i;
    return b;
  }
};

}  // namespace pdmpm::mpm
