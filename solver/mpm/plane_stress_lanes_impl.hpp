#pragma once
// The lane arithmetic of plane_stress_lanes.hpp, compiled once per instruction set (lane_set.hpp;
// lanes.hpp stops any other includer).
#include <cmath>
#include <limits>

#include "solver/mpm/j2_plasticity.hpp"
#include "solver/mpm/lanes.hpp"
#include "solver/mpm/plane_stress_lanes.hpp"
#include "solver/mpm/series_log_exp.hpp"

namespace pdmpm::mpm {
namespace {

// The plane-stress return map of j2_return_plane_stress for the lanes in `run`, each
// lane on its own iterates: f and its Newton step at Δγ (plane_stress_consistency, the
// scalar code's own function), Newton steps safeguarded by the bracket
// [lo, hi] that every iterate's sign tightens, bisection when a step leaves it. A lane
// whose step leaves the bracket while hi is still unknown joins `scalar` (the scalar
// code would now search for hi). Returns Δγ per lane.
template <int W>
__attribute__((always_inline)) inline typename Lanes<W>::d consistency_parameter(
    const PlaneStressLaw& law, typename Lanes<W>::m run, typename Lanes<W>::d s1, typename Lanes<W>::d s2,
    typename Lanes<W>::d alpha0, typename Lanes<W>::m& scalar) {
  using V = Lanes<W>;
  using d = typename V::d;
  using m = typename V::m;
  const double c1 = law.c1, c2 = 2.0 * law.shear, H = law.hardening;
  const double inf = std::numeric_limits<double>::infinity();
  // j2_return_plane_stress's tolerance, relative to κ_n² = max(σ_y, σ_y + H α₀)².
  const d hardened = law.yield_stress + H * alpha0;
  const d kappa_n = V::select(law.yield_stress < hardened, hardened, d{} + law.yield_stress);
  const d tol = 1e-15 * (kappa_n * kappa_n);
  auto f = [&](d dg) {
    return plane_stress_consistency(dg, s1, s2, c1, c2, law.yield_stress, H, alpha0, [](d x) { return V::sqrt(x); });
  };
  // j2_return_plane_stress's start and first bracket.
  const d start =
      plane_stress_newton_start(s1, s2, c1, c2, law.yield_stress + H * alpha0, H, [](d x) { return V::sqrt(x); });
  const d dg0 = V::select((start > 0.0) & ((start - start) == 0.0), start, d{} + 0.0);
  d dg = dg0;
  PlaneStressConsistency<d> e = f(dg);
  d fv = e.f, step = e.step;
  d lo = V::select(fv > 0.0, dg0, d{} + 0.0), hi = V::select(fv > 0.0, d{} + inf, dg0);
  m active = run;
  for (int it = 0; it < 200; ++it) {
    const d abs_f = V::select(fv < 0.0, -fv, fv);
    const m hi_finite = (hi - hi) == 0.0;
    active &= ~((abs_f <= tol) | (hi_finite & (hi - lo <= 1e-16 * hi)));
    d next = dg - step;
    const m outside = ~((next > lo) & (next < hi));
    const m unbracketed = active & outside & (hi == inf);
    scalar |= unbracketed;
    active &= ~unbracketed;
    if (V::bits(active) == 0) break;
    next = V::select(outside, 0.5 * (lo + hi), next);
    dg = V::select(active, next, dg);
    const PlaneStressConsistency<d> e_new = f(dg);
    fv = V::select(active, e_new.f, fv), step = V::select(active, e_new.step, step);
    const m up = fv > 0.0;
    lo = V::select(active & up, dg, lo), hi = V::select(active & ~up, dg, hi);
  }
  return dg;
}

template <int W>
inline unsigned plane_stress_lanes_by(const PlaneStressLaw& law, PlaneStressLanes& in) {
  using V = Lanes<W>;
  using d = typename V::d;
  using m = typename V::m;
  const double C = law.modulus, nu = law.nu, k = law.thickness_strain;
  const double c1 = law.c1, c2 = 2.0 * law.shear, oop_per_trace = -nu / law.youngs;
  unsigned by_law = 0;
  in.yielded = 0;
  for (int c0 = 0; c0 < kLawLanes; c0 += W) {
    // The elastic trial (hooke_plane_stress on ε − ε_p).
    const d l00 = V::load(in.l00 + c0), l11 = V::load(in.l11 + c0), l01 = V::load(in.l01 + c0);
    const d p00 = V::load(in.p00 + c0), p11 = V::load(in.p11 + c0), p01 = V::load(in.p01 + c0);
    const d p22 = V::load(in.p22 + c0), alpha = V::load(in.alpha + c0);
    const d e00 = l00 - p00, e11 = l11 - p11, e01 = l01 - p01;
    const d tr = e00 + e11;
    const d t00 = C * ((1.0 - nu) * e00 + nu * tr), t11 = C * ((1.0 - nu) * e11 + nu * tr);
    const d t01 = C * (1.0 - nu) * e01;
    // The yield check of j2_return_plane_stress in its spectral coordinates.
    const d a1 = (t00 + t11) * kInvSqrt2, a2 = (t11 - t00) * kInvSqrt2;
    const d s1 = a1 * a1 * kThird, s2 = a2 * a2 + 2.0 * t01 * t01;
    const d kappa = law.yield_stress + law.hardening * alpha;
    const d f0 = 0.5 * (s1 + s2) - kThird * (kappa * kappa);
    const m elastic = f0 <= 0.0, yielding = (f0 > 0.0) & ((f0 - f0) == 0.0);
    m scalar = ~(elastic | yielding);  // not finite
    d T00 = t00, T11 = t11, T01 = t01, out_of_plane = k * tr + p22;
    d energy;
    {
      const d q00 = t00 * e00, q11 = t11 * e11, q01 = t01 * e01;
      energy = 0.5 * ((q00 + q11) + (q01 + q01));
    }
    if (V::bits(yielding) != 0) {
      const d dg = consistency_parameter<W>(law, yielding, s1, s2, alpha, scalar);
      const m ret = yielding & ~scalar;
      // The returned stress and the plastic flow Δε_p = Δγ P σ.
      const PlaneStressReciprocals<d> i = plane_stress_reciprocals(dg, c1, c2);
      const d b1 = a1 * i.r1, b2 = a2 * i.r2, b3 = t01 * i.r2;
      const d r00 = (b1 - b2) * kInvSqrt2, r11 = (b1 + b2) * kInvSqrt2, r01 = b3;
      const d d00 = dg * (2.0 * r00 - r11) * kThird, d11 = dg * (2.0 * r11 - r00) * kThird, d01 = dg * r01;
      const d d22 = -(d00 + d11);
      const d d_alpha = kSqrt2over3 * dg * V::sqrt(s1 * i.r1 * i.r1 + s2 * i.r2 * i.r2);
      const d n00 = p00 + d00, n11 = p11 + d11, n01 = p01 + d01, n22 = p22 + d22;
      // T : Δε_p summed as Eigen sums the 3×3 product (T₃₃ = 0 times Δε_p,33 last).
      const d dissipation = ((r00 * d00 + r11 * d11) + (r01 * d01 + r01 * d01)) + 0.0 * d22;
      const d ee00 = l00 - n00, ee11 = l11 - n11, ee01 = l01 - n01;
      T00 = V::select(ret, r00, T00), T11 = V::select(ret, r11, T11), T01 = V::select(ret, r01, T01);
      energy = V::select(ret, 0.5 * (r00 * ee00 + r11 * ee11 + 2.0 * r01 * ee01), energy);
      out_of_plane = V::select(ret, oop_per_trace * (r00 + r11) + n22, out_of_plane);
      V::store(in.d00 + c0, d00), V::store(in.d11 + c0, d11), V::store(in.d01 + c0, d01);
      V::store(in.d22 + c0, d22), V::store(in.d_alpha + c0, d_alpha), V::store(in.dissipation + c0, dissipation);
      in.yielded |= V::bits(ret) << c0;
    }
    // τ = R T Rᵀ on the in-plane block.
    const d c = V::load(in.c + c0), s = V::load(in.s + c0), ms = -s;
    const d rt00 = c * T00 + ms * T01, rt01 = c * T01 + ms * T11;
    const d rt10 = s * T00 + c * T01, rt11 = s * T01 + c * T11;
    // J = exp(tr ε + ε₃₃) as the law makes it (series_exp).
    const d trace = (l00 + l11) + out_of_plane;
    const d by_series = exp_series(trace);
    const m small = V::select(trace < 0.0, -trace, trace) < kSeriesLimit;
    // Lanes beyond the series' range call the library; the law takes the flagged ones.
    const unsigned flagged = V::bits(scalar);
    d J = V::per_lane_where(V::bits(~small) & ~flagged, V::select(small, by_series, d{} + 1.0), trace,
                            [](double t) { return std::exp(t); });
    J = V::select(scalar, d{} + 1.0, J);
    by_law |= flagged << c0;
    V::store(in.k00 + c0, rt00 * c + rt01 * ms);
    V::store(in.k01 + c0, rt00 * s + rt01 * c);
    V::store(in.k10 + c0, rt10 * c + rt11 * ms);
    V::store(in.k11 + c0, rt10 * s + rt11 * c);
    V::store(in.J + c0, J);
    V::store(in.out_of_plane + c0, out_of_plane);
    V::store(in.energy + c0, energy);
  }
  return by_law;
}

}  // namespace
}  // namespace pdmpm::mpm
