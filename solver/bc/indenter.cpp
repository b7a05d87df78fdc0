#include "solver/bc/indenter.hpp"

namespace pdmpm::bc {

template <int D>
Vec<D> Indenter<D>::add_forces(core::Particles<D>& p, double t) const {
  const Vec<D> c = center(t);
  Vec<D> total = Vec<D>::Zero();
  for (Index i = 0; i < p.n_real; ++i) {
    const Vec<D> d = p.position(i) - c;
    const double r = d.norm();
    if (r >= radius || r == 0.0) continue;
    const double magnitude = stiffness * (radius - r) * (radius - r);
    const Vec<D> F = (magnitude / r) * d;
    if (force_density) {
      p.b[i] += F;
      total -= F * p.volume[i];
    } else {
      p.b[i] += F / p.volume[i];
      total -= F;
    }
  }
  return total;
}

template struct Indenter<1>;
template struct Indenter<2>;
template struct Indenter<3>;

}  // namespace pdmpm::bc
