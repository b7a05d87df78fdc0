#include "solver/pd/lps.hpp"

#include <cmath>

#include "solver/pd/bond_kinematics.hpp"
#include "solver/pd/weighted_volume.hpp"

namespace pdmpm::pd {

template <int D>
std::pair<double, double> Lps<D>::poisson_range(Setting s) const {
  // Plane stress needs ν < 1 for κ₂ and ν < 1/2 for a 3D-consistent material;
  // elsewhere K = E / (3(1 − 2ν)) must stay finite. ν = 1/2 itself is excluded.
  (void)s;
  return {-1.0, 0.5};
}

template <int D>
void Lps<D>::initialise(const System<D>& sys) {
  k_ = lps_coefficients(sys.setting, sys.material);
  m_ = weighted_volumes(sys);
  theta_.assign(sys.particles.size(), 0.0);
}

template <int D>
std::int64_t Lps<D>::compute_forces(System<D>& sys, const ForceRequest& req) {
  auto& p = sys.particles;
  const auto& fam = sys.families;
  const auto& t = sys.table;
  const Index n = p.n_real;
  const double s0 = req.critical_stretch;
  const bool breaking = req.break_bonds, after = req.break_after_force;
  std::uint8_t* broken = sys.broken.data();
  const Index* nbr = fam.neighbor.data();
  const std::uint16_t* shape = fam.shape.data();
  const Vec<D>* u = p.u.data();
  const double* vol = p.volume.data();
  const double* m = m_.data();
  double* theta = theta_.data();
  std::int64_t newly_broken = 0;

  // Pass 1: break bonds, then dilatation over the bonds still intact.
#pragma omp parallel for schedule(static) reduction(+ : newly_broken)
  for (Index i = 0; i < n; ++i) {
    double sum = 0.0;
    const Vec<D> ui = u[i];
    for (BondIndex b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
      if (broken[b]) continue;
      const Index j = nbr[b];
      const int k = shape[b];
      const double L = t.length[k];
      const auto bond = deform<D>(t.xi[k], L, u[j] - ui);
      if (breaking && !after && bond.e >= s0 * L) {
        broken[b] = 1;
        ++newly_broken;
        continue;
      }
      sum += t.weight[k] * L * bond.e * vol[j];
    }
    theta[i] = m[i] > 0.0 ? k_.d * sum / m[i] : 0.0;
  }
  for (Index g = 0; g < p.n_ghost(); ++g) theta[n + g] = theta[p.ghost_owner[g]];

  // Pass 2: pair forces (t_ij + t_ji) β V_j M_ij.
  const double A = k_.A, B = k_.B;
  std::vector<double>* energy = req.energy;
#pragma omp parallel for schedule(static) reduction(+ : newly_broken)
  for (Index i = 0; i < n; ++i) {
    Vec<D> fi = Vec<D>::Zero();
    double dev = 0.0;
    const Vec<D> ui = u[i];
    const double inv_mi = m[i] > 0.0 ? 1.0 / m[i] : 0.0;
    const double th_i = theta[i];
    for (BondIndex b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
      if (broken[b]) continue;
      const Index j = nbr[b];
      const int k = shape[b];
      const double L = t.length[k];
      const auto bond = deform<D>(t.xi[k], L, u[j] - ui);
      const double inv_mj = m[j] > 0.0 ? 1.0 / m[j] : 0.0;
      const double t_ij = (A * th_i * L + B * bond.e) * inv_mi;
      const double t_ji = (A * theta[j] * L + B * bond.e) * inv_mj;
      fi += ((t_ij + t_ji) * t.weight[k] * vol[j] / bond.l) * bond.y;
      if (energy) {
        const double ed = bond.e - k_.gamma * th_i * L;
        dev += t.weight[k] * ed * ed * vol[j];
      }
      // i's side only, which no other particle reads in this pass.
      if (breaking && after && bond.e > s0 * L) {
        broken[b] = 1;
        ++newly_broken;
      }
    }
    p.f[i] = fi;
    if (energy) (*energy)[i] = 0.5 * k_.kappa * th_i * th_i + 0.5 * B * inv_mi * dev;
  }
  return newly_broken;
}

template <int D>
void Lps<D>::dilatation(const System<D>& sys, std::vector<double>& theta) const {
  theta.assign(sys.particles.n_real, 0.0);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < sys.particles.n_real; ++i) theta[i] = dilatation_of(sys, i, m_[i]);
}

template <int D>
double Lps<D>::stiffness_row_sum(const System<D>& sys, Index i) const {
  // Bond stiffness per unit extension: the direct term B ω β (1/m_i + 1/m_j)
  // plus a bound on the dilatation coupling, d|A| ω β (1/m_i + 1/m_j).
  const auto& fam = sys.families;
  const double coef = k_.B + k_.d * std::abs(k_.A);
  double sum = 0.0;
  for (BondIndex b = fam.begin(i); b < fam.end(i); ++b) {
    if (sys.broken[b]) continue;
    const Index j = fam.neighbor[b];
    const int k = fam.shape[b];
    const double inv = (m_[i] > 0 ? 1.0 / m_[i] : 0.0) + (m_[j] > 0 ? 1.0 / m_[j] : 0.0);
    sum += coef * inv * sys.table.weight[k] * sys.particles.volume[j];
  }
  return sum;
}

template class Lps<1>;
template class Lps<2>;
template class Lps<3>;

}  // namespace pdmpm::pd
