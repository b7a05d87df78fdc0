#include "solver/pd/pmb.hpp"

#include "solver/pd/bond_kinematics.hpp"
#include "solver/pd/constants.hpp"

namespace pdmpm::pd {

template <int D>
std::pair<double, double> Pmb<D>::poisson_range(Setting s) const {
  // A pair potential fixes ν (Cauchy relation): 1/4 in 3D and plane strain, 1/3 in plane stress.
  if (s == Setting::plane_stress) return {1.0 / 3.0, 1.0 / 3.0};
  if (s == Setting::bar1d) return {0.0, 0.5};  // ν plays no role in a bar
  return {0.25, 0.25};
}

template <int D>
void Pmb<D>::initialise(const System<D>& sys) {
  c_ = pmb_micromodulus(sys.influence, sys.setting, sys.material, sys.delta, sys.measure);
}

template <int D>
std::int64_t Pmb<D>::compute_forces(System<D>& sys, const ForceRequest& req) {
  auto& p = sys.particles;
  const auto& fam = sys.families;
  const auto& t = sys.table;
  const Index n = p.n_real;
  const double c = c_;
  const double s0 = req.critical_stretch;
  const bool breaking = req.break_bonds, after = req.break_after_force;
  std::vector<double>* energy = req.energy;
  std::uint8_t* broken = sys.broken.data();
  const Index* nbr = fam.neighbor.data();
  const std::uint16_t* shape = fam.shape.data();
  const Vec<D>* u = p.u.data();
  const double* vol = p.volume.data();
  std::int64_t newly_broken = 0;

#pragma omp parallel for schedule(static) reduction(+ : newly_broken)
  for (Index i = 0; i < n; ++i) {
    Vec<D> fi = Vec<D>::Zero();
    double wi = 0.0;
    const Vec<D> ui = u[i];
    for (BondIndex b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
      if (broken[b]) continue;
      const Index j = nbr[b];
      const int k = shape[b];
      const double L = t.length[k];
      const auto bond = deform<D>(t.xi[k], L, u[j] - ui);
      const double s = bond.e / L;
      if (breaking && !after && s >= s0) {
        broken[b] = 1;
        ++newly_broken;
        continue;
      }
      const double cw = c * t.weight[k] * vol[j];
      fi += (cw * s / bond.l) * bond.y;
      if (energy) wi += 0.25 * cw * s * s * L;  // ½ Σ_j (c ω s² |ξ| / 2) β V_j
      if (breaking && after && s > s0) {
        broken[b] = 1;
        ++newly_broken;
      }
    }
    p.f[i] = fi;
    if (energy) (*energy)[i] = wi;
  }
  return newly_broken;
}

template <int D>
double Pmb<D>::stiffness_row_sum(const System<D>& sys, Index i) const {
  // C_ij = c ω β / |ξ| for PMB (Silling & Askari 2005).
  const auto& fam = sys.families;
  double sum = 0.0;
  for (BondIndex b = fam.begin(i); b < fam.end(i); ++b) {
    if (sys.broken[b]) continue;
    const int k = fam.shape[b];
    sum += c_ * sys.table.weight[k] / sys.table.length[k] * sys.particles.volume[fam.neighbor[b]];
  }
  return sum;
}

template class Pmb<1>;
template class Pmb<2>;
template class Pmb<3>;

}  // namespace pdmpm::pd
