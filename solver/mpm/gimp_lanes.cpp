#include "solver/mpm/gimp_lanes.hpp"

#include <cmath>
#include <cstdlib>
#include <cstring>

namespace pdmpm::mpm {

namespace {

// W double lanes of the instruction set's native width (2 SSE2, 4 AVX2, 8 AVX-512):
// wider generic vectors make GCC 12 compare lane by lane. Every operation is the
// IEEE one per lane; no FMA (CMakeLists.txt: -ffp-contract=off).
template <int W>
struct Lanes {
  typedef double d __attribute__((vector_size(8 * W)));
  typedef long long m __attribute__((vector_size(8 * W)));
  // a where the mask is set, else b: bitwise, mask lanes are all ones or zeros.
  static d select(m mask, d a, d b) {
    return reinterpret_cast<d>((reinterpret_cast<m>(a) & mask) | (reinterpret_cast<m>(b) & ~mask));
  }
};

template <int W>
__attribute__((always_inline)) inline void gimp_lanes_by(const double* x_rel, const double* lp_in, double h,
                                                          GimpLanes& out) {
  using V = Lanes<W>;
  using d = typename V::d;
  using m = typename V::m;
  for (int c0 = 0; c0 < kGimpLanes; c0 += W) {
    d x, lp;
    std::memcpy(&x, x_rel + c0, sizeof x);
    std::memcpy(&lp, lp_in + c0, sizeof lp);
    const d g = x / h;
    // First node strictly inside the support (x_I > x − h − lp), as weights_1d.
    const d reach = g - 1.0 - lp / h;
    double below[W];
    for (int i = 0; i < W; ++i) {
      below[i] = std::floor(reach[i]);
      out.first[c0 + i] = static_cast<int>(below[i]) + 1;
    }
    d before;
    std::memcpy(&before, below, sizeof before);
    const d zero{}, one = zero + 1.0, hv = zero + h;
    for (int k = 0; k < 3; ++k) {
      const d r = (g - (before + 1.0 + k)) * h;  // x_p − x_I, as weights_1d's (g − (first + k)) h
      const m negative = r < 0.0;
      const d a = V::select(negative, -r, r), sign = V::select(negative, -one, one);
      const m inner = a < lp, middle = a < h - lp, outer = a < h + lp;  // inner ⊂ middle ⊂ outer
      const d dist = h + lp - a;
      // S = c − num/den: inner 1 − (r² + lp²)/(2h lp), middle 1 − |r|/h,
      // outer 0 − (−d²)/(4h lp) = d²/(4h lp), outside 0 − 0/1.
      const d c = V::select(middle, one, zero);
      const d num = V::select(inner, r * r + lp * lp, V::select(middle, a, V::select(outer, -(dist * dist), zero)));
      const d den = V::select(inner, 2.0 * hv * lp, V::select(middle, hv, V::select(outer, 4.0 * hv * lp, one)));
      const d w = c - num / den;
      // ∂S/∂x: inner −r/(h lp), middle −sign/h, outer −sign d/(2h lp), outside 0/1.
      const d gnum = V::select(inner, -r, V::select(middle, -sign, V::select(outer, -sign * dist, zero)));
      const d gden = V::select(inner, hv * lp, V::select(middle, hv, V::select(outer, 2.0 * hv * lp, one)));
      const d dw = gnum / gden;
      std::memcpy(out.w[k] + c0, &w, sizeof w);
      std::memcpy(out.dw[k] + c0, &dw, sizeof dw);
    }
  }
}

void gimp_lanes_sse2(const double* x, const double* lp, double h, GimpLanes& out) {
  gimp_lanes_by<2>(x, lp, h, out);
}
__attribute__((target("avx2"))) void gimp_lanes_avx2(const double* x, const double* lp, double h, GimpLanes& out) {
  gimp_lanes_by<4>(x, lp, h, out);
}
__attribute__((target("avx512f"))) void gimp_lanes_avx512(const double* x, const double* lp, double h,
                                                          GimpLanes& out) {
  gimp_lanes_by<8>(x, lp, h, out);
}

}  // namespace

std::vector<GimpLanesVariant> gimp_lanes_variants() {
  std::vector<GimpLanesVariant> v{{"sse2", gimp_lanes_sse2}};
  if (__builtin_cpu_supports("avx2")) v.push_back({"avx2", gimp_lanes_avx2});
  if (__builtin_cpu_supports("avx512f")) v.push_back({"avx512", gimp_lanes_avx512});
  return v;
}

// The widest this machine runs, or PDMPM_SIMD's choice (as the PD bond kernels).
void gimp_lanes(const double* x_rel, const double* lp, double h, GimpLanes& out) {
  static const GimpLanesFunction chosen = [] {
    const std::vector<GimpLanesVariant> v = gimp_lanes_variants();
    if (const char* want = std::getenv("PDMPM_SIMD"))
      for (const GimpLanesVariant& s : v)
        if (std::strcmp(want, s.name) == 0) return s.function;
    return v.back().function;
  }();
  chosen(x_rel, lp, h, out);
}

}  // namespace pdmpm::mpm
