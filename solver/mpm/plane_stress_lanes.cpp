#include "solver/mpm/plane_stress_lanes.hpp"

#include <cmath>

#include "solver/mpm/lanes.hpp"

namespace pdmpm::mpm {

namespace {

template <int W>
__attribute__((always_inline)) inline unsigned plane_stress_lanes_by(const PlaneStressLaw& law, PlaneStressLanes& in) {
  using V = Lanes<W>;
  using d = typename V::d;
  using m = typename V::m;
  const double C = law.modulus, nu = law.nu, k = law.thickness_strain;
  const double sqrt2 = std::sqrt(2.0);
  unsigned plastic = 0;
  for (int c0 = 0; c0 < kLawLanes; c0 += W) {
    // The elastic trial (hooke_plane_stress on ε − ε_p).
    const d e00 = V::load(in.l00 + c0) - V::load(in.p00 + c0), e11 = V::load(in.l11 + c0) - V::load(in.p11 + c0);
    const d e01 = V::load(in.l01 + c0) - V::load(in.p01 + c0);
    const d tr = e00 + e11;
    const d t00 = C * ((1.0 - nu) * e00 + nu * tr), t11 = C * ((1.0 - nu) * e11 + nu * tr);
    const d t01 = C * (1.0 - nu) * e01;
    // The yield check of j2_return_plane_stress in its spectral coordinates.
    const d a1 = (t00 + t11) / sqrt2, a2 = (t11 - t00) / sqrt2;
    const d s1 = a1 * a1 / 3.0, s2 = a2 * a2 + 2.0 * t01 * t01;
    const d kappa = law.yield_stress + law.hardening * V::load(in.alpha + c0);
    const m elastic = 0.5 * (s1 + s2) - kappa * kappa / 3.0 <= 0.0;
    const d out_of_plane = k * tr + V::load(in.p22 + c0);
    const d p00 = t00 * e00, p11 = t11 * e11, p01 = t01 * e01;
    // τ = R T Rᵀ on the in-plane block.
    const d c = V::load(in.c + c0), s = V::load(in.s + c0), ms = -s;
    const d rt00 = c * t00 + ms * t01, rt01 = c * t01 + ms * t11;
    const d rt10 = s * t00 + c * t01, rt11 = s * t01 + c * t11;
    // J = exp(tr ε + ε₃₃), one library call per elastic lane (as the law makes it).
    const d trace = (V::load(in.l00 + c0) + V::load(in.l11 + c0)) + out_of_plane;
    double J[W];
    for (int i = 0; i < W; ++i) {
      if (elastic[i]) {
        J[i] = std::exp(trace[i]);
      } else {
        J[i] = 1.0;
        plastic |= 1u << (c0 + i);
      }
    }
    V::store(in.k00 + c0, rt00 * c + rt01 * ms);
    V::store(in.k01 + c0, rt00 * s + rt01 * c);
    V::store(in.k10 + c0, rt10 * c + rt11 * ms);
    V::store(in.k11 + c0, rt10 * s + rt11 * c);
    V::store(in.J + c0, V::load(J));
    V::store(in.out_of_plane + c0, out_of_plane);
    V::store(in.energy + c0, 0.5 * ((p00 + p11) + (p01 + p01)));
  }
  return plastic;
}

unsigned plane_stress_lanes_sse2(const PlaneStressLaw& law, PlaneStressLanes& in) {
  return plane_stress_lanes_by<2>(law, in);
}
__attribute__((target("avx2"))) unsigned plane_stress_lanes_avx2(const PlaneStressLaw& law, PlaneStressLanes& in) {
  return plane_stress_lanes_by<4>(law, in);
}
__attribute__((target("avx512f"))) unsigned plane_stress_lanes_avx512(const PlaneStressLaw& law, PlaneStressLanes& in) {
  return plane_stress_lanes_by<8>(law, in);
}

}  // namespace

std::vector<LaneVariant<PlaneStressLanesFunction>> plane_stress_lanes_variants() {
  return lane_variants<PlaneStressLanesFunction>(plane_stress_lanes_sse2, plane_stress_lanes_avx2,
                                                 plane_stress_lanes_avx512);
}

unsigned plane_stress_lanes(const PlaneStressLaw& law, PlaneStressLanes& lanes) {
  static const PlaneStressLanesFunction chosen = choose_lane_variant(plane_stress_lanes_variants());
  return chosen(law, lanes);
}

}  // namespace pdmpm::mpm
