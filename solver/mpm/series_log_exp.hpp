#pragma once
// ln and exp where a material point's strains put them: ½ ln d for d near 1 (the
// determinant of a stretch) and exp t for t near 0 (a volumetric log strain), by short
// series instead of a library call. Both are templates over double and the lane vectors
// (lanes.hpp): the same operations in the same order, so the scalar law and its lanes
// give the same bits. Outside the series' ranges the callers use std::log / std::exp.
//
// ½ ln d = atanh z with z = (d − 1)/(d + 1), and atanh z = z (1 + z²/3 + z⁴/5 + …): for
// |z| < 0.1 (d in 0.818 … 1.222) the terms to z¹⁵ leave out < z¹⁶/17 < 6e-18 relative.
// d − 1 is exact there (Sterbenz), so z carries two roundings (d + 1 and the division)
// and the sum one more: two ulps at most (the library's log: one). exp t = Σ tᵏ/k! for
// |t| < 0.1: the terms to t¹⁰ leave out < 0.1¹¹/11! ≈ 2.5e-19.
#include <cmath>

namespace pdmpm::mpm {

inline constexpr double kSeriesLimit = 0.1;  // |z| and |t| below which the series hold

// 1/3 + y/5 + … + y⁶/15 (y = x²): atanh(x)/x = 1 + y · this, to round-off for |x| < 0.1.
// Every coefficient a constant reciprocal: a division costs a point's whole chain.
template <class T>
inline T atanh_series_tail(T y) {
  return 1.0 / 3 + y * (1.0 / 5 + y * (1.0 / 7 + y * (1.0 / 9 + y * (1.0 / 11 + y * (1.0 / 13 + y * (1.0 / 15))))));
}

// atanh(x)/x for |x| < 0.1 (y = x²).
template <class T>
inline T atanh_over_x_series(T y) {
  return 1.0 + y * atanh_series_tail(y);
}

// z = (d − 1)/(d + 1), whose atanh is ½ ln d.
template <class T>
inline T half_log_argument(T d) {
  return (d - 1.0) / (d + 1.0);
}

// ½ ln d from z = half_log_argument(d), |z| < kSeriesLimit.
// z + z·(z² tail) rather than z·(1 + …): the small part is added to z, not rounded into 1.
template <class T>
inline T half_log_series(T z) {
  const T y = z * z;
  return z + z * (y * atanh_series_tail(y));
}

// exp t for |t| < kSeriesLimit (Horner, degree 10).
template <class T>
inline T exp_series(T t) {
  constexpr double c2 = 1.0 / 2, c3 = c2 / 3, c4 = c3 / 4, c5 = c4 / 5, c6 = c5 / 6, c7 = c6 / 7, c8 = c7 / 8,
                   c9 = c8 / 9, c10 = c9 / 10;
  return 1.0 +
      t * (1.0 + t * (c2 + t * (c3 + t * (c4 + t * (c5 + t * (c6 + t * (c7 + t * (c8 + t * (c9 + t * c10)))))))));
}

// ½ ln d and exp t: by the series where they hold, else the library's.
inline double series_half_log(double d) {
  const double z = half_log_argument(d);
  return std::abs(z) < kSeriesLimit ? half_log_series(z) : 0.5 * std::log(d);
}
inline double series_exp(double t) { return std::abs(t) < kSeriesLimit ? exp_series(t) : std::exp(t); }

}  // namespace pdmpm::mpm
