#include "verification/support/regression_cases.hpp"

#include <cmath>

#include "solver/pd/model.hpp"
#include "verification/support/patch_check.hpp"
#include "verification/support/pd_fixtures.hpp"

namespace pdmpm::test::regression {

std::string Case::group() const {
  return "/" + model + "/" + std::string(name(setting)) + "/" + std::string(name(influence));
}

std::vector<Case> cases() {
  std::vector<Case> out;
  for (core::Setting s : {core::Setting::bar1d, core::Setting::plane_stress, core::Setting::plane_strain, core::Setting::solid3d})
    for (const auto& m : pd::model_names())
      for (pd::Influence w : pd::all_influences) out.push_back({m, s, w});
  return out;
}

std::string describe() {
  return "Block of 14 (1D), 9 x 9 (2D) or 6 x 6 x 6 (3D) sites, dx = 1 mm, m = 3.015, partial volume seed001, "
         "E = 200 GPa, rho = 7850, nu = 0.25 (PMB; 1/3 in plane stress) or 0.3 (LPS), h = 1 mm, A = 1 mm^2; bonds "
         "crossing the plane x = 3.5 mm (1D: 6.5 mm) with midpoint y < 4 mm cut before initialise; "
         "u_a = 1e-3 dx [sin(0.9 y0 + 0.3 y1 + 0.5 a) + 0.2 cos(0.7 y_(a+1) - 0.4 y_(a+2)) + 0.05 y_a y_(a+1)], "
         "y = x/dx (indices mod D). Plastic models: yield stress 1 MPa, E_t = 2 GPa, isotropy corrected.";
}

namespace {

template <int D>
Result compute_dim(const Case& c) {
  BlockSpec spec;
  spec.sites = D == 1 ? 14 : D == 2 ? 9 : 6;
  spec.spacing = 1e-3;
  spec.setting = c.setting;
  spec.influence = c.influence;
  spec.measure = default_measure(c.setting);
  spec.material = {200e9, pd::model_info(c.model).fixed_poisson(c.setting).value_or(0.3), 7850.0};
  auto sys = make_block<D>(spec);
  auto& p = sys.particles;
  const double dx = spec.spacing;
  // Partial edge crack: cut bonds crossing x = x_c whose midpoint lies at y < 4 mm.
  const double xc = (D == 1 ? 6.5 : 3.5) * dx;
  Result r;
  for (Index i = 0; i < sys.n_real(); ++i)
    for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b) {
      const Vec<D> xj = p.x0[sys.families.neighbor[b]];
      const bool crosses = (p.x0[i][0] - xc) * (xj[0] - xc) < 0.0;
      const bool on_crack = D == 1 || 0.5 * (p.x0[i][1 % D] + xj[1 % D]) < 4.0 * dx;
      if (crosses && on_crack) sys.bonds.cut(b), ++r.broken_bond_sides;
    }
  if (pd::model_info(c.model).plastic) {
    // Yield at 1 MPa (the displacement field strains to ~1e-3): the return mapping is in the gold.
    sys.hardening = core::J2Hardening{1e6, 2e9};
    sys.isotropic_deviatoric = true;
  }
  auto model = pd::make_model<D>(c.model);
  model->initialise(sys);
  for (Index i = 0; i < p.size(); ++i) {
    const Vec<D> y = p.x0[i] / dx;
    for (int a = 0; a < D; ++a)
      p.u[i][a] = 1e-3 * dx *
                  (std::sin(0.9 * y[0] + 0.3 * y[1 % D] + 0.5 * a) + 0.2 * std::cos(0.7 * y[(a + 1) % D] - 0.4 * y[(a + 2) % D]) +
                   0.05 * y[a] * y[(a + 1) % D]);
  }
  std::vector<double> W(sys.n_real());
  pd::ForceRequest req;
  req.energy = &W;
  model->compute_forces(sys, req);
  std::vector<double> theta;
  model->dilatation(sys, theta);
  r.particles = sys.n_real();
  r.dimension = D;
  for (Index i = 0; i < sys.n_real(); ++i)
    for (int a = 0; a < D; ++a) r.force.push_back(p.f[i][a]);
  r.energy = W;
  r.dilatation = theta;
  return r;
}

}  // namespace

Result compute(const Case& c) {
  switch (c.dimension()) {
    case 1: return compute_dim<1>(c);
    case 2: return compute_dim<2>(c);
    default: return compute_dim<3>(c);
  }
}

}  // namespace pdmpm::test::regression
