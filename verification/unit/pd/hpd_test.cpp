// Stabilized hybrid PD (solver/pd/hpd.hpp): the 1D law is PMB; affine fields give no interior
// force, and the stress of the forces (their virial) and the energy density are the constitutive
// ones for any ν; the checkerboard mode is resisted (a particle-centred correspondence gradient
// is blind to it); long waves travel at the classical speeds; cut bonds decouple the body.
#include "solver/pd/hpd.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "solver/pd/pmb.hpp"
#include "verification/support/hpd_checkerboard.hpp"
#include "verification/support/pd_fixtures.hpp"

namespace pdmpm::pd {
namespace {

// 3D blocks use δ = 2.015 Δx: a 3.015 Δx family stores ~6000 sub-horizon slots per particle
// (~0.4 MB), too many for a unit test's 10⁴ particles; 2D keeps the default 3.015 Δx.
template <int D>
System<D> block(core::Setting s, double nu, int sites, HpdLaw law = HpdLaw::linear_elastic) {
  test::BlockSpec spec;
  spec.sites = sites;
  if (D == 3 && law == HpdLaw::linear_elastic) spec.horizon_ratio = 2.015;
  spec.setting = s;
  spec.material = {200e9, nu, 7850.0};
  spec.measure = D == 3 ? 1.0 : 1e-3;
  auto sys = test::make_block<D>(spec);
  sys.hpd.law = law;
  return sys;
}

template <int D>
double max_norm(const std::vector<Vec<D>>& v, Index n) {
  double m = 0.0;
  for (Index i = 0; i < n; ++i) m = std::max(m, v[i].norm());
  return m;
}

// Saint Venant–Kirchhoff first Piola stress F S(Ẽ) of the setting (what HPD must reproduce).
template <int D>
Mat<D> svk_stress(const Mat<D>& F, const core::Elastic& m, core::Setting s, double& psi) {
  const Mat<D> e = 0.5 * (F.transpose() * F - Mat<D>::Identity());
  const double lambda = s == core::Setting::plane_stress ? m.E * m.nu / (1.0 - m.nu * m.nu) : m.lame();
  const Mat<D> S = lambda * e.trace() * Mat<D>::Identity() + 2.0 * m.shear() * e;
  psi = 0.5 * (S.array() * e.array()).sum();
  return F * S;
}

template <int D>
void axial_equals_pmb(core::Setting s) {
  auto sys = block<D>(s, 0.25, D == 2 ? 12 : 8, HpdLaw::axial_1d);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto& x : sys.particles.u)
    for (int a = 0; a < D; ++a) x[a] = 2e-5 * u(rng);  // strains up to ~4 %: the nonlinear stretch matters
  const Index n = sys.n_real();
  std::vector<double> w_pmb(n), w_hpd(n);
  Pmb<D> pmb;
  pmb.initialise(sys);
  ForceRequest req;
  req.energy = &w_pmb;
  pmb.compute_forces(sys, req);
  const auto f_pmb = sys.particles.f;
  Hpd<D> hpd;
  hpd.initialise(sys);
  req.energy = &w_hpd;
  hpd.compute_forces(sys, req);
  const double scale = max_norm<D>(f_pmb, n);
  double df = 0.0, dw = 0.0, wmax = 0.0;
  for (Index i = 0; i < n; ++i) {
    df = std::max(df, (sys.particles.f[i] - f_pmb[i]).norm());
    dw = std::max(dw, std::abs(w_hpd[i] - w_pmb[i]));
    wmax = std::max(wmax, w_pmb[i]);
  }
  // 1e-13: the same bond terms, summed in another order (PMB's kernel adds SIMD lanes).
  EXPECT_LT(df / scale, 1e-13) << name(s);
  EXPECT_LT(dw / wmax, 1e-13) << name(s);
}

TEST(Hpd, Axial1dEqualsPmbOnARandomDeformation) {
  axial_equals_pmb<2>(core::Setting::plane_stress);
  axial_equals_pmb<2>(core::Setting::plane_strain);
  axial_equals_pmb<3>(core::Setting::solid3d);
}

// An affine field u = G x: (a) no force on particles 2δ inside; (b) the virial of the forces,
// −(1/V) Σ_k V_k f_k ⊗ x_k (free body), equals the constitutive stress F S; (c) every particle's
// energy density and bond-averaged stress are the constitutive ones, at the boundary too.
template <int D>
void affine_patch(core::Setting s, double nu) {
  auto sys = block<D>(s, nu, D == 2 ? 16 : 11);
  Mat<D> G;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) G(a, b) = 1e-4 * (1.0 + a + 2.0 * b) * (a == b ? 1.0 : -0.5);
  const Index n = sys.n_real();
  for (Index i = 0; i < n; ++i) sys.particles.u[i] = G * sys.particles.x0[i];
  Hpd<D> hpd;
  hpd.initialise(sys);
  std::vector<double> W(n);
  ForceRequest req;
  req.energy = &W;
  hpd.compute_forces(sys, req);
  double psi = 0.0;
  const Mat<D> P = svk_stress<D>(Mat<D>::Identity() + G, sys.material, s, psi);
  const double stress = P.norm(), force_scale = stress / sys.spacing();
  double interior = 0.0, volume = 0.0, dw = 0.0, dstress = 0.0;
  Mat<D> virial = Mat<D>::Zero();
  for (Index i = 0; i < n; ++i) {
    const double V = sys.particles.volume[i];
    if (test::distance_to_boundary(sys, i) >= 2.0 * sys.delta - 1e-12)
      interior = std::max(interior, sys.particles.f[i].norm());
    virial -= V * sys.particles.f[i] * sys.particles.x0[i].transpose();
    volume += V;
    dw = std::max(dw, std::abs(W[i] - psi));
    dstress = std::max(dstress, (hpd.bond_averaged_stress(sys, i) - P).norm());
  }
  virial /= volume;
  const std::string what = std::string(name(s)) + " ν = " + std::to_string(nu);
  // Round-off: each force is a sum of ~10³ (2D) to ~10⁴ (3D) terms of size σ/Δx that cancel.
  EXPECT_LT(interior / force_scale, 1e-11) << what;
  // The virial sums V f ⊗ x over the body (x up to 15 Δx): round-off of the boundary forces.
  EXPECT_LT((virial - P).norm() / stress, 1e-11) << what;
  // W and Σ a P: sums of ~10² bond terms of one value (partition of unity).
  EXPECT_LT(dw / psi, 1e-12) << what;
  EXPECT_LT(dstress / stress, 1e-12) << what;
}

TEST(Hpd, AffineFieldsGiveTheConstitutiveStressForAnyPoissonRatio) {
  for (double nu : {0.0, 0.25, 0.33, 0.45}) {
    affine_patch<2>(core::Setting::plane_stress, nu);
    affine_patch<2>(core::Setting::plane_strain, nu);
    affine_patch<3>(core::Setting::solid3d, nu);
  }
}

// Checkerboard u = a (−1)^(Σ lattice indices) e: the mean |f| over particles 2δ inside, for HPD
// and the correspondence evaluation, over LPS's (verification/support/hpd_checkerboard.hpp; the
// hpd gate records the same numbers for the report).
template <int D>
double checkerboard(core::Setting s) {
  const auto f = test::checkerboard_forces<D>(s, D == 2 ? 16 : 12, D == 2 ? 3.015 : 2.015);
  std::printf(
      "checkerboard %s: |f| / LPS's: HPD %.4f (stabilization 0: %.4f; plain fit, end weight 1: %.4f), correspondence "
      "%.2e\n",
      std::string(name(s)).c_str(), f.hpd, f.hpd_unstabilized, f.hpd_plain, f.correspondence);
  // The correspondence gradient is zero for this mode (even about every particle): no force,
  // to round-off of the sums (terms of size a·E/Δx² cancel).
  EXPECT_LT(f.correspondence, 1e-12) << name(s);
  return f.hpd;
}

// The forces are −(1/V_k) ∂E/∂u_k of the energy the model reports, with and without the fit-residual
// stabilisation (its force −G w_k r_k rests on the fit being a w-orthogonal projection): central
// differences of E = Σ V_i W_i on a random, non-affine deformation.
template <int D>
void forces_are_the_energy_gradient(core::Setting s, double stabilization) {
  auto sys = block<D>(s, 0.3, D == 2 ? 10 : 6);
  sys.hpd.stabilization = stabilization;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto& x : sys.particles.u)
    for (int a = 0; a < D; ++a) x[a] = 1e-6 * u(rng);
  const Index n = sys.n_real();
  Hpd<D> hpd;
  hpd.initialise(sys);
  std::vector<double> w(n);
  ForceRequest req;
  req.energy = &w;
  auto energy = [&] {
    hpd.compute_forces(sys, req);
    double e = 0.0;
    for (Index i = 0; i < n; ++i) e += sys.particles.volume[i] * w[i];
    return e;
  };
  energy();
  const auto f = sys.particles.f;
  const double scale = max_norm<D>(f, n);
  const double h = 1e-9;  // central difference: error O(h²) ≪ the check's 1e-6, round-off ~1e-16 E / h
  for (Index k : {Index{0}, n / 3, n / 2, n - 1})
    for (int a = 0; a < D; ++a) {
      const double keep = sys.particles.u[k][a];
      sys.particles.u[k][a] = keep + h;
      const double up = energy();
      sys.particles.u[k][a] = keep - h;
      const double down = energy();
      sys.particles.u[k][a] = keep;
      const double dE = (up - down) / (2.0 * h);
      EXPECT_NEAR(-dE / sys.particles.volume[k], f[k][a], 1e-6 * scale)
          << name(s) << " stabilization " << stabilization << " particle " << k << " axis " << a;
    }
}

TEST(Hpd, ForcesAreTheGradientOfTheEnergy) {
  for (double g : {0.0, 1.0}) {
    forces_are_the_energy_gradient<2>(core::Setting::plane_stress, g);
    forces_are_the_energy_gradient<3>(core::Setting::solid3d, g);
  }
}

// The mode's force scale is LPS's restoring force for it (a stable model of the same moduli);
// the issue asks ≥ 0.5 (measured with the defaults: 2D 0.91, 3D 0.65; the fit alone gives 3D 0.43).
TEST(Hpd, CheckerboardModeIsResisted) {
  EXPECT_GE(checkerboard<2>(core::Setting::plane_strain), 0.5);
  EXPECT_GE(checkerboard<3>(core::Setting::solid3d), 0.5);
}

// Long waves: u = a e cos(k (x − x_c)) on a block; at the centre particle (far from the boundary,
// which the force there does not see) f = −ρ ω² u gives ω(k), and ω/k → c as kδ → 0.
template <int D>
double wave_speed(core::Setting s, double nu, bool shear) {
  const int sites = D == 2 ? 15 : 11;  // the centre lies ≥ 2δ inside
  auto sys = block<D>(s, nu, sites);
  const double L = 200.0 * sys.spacing(), k = 2.0 * M_PI / L;  // kδ = 0.095
  const Index n = sys.n_real();
  const Vec<D> centre = Vec<D>::Constant(0.5 * (sites - 1) * sys.spacing());
  Index c = 0;
  for (Index i = 0; i < n; ++i)
    if ((sys.particles.x0[i] - centre).norm() < 1e-9) c = i;
  const double a = 1e-12;
  for (Index i = 0; i < n; ++i) {
    sys.particles.u[i] = Vec<D>::Zero();
    sys.particles.u[i][shear ? 1 : 0] = a * std::cos(k * (sys.particles.x0[i][0] - centre[0]));
  }
  Hpd<D> hpd;
  hpd.initialise(sys);
  ForceRequest req;
  hpd.compute_forces(sys, req);
  const double omega2 = -sys.particles.f[c][shear ? 1 : 0] / (sys.material.rho * a);
  return std::sqrt(omega2) / k;
}

TEST(Hpd, LongWavesTravelAtTheClassicalSpeeds) {
  for (double nu : {0.2, 0.4}) {
    const core::Elastic m{200e9, nu, 7850.0};
    const double cs = std::sqrt(m.shear() / m.rho);
    struct Case {
      core::Setting s;
      double cp;
    };
    for (const Case& cs_case : {Case{core::Setting::plane_stress, std::sqrt(m.E / (1.0 - nu * nu) / m.rho)},
                                Case{core::Setting::plane_strain, std::sqrt((m.lame() + 2.0 * m.shear()) / m.rho)},
                                Case{core::Setting::solid3d, std::sqrt((m.lame() + 2.0 * m.shear()) / m.rho)}}) {
      const bool three = cs_case.s == core::Setting::solid3d;
      const double p = three ? wave_speed<3>(cs_case.s, nu, false) : wave_speed<2>(cs_case.s, nu, false);
      const double sh = three ? wave_speed<3>(cs_case.s, nu, true) : wave_speed<2>(cs_case.s, nu, true);
      std::printf("waves %s ν = %.2f: c_p/c_p,classical − 1 = %.2e, c_s/c_s,classical − 1 = %.2e\n",
                  std::string(name(cs_case.s)).c_str(), nu, p / cs_case.cp - 1.0, sh / cs - 1.0);
      // 1 %: the gate; the nonlocal dispersion at kδ ≈ 0.1 is O((kδ)²) ≈ 1e-3.
      EXPECT_NEAR(p / cs_case.cp, 1.0, 0.01) << name(cs_case.s) << " ν = " << nu;
      EXPECT_NEAR(sh / cs, 1.0, 0.01) << name(cs_case.s) << " ν = " << nu;
    }
  }
}

// Cutting every bond across x = x_m separates the body: the sub-horizons are rebuilt without the
// points across the cut, so moving the right half rigidly (a large rotation and a translation)
// leaves every particle force-free (SVK energy: rotations cost nothing).
TEST(Hpd, CutBondsDecoupleTheTwoHalves) {
  auto sys = block<2>(core::Setting::plane_strain, 0.3, 14);
  const double xm = 6.5 * sys.spacing();
  Hpd<2> hpd;
  hpd.initialise(sys);
  for (Index i = 0; i < sys.n_real(); ++i)
    for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b) {
      const Index j = sys.families.neighbor[b];
      if ((sys.particles.x0[i][0] - xm) * (sys.particles.x0[j][0] - xm) < 0.0) sys.bonds.flags.trial[b] |= kBondBroken;
    }
  const Mat<2> R = Eigen::Rotation2Dd(0.3).toRotationMatrix();
  for (Index i = 0; i < sys.n_real(); ++i) {
    const Vec<2> x = sys.particles.x0[i];
    sys.particles.u[i] = x[0] > xm ? Vec<2>((R - Mat<2>::Identity()) * x + Vec<2>(1e-4, -3e-4)) : Vec<2>::Zero();
  }
  ForceRequest req;
  hpd.compute_forces(sys, req);
  // Scale: the force of a strain of 1 (E/Δx); 1e-12: round-off of sums with rotations of order 1.
  EXPECT_LT(max_norm<2>(sys.particles.f, sys.n_real()) / (sys.material.E / sys.spacing()), 1e-12);
  EXPECT_EQ(hpd.sub_horizon().n_axial, 0);
}

// A strip one particle wide: every sub-horizon is collinear, so every bond takes the axial
// fallback; a uniform stretch along the strip then gives its uniaxial-stress energy ½ E ε².
TEST(Hpd, CollinearSubHorizonsFallBackToTheAxialStrain) {
  System<2> sys;
  {
    test::BlockSpec spec;
    spec.sites = 12;
    spec.setting = core::Setting::plane_stress;
    spec.measure = 1e-3;
    sys = test::make_block<2>(spec);
  }
  // Keep the row y = 0 only: deactivate every bond that leaves it (particles stay, unbonded).
  for (Index i = 0; i < sys.n_real(); ++i)
    for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b) {
      const Index j = sys.families.neighbor[b];
      if (sys.particles.x0[i][1] != 0.0 || sys.particles.x0[j][1] != 0.0) sys.bonds.flags.trial[b] |= kBondCut;
    }
  Hpd<2> hpd;
  hpd.initialise(sys);
  Index live = 0;
  for (BondIndex b = 0; b < sys.families.n_bonds(); ++b) live += sys.bonds.live(b);
  EXPECT_EQ(hpd.sub_horizon().n_axial, live);
  const double eps = 1e-4;
  for (Index i = 0; i < sys.n_real(); ++i) sys.particles.u[i] = Vec<2>(eps * sys.particles.x0[i][0], 0.0);
  std::vector<double> W(sys.n_real());
  ForceRequest req;
  req.energy = &W;
  hpd.compute_forces(sys, req);
  const double green = eps + 0.5 * eps * eps;  // Ẽ_xx of the stretch
  for (Index i = 0; i < sys.n_real(); ++i)
    if (sys.particles.x0[i][1] == 0.0) {
      EXPECT_NEAR(W[i], 0.5 * sys.material.E * green * green, 1e-12 * W[i]);
    }
}

TEST(Hpd, TooSmallAHorizonIsRefused) {
  // δ = 1.2 Δx: the nearest-neighbour bond's sub-horizon holds its two ends only.
  EXPECT_NE(sub_horizon_shortfall(core::Stencil<2>::build(1.2), 3), "");
  EXPECT_EQ(sub_horizon_shortfall(core::Stencil<2>::build(1.5), 3), "");
  test::BlockSpec spec;
  spec.sites = 5;
  spec.horizon_ratio = 1.2;
  spec.setting = core::Setting::plane_strain;
  spec.partial_volume = PartialVolume::none;
  auto sys = test::make_block<2>(spec);
  Hpd<2> hpd;
  EXPECT_THROW(hpd.initialise(sys), std::invalid_argument);
}

}  // namespace
}  // namespace pdmpm::pd
