#include "solver/pd/constants.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pdmpm::pd {
namespace {

constexpr double pi = std::numbers::pi;

// Laterally confined 1D is an MPM setting: the scene parser gives PD scenes only the others.
[[noreturn]] void not_a_pd_setting() {
  throw std::invalid_argument("PD models have no uniaxial_strain setting (a 1D PD bar is uniaxial stress)");
}

// ∫₀¹ qⁿ e^{−q} dq = n! (1 − e^{−1} Σ_{k≤n} 1/k!)
double exponential_unit_moment(int n) {
  double fact = 1.0, partial = 0.0, kfact = 1.0;
  for (int k = 0; k <= n; ++k) {
    if (k > 0) kfact *= k;
    partial += 1.0 / kfact;
  }
  for (int k = 2; k <= n; ++k) fact *= k;
  return fact * (1.0 - std::exp(-1.0) * partial);
}

// J_n = ∫₀¹ qⁿ e^{−q²} dq, J_n = ((n−1)/2) J_{n−2} − e^{−1}/2.
double gaussian_unit_moment(int n) {
  if (n == 0) return 0.5 * std::sqrt(pi) * std::erf(1.0);
  if (n == 1) return 0.5 * (1.0 - std::exp(-1.0));
  return 0.5 * (n - 1) * gaussian_unit_moment(n - 2) - 0.5 * std::exp(-1.0);
}

}  // namespace

double influence_moment(Influence w, int n, double delta) {
  const double k = n + 1.0;
  double unit = 0.0;  // ∫₀¹ ω(q) qⁿ dq
  switch (w) {
    case Influence::constant:
      unit = 1.0 / k;
      break;
    case Influence::triangular:
      unit = 1.0 / k - 1.0 / (k + 1.0);
      break;
    case Influence::quadratic:
      unit = 1.0 / k - 2.0 / (k + 2.0) + 1.0 / (k + 4.0);
      break;
    case Influence::semi_elliptical:
      unit = 1.0 / k - 1.0 / (k + 2.0);
      break;
    case Influence::exponential:
      unit = exponential_unit_moment(n);
      break;
    case Influence::gaussian:
      unit = gaussian_unit_moment(n);
      break;
    case Influence::inverse_distance:  // ω = δ/r
      unit = 1.0 / n;
      break;
  }
  return unit * std::pow(delta, k);
}

double pmb_micromodulus(Influence w, core::Setting s, const core::Elastic& m, double delta, double measure) {
  switch (s) {
    case core::Setting::bar1d:
      return m.E / (measure * influence_moment(w, 1, delta));
    case core::Setting::plane_stress:
      return 2.0 * m.E / ((1.0 - m.nu) * pi * measure * influence_moment(w, 2, delta));
    case core::Setting::plane_strain:
      return 2.0 * m.E / ((1.0 + m.nu) * (1.0 - 2.0 * m.nu) * pi * measure * influence_moment(w, 2, delta));
    case core::Setting::solid3d:
      return 3.0 * m.E / (2.0 * pi * (1.0 - 2.0 * m.nu) * influence_moment(w, 3, delta));
    case core::Setting::uniaxial_strain:
      break;
  }
  not_a_pd_setting();
}

double lps_weighted_volume(Influence w, core::Setting s, double delta, double measure) {
  switch (s) {
    case core::Setting::bar1d:
      return 2.0 * measure * influence_moment(w, 2, delta);
    case core::Setting::plane_stress:
    case core::Setting::plane_strain:
      return 2.0 * pi * measure * influence_moment(w, 3, delta);
    case core::Setting::solid3d:
      return 4.0 * pi * influence_moment(w, 4, delta);
    case core::Setting::uniaxial_strain:
      break;
  }
  not_a_pd_setting();
}

double critical_stretch(Influence w, core::Setting s, const core::Elastic& m, double fracture_energy, double delta,
                        double measure) {
  const double c = pmb_micromodulus(w, s, m, delta, measure);
  switch (s) {
    case core::Setting::bar1d:
      return std::sqrt(2.0 * fracture_energy / (c * measure * influence_moment(w, 2, delta)));
    case core::Setting::plane_stress:
    case core::Setting::plane_strain:
      return std::sqrt(fracture_energy / (c * measure * influence_moment(w, 3, delta)));
    case core::Setting::solid3d:
      return std::sqrt(2.0 * fracture_energy / (pi * c * influence_moment(w, 4, delta)));
    case core::Setting::uniaxial_strain:
      break;
  }
  not_a_pd_setting();
}

LpsCoefficients lps_coefficients(core::Setting s, const core::Elastic& m) {
  const double G = m.shear();
  switch (s) {
    case core::Setting::bar1d:
      return {0.0, m.E, 0.0, 0.0, 1};
    case core::Setting::plane_stress:
    case core::Setting::plane_strain: {
      const double k2 = m.bulk_2d(s);
      return {2.0 * (k2 - 2.0 * G), 8.0 * G, k2, 0.5, 2};
    }
    case core::Setting::solid3d: {
      const double K = m.bulk();
      return {3.0 * K - 5.0 * G, 15.0 * G, K, 1.0 / 3.0, 3};
    }
    case core::Setting::uniaxial_strain:
      break;
  }
  not_a_pd_setting();
}

MadenciOterkus madenci_oterkus(core::Setting s, const core::Elastic& m, double delta, double measure) {
  const double mu = m.shear();
  switch (s) {
    case core::Setting::bar1d:
      return {0.0, m.E / (2.0 * measure * std::pow(delta, 3)), 1.0 / (2.0 * measure * delta * delta)};
    case core::Setting::plane_stress:
    case core::Setting::plane_strain: {
      const double kappa = m.bulk_2d(s);
      return {0.5 * (kappa - 2.0 * mu), 6.0 * mu / (pi * measure * std::pow(delta, 4)),
              2.0 / (pi * measure * std::pow(delta, 3))};
    }
    case core::Setting::solid3d:
      return {0.5 * (m.bulk() - 5.0 * mu / 3.0), 15.0 * mu / (2.0 * pi * std::pow(delta, 5)),
              9.0 / (4.0 * pi * std::pow(delta, 4))};
    case core::Setting::uniaxial_strain:
      break;
  }
  not_a_pd_setting();
}

}  // namespace pdmpm::pd
