#include "solver/hybrid/conversion.hpp"

#include <cmath>

#include "solver/hybrid/plastic_state_transfer.hpp"
#include "solver/mpm/kinematics.hpp"
#include "solver/pd/lps_plastic.hpp"

namespace pdmpm::hybrid {

template <int D>
std::optional<Mat<D>> bond_deformation_gradient(const pd::System<D>& sys, Index i) {
  const auto& p = sys.particles;
  Mat<D> K = Mat<D>::Zero(), N = Mat<D>::Zero();
  const Vec<D> yi = p.position(i);
  sys.for_each_live_bond(i, [&](BondIndex, Index j, int k) {
    const Vec<D>& xi = sys.table.xi[k];
    K += p.volume[j] * xi * xi.transpose();
    N += p.volume[j] * (p.position(j) - yi) * xi.transpose();
  });
  // Rank: the smallest eigenvalue against the trace; 1e-8 is far above round-off and
  // far below any two non-parallel bonds (a 45° pair gives ~0.15).
  const Eigen::SelfAdjointEigenSolver<Mat<D>> eig(K);
  if (!(K.trace() > 0.0) || eig.eigenvalues().minCoeff() <= 1e-8 * K.trace()) return std::nullopt;
  return Mat<D>(N * K.inverse());
}

template <int D>
void to_pd(const mpm::Simulation<D>& mpm, const pd::System<D>& sys, pd::Model<D>& model, Index i) {
  if constexpr (D >= 2)
    if (auto* plastic = dynamic_cast<pd::LpsPlastic<D>*>(&model))
      carry_plastic_state_into_pd<D>(sys, *plastic, i, mpm.state().history(i));
}

template <int D>
Mat<3> grid_elastic_strain(const mpm::Simulation<D>& mpm, Index i) {
  Mat<3> log_u = Mat<3>::Zero();
  log_u.topLeftCorner<D, D>() = mpm::polar_log<D>(mpm.state().F.get(i)).log_U;
  if constexpr (D == 2) log_u(2, 2) = mpm.state().out_of_plane_strain[i];
  return log_u - mpm.state().history(i).plastic_strain;
}

template <int D>
void to_pd_elastic_state(const mpm::Simulation<D>& mpm, const pd::System<D>& sys, pd::Model<D>& model, Index i) {
  if constexpr (D >= 2)
    if (auto* plastic = dynamic_cast<pd::LpsPlastic<D>*>(&model))
      carry_elastic_state_into_pd<D>(sys, *plastic, i, grid_elastic_strain<D>(mpm, i),
                                     mpm.state().history(i).eq_plastic_strain);
}

template <int D>
void to_mpm(const pd::System<D>& sys, const pd::Model<D>& model, mpm::Simulation<D>& mpm, Index i,
            PlasticTransfer transfer) {
  const std::optional<Mat<D>> F = bond_deformation_gradient<D>(sys, i);
  const auto* plastic = dynamic_cast<const pd::LpsPlastic<D>*>(&model);
  mpm::PointHistory h = mpm.state().history(i);
  if (transfer == PlasticTransfer::elastic_state && F && plastic)
    if (const std::optional<Mat<3>> eps_e = elastic_strain_from_pd<D>(sys, *plastic, i)) {
      h.plastic_strain.setZero();
      h.plastic_strain.topLeftCorner<D, D>() = mpm::polar_log<D>(*F).log_U - eps_e->topLeftCorner<D, D>();
      if constexpr (D == 2) h.plastic_strain(2, 2) = -(h.plastic_strain(0, 0) + h.plastic_strain(1, 1));
      h.eq_plastic_strain = plastic->committed_eq_plastic_strain(i);
      mpm.set_state(i, *F, h);
      return;
    }
  // strain, or the bonds do not determine the elastic strain
  if constexpr (D >= 2)
    if (plastic)
      if (const auto fitted = plastic_state_from_pd<D>(sys, *plastic, i)) h = *fitted;
  mpm.set_state(i, F.value_or(mpm.state().F.get(i)), h);
}

template std::optional<Mat<2>> bond_deformation_gradient<2>(const pd::System<2>&, Index);
template std::optional<Mat<3>> bond_deformation_gradient<3>(const pd::System<3>&, Index);
template void to_pd<2>(const mpm::Simulation<2>&, const pd::System<2>&, pd::Model<2>&, Index);
template void to_pd<3>(const mpm::Simulation<3>&, const pd::System<3>&, pd::Model<3>&, Index);
template Mat<3> grid_elastic_strain<2>(const mpm::Simulation<2>&, Index);
template Mat<3> grid_elastic_strain<3>(const mpm::Simulation<3>&, Index);
template void to_pd_elastic_state<2>(const mpm::Simulation<2>&, const pd::System<2>&, pd::Model<2>&, Index);
template void to_pd_elastic_state<3>(const mpm::Simulation<3>&, const pd::System<3>&, pd::Model<3>&, Index);
template void to_mpm<2>(const pd::System<2>&, const pd::Model<2>&, mpm::Simulation<2>&, Index, PlasticTransfer);
template void to_mpm<3>(const pd::System<3>&, const pd::Model<3>&, mpm::Simulation<3>&, Index, PlasticTransfer);

}  // namespace pdmpm::hybrid
