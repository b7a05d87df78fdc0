#include "solver/bc/boundary.hpp"

namespace pdmpm::bc {

template <int D>
void Boundaries<D>::finalise(Index n_real) {
  mask_.assign(static_cast<std::size_t>(n_real) * D, 0);
  for (const auto& c : constraints)
    for (Index i : c.particles)
      for (int a = 0; a < D; ++a)
        if (c.active[a]) mask_[static_cast<std::size_t>(i) * D + a] = 1;
}

template <int D>
void Boundaries<D>::apply_velocity(core::Particles<D>& p, double t) const {
  for (const auto& c : constraints) {
    if (c.kind != ConstraintKind::velocity) continue;
    for (Index i : c.particles) {
      if (p.kind[i] != core::ParticleKind::pd) continue;  // the grid constrains MPM particles (hybrid)
      const auto vars = variables_at<D>(p.x0[i], t);
      for (int a = 0; a < D; ++a)
        if (c.active[a]) p.v[i][a] = c.value[a](vars);
    }
  }
}

template <int D>
void Boundaries<D>::apply_displacement(core::Particles<D>& p, double t, double dt) const {
  for (const auto& c : constraints) {
    for (Index i : c.particles) {
      if (p.kind[i] != core::ParticleKind::pd) continue;
      switch (c.kind) {
        case ConstraintKind::velocity:
          break;
        case ConstraintKind::fixed:
          for (int a = 0; a < D; ++a)
            if (c.active[a]) p.u[i][a] = 0.0, p.v[i][a] = 0.0;
          break;
        case ConstraintKind::displacement: {
          // v from the change over the step: consistent with the drift u += dt v.
          const auto now = variables_at<D>(p.x0[i], t), before = variables_at<D>(p.x0[i], t - dt);
          for (int a = 0; a < D; ++a) {
            if (!c.active[a]) continue;
            const double u1 = c.value[a](now);
            p.v[i][a] = dt > 0.0 ? (u1 - c.value[a](before)) / dt : 0.0;
            p.u[i][a] = u1;
          }
          break;
        }
        case ConstraintKind::analytic: {
          Vec<D> u, v;
          c.field->evaluate(p.x0[i], t, u, v);
          p.u[i] = u;
          p.v[i] = v;
          break;
        }
      }
    }
  }
}

template <int D>
void Boundaries<D>::add_tractions(core::Particles<D>& p, double t) const {
  for (const auto& tr : tractions) {
    for (Index i : tr.particles) {
      const auto vars = variables_at<D>(p.x0[i], t);
      for (int a = 0; a < D; ++a) p.b[i][a] += tr.value[a](vars) / tr.layer;
    }
  }
}

template class Boundaries<1>;
template class Boundaries<2>;
template class Boundaries<3>;

}  // namespace pdmpm::bc
