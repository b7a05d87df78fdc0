#include "solver/core/shapes.hpp"

#include <algorithm>
#include <limits>

namespace pdmpm::core {

template <int D>
bool Box<D>::contains(const Vec<D>& x, double tol) const {
  for (int a = 0; a < D; ++a)
    if (x[a] < lo_[a] - tol || x[a] > hi_[a] + tol) return false;
  return true;
}

template <int D>
bool Ball<D>::contains(const Vec<D>& x, double tol) const {
  return (x - c_).norm() <= r_ + tol;
}

template <int D>
Bounds<D> Ball<D>::bounds() const {
  return {c_ - Vec<D>::Constant(r_), c_ + Vec<D>::Constant(r_)};
}

bool Cylinder::contains(const Vec<3>& x, double tol) const {
  const double along = x[axis_] - c_[axis_];
  if (along < -tol || along > h_ + tol) return false;
  Vec<3> d = x - c_;
  d[axis_] = 0.0;
  return d.norm() <= r_ + tol;
}

Bounds<3> Cylinder::bounds() const {
  Vec<3> lo = c_ - Vec<3>::Constant(r_), hi = c_ + Vec<3>::Constant(r_);
  lo[axis_] = c_[axis_];
  hi[axis_] = c_[axis_] + h_;
  return {lo, hi};
}

template <int D>
bool Geometry<D>::contains(const Vec<D>& x, double tol) const {
  bool inside = false;
  for (const auto& p : parts_) {
    if (p.added) {
      inside = inside || p.shape->contains(x, tol);
    } else if (inside && p.shape->contains(x, tol)) {
      inside = false;
    }
  }
  return inside;
}

template <int D>
Bounds<D> Geometry<D>::bounds() const {
  Bounds<D> b{Vec<D>::Constant(std::numeric_limits<double>::max()),
              Vec<D>::Constant(std::numeric_limits<double>::lowest())};
  for (const auto& p : parts_) {
    if (!p.added) continue;
    const Bounds<D> s = p.shape->bounds();
    b.min = b.min.cwiseMin(s.min);
    b.max = b.max.cwiseMax(s.max);
  }
  return b;
}

template <int D>
bool Geometry<D>::empty() const {
  return std::none_of(parts_.begin(), parts_.end(), [](const Part& p) { return p.added; });
}

template class Box<1>;
template class Box<2>;
template class Box<3>;
template class Ball<1>;
template class Ball<2>;
template class Ball<3>;
template class Geometry<1>;
template class Geometry<2>;
template class Geometry<3>;

}  // namespace pdmpm::core
