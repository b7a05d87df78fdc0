#include "solver/pd/precrack.hpp"

namespace pdmpm::pd {
namespace {

double cross2(const Vec<2>& a, const Vec<2>& b) { return a[0] * b[1] - a[1] * b[0]; }

// Does the bond x→y cross the segment p→q? Sides of the crack line are taken
// half-open (on the line = positive side).
bool crosses(const Vec<2>& x, const Vec<2>& y, const std::vector<Vec<2>>& seg) {
  const Vec<2> p = seg[0], q = seg[1];
  const bool sx = cross2(q - p, x - p) >= 0.0, sy = cross2(q - p, y - p) >= 0.0;
  if (sx == sy) return false;
  // The crack line separates x and y; the crossing point must lie within [p, q].
  const double dp = cross2(y - x, p - x), dq = cross2(y - x, q - x);
  return (dp >= 0.0 && dq <= 0.0) || (dp <= 0.0 && dq >= 0.0);
}

bool crosses(const Vec<3>& x, const Vec<3>& y, const std::vector<Vec<3>>& c) {
  const Vec<3> e1 = c[1] - c[0], e2 = c[2] - c[0];
  const Vec<3> n = e1.cross(e2);
  const double hx = n.dot(x - c[0]), hy = n.dot(y - c[0]);
  if ((hx >= 0.0) == (hy >= 0.0)) return false;
  const Vec<3> hit = x + (hx / (hx - hy)) * (y - x);  // where the bond meets the plane
  // Coordinates of the hit point in the (e1, e2) frame.
  const Vec<3> r = hit - c[0];
  const double a11 = e1.dot(e1), a12 = e1.dot(e2), a22 = e2.dot(e2);
  const double b1 = r.dot(e1), b2 = r.dot(e2), det = a11 * a22 - a12 * a12;
  const double s = (b1 * a22 - b2 * a12) / det, t = (a11 * b2 - a12 * b1) / det;
  return s >= 0.0 && s <= 1.0 && t >= 0.0 && t <= 1.0;
}

template <int D>
bool crosses_any(const Vec<D>& x, const Vec<D>& y, const CrackSurface<D>& crack) {
  if constexpr (D == 1) {
    (void)x, (void)y, (void)crack;
    return false;
  } else {
    return crosses(x, y, crack.points);
  }
}

}  // namespace

template <int D>
std::int64_t cut_bonds(System<D>& sys, const CrackSurface<D>& crack) {
  const auto& fam = sys.families;
  const auto& p = sys.particles;
  std::int64_t cut = 0;
#pragma omp parallel for schedule(static) reduction(+ : cut)
  for (Index i = 0; i < p.n_real; ++i)
    for (BondIndex b = fam.begin(i); b < fam.end(i); ++b) {
      if (sys.bonds.broken(b)) continue;
      if (crosses_any<D>(p.x0[i], p.x0[fam.neighbor[b]], crack)) {
        sys.bonds.cut(b);
        ++cut;
      }
    }
  return cut;
}

template std::int64_t cut_bonds<1>(System<1>&, const CrackSurface<1>&);
template std::int64_t cut_bonds<2>(System<2>&, const CrackSurface<2>&);
template std::int64_t cut_bonds<3>(System<3>&, const CrackSurface<3>&);

}  // namespace pdmpm::pd
