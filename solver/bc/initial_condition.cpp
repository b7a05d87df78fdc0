#include "solver/bc/initial_condition.hpp"

namespace pdmpm::bc {

// Initial values are at t = 0 (the parser refuses t in them).
template <int D>
void apply_initial_conditions(const std::vector<InitialCondition<D>>& conditions, core::Particles<D>& p) {
  for (const auto& c : conditions)
    for (Index i : c.particles) {
      const auto vars = variables_at<D>(p.x0[i], 0.0);
      for (int a = 0; a < D; ++a) {
        if (c.velocity[a]) p.v[i][a] = (*c.velocity[a])(vars);
        if (c.displacement[a]) p.u[i][a] = (*c.displacement[a])(vars);
      }
    }
}

template <int D>
std::vector<std::pair<Index, Mat<D>>> initial_displacement_gradients(const std::vector<InitialCondition<D>>& conditions,
                                                                     const core::Particles<D>& p) {
  // The expression that set each particle's u_a last (later conditions overwrite earlier ones).
  std::vector<std::array<const Expression*, D>> source(static_cast<std::size_t>(p.n_real));
  for (auto& s : source) s.fill(nullptr);
  for (const auto& c : conditions)
    for (Index i : c.particles)
      for (int a = 0; a < D; ++a)
        if (c.displacement[a]) source[i][a] = &*c.displacement[a];

  const double h = kGradientStep * p.lattice.spacing;
  std::vector<std::pair<Index, Mat<D>>> out;
  for (Index i = 0; i < p.n_real; ++i) {
    bool any = false;
    Mat<D> grad = Mat<D>::Zero();
    for (int a = 0; a < D; ++a) {
      if (!source[i][a]) continue;
      any = true;
      for (int b = 0; b < D; ++b) {
        Vec<D> ahead = p.x0[i], behind = p.x0[i];
        ahead[b] += h;
        behind[b] -= h;
        grad(a, b) =
            ((*source[i][a])(variables_at<D>(ahead, 0.0)) - (*source[i][a])(variables_at<D>(behind, 0.0))) / (2.0 * h);
      }
    }
    if (any) out.emplace_back(i, grad);
  }
  return out;
}

template void apply_initial_conditions<1>(const std::vector<InitialCondition<1>>&, core::Particles<1>&);
template void apply_initial_conditions<2>(const std::vector<InitialCondition<2>>&, core::Particles<2>&);
template void apply_initial_conditions<3>(const std::vector<InitialCondition<3>>&, core::Particles<3>&);
template std::vector<std::pair<Index, Mat<1>>> initial_displacement_gradients<1>(
    const std::vector<InitialCondition<1>>&, const core::Particles<1>&);
template std::vector<std::pair<Index, Mat<2>>> initial_displacement_gradients<2>(
    const std::vector<InitialCondition<2>>&, const core::Particles<2>&);
template std::vector<std::pair<Index, Mat<3>>> initial_displacement_gradients<3>(
    const std::vector<InitialCondition<3>>&, const core::Particles<3>&);

}  // namespace pdmpm::bc
