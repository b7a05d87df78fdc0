#include "solver/bc/indenter.hpp"

namespace pdmpm::bc {

template <int D>
Vec<D> Indenter<D>::add_forces(core::Particles<D>& p, double t) const {
  const Vec<D> c = center(t);
  // The total in the global particle order: a distributed run's is the one-process total.
  const auto total = p.template sum_in_order<D>([&](double* sum) {
    for (Index i = 0; i < p.n_real; ++i) {
      const Vec<D> d = p.position(i) - c;
      const double r = d.norm();
      if (r >= radius || r == 0.0) continue;
      const double magnitude = stiffness * (radius - r) * (radius - r);
      const Vec<D> F = (magnitude / r) * d;
      const Vec<D> on_indenter = force_density ? Vec<D>(F * p.volume[i]) : F;
      p.b[i] += force_density ? F : Vec<D>(F / p.volume[i]);
      for (int a = 0; a < D; ++a) sum[a] -= on_indenter[a];
    }
  });
  return Eigen::Map<const Vec<D>>(total.data());
}

template struct Indenter<1>;
template struct Indenter<2>;
template struct Indenter<3>;

}  // namespace pdmpm::bc
