#include "solver/pd/constants_quadrature.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <numbers>
#include <string>

#include "solver/pd/constants.hpp"

namespace pdmpm::pd::quadrature {
namespace {

constexpr double pi = std::numbers::pi;

// GSL reports errors through a process-wide handler that aborts by default.
// While one of our integrals runs, a handler that only records the message is
// installed; the caller turns the returned status into an exception.
thread_local std::string gsl_message;
thread_local int handler_depth = 0;

void record_gsl_error(const char* reason, const char* file, int line, int gsl_errno) {
  gsl_message = std::string(gsl_strerror(gsl_errno)) + ": " + (reason ? reason : "") + " (" + (file ? file : "?") +
                ":" + std::to_string(line) + ")";
}

class RecordingHandler {
 public:
  RecordingHandler() {
    if (handler_depth++ == 0) previous_ = gsl_set_error_handler(&record_gsl_error);
  }
  ~RecordingHandler() {
    if (--handler_depth == 0) gsl_set_error_handler(previous_);
  }
  RecordingHandler(const RecordingHandler&) = delete;
  RecordingHandler& operator=(const RecordingHandler&) = delete;

 private:
  gsl_error_handler_t* previous_ = nullptr;
};

// An exception must not unwind through GSL's C frames: the trampoline catches
// it, returns 0 so GSL finishes quickly, and integrate() rethrows it.
struct Callback {
  const std::function<double(double)>* f;
  std::exception_ptr error;
};

double trampoline(double x, void* data) {
  auto* cb = static_cast<Callback*>(data);
  if (cb->error) return 0.0;
  try {
    return (*cb->f)(x);
  } catch (...) {
    cb->error = std::current_exception();
    return 0.0;
  }
}

struct WorkspaceDeleter {
  void operator()(gsl_integration_workspace* w) const { gsl_integration_workspace_free(w); }
};

// Integrates an inner integral over [a, b]. The outer rule sums inner values,
// so the inner errors add at most (b − a)·max(inner error) to the outer estimate.
Estimate integrate_nested(const std::function<Estimate(double)>& inner, double a, double b, const Options& opt) {
  double worst = 0.0;
  const Estimate outer = integrate(
      [&](double x) {
        const Estimate e = inner(x);
        worst = std::max(worst, e.abserr);
        return e.value;
      },
      a, b, opt);
  return {outer.value, outer.abserr + std::abs(b - a) * worst};
}

Estimate scaled(const Estimate& e, double k) { return {k * e.value, std::abs(k) * e.abserr}; }

double normal_strain(const Strain& eps, const Eigen::Vector3d& n) { return n.dot(eps * n); }

}  // namespace

double Estimate::relerr() const { return value != 0.0 ? abserr / std::abs(value) : abserr; }

Estimate integrate(const std::function<double(double)>& f, double a, double b, const Options& opt) {
  RecordingHandler handler;
  std::unique_ptr<gsl_integration_workspace, WorkspaceDeleter> ws(gsl_integration_workspace_alloc(opt.limit));
  if (!ws)
    throw QuadratureError("quadrature: cannot allocate a GSL workspace of " + std::to_string(opt.limit) + " intervals");
  Callback cb{&f, nullptr};
  gsl_function F{&trampoline, &cb};
  double result = 0.0, abserr = 0.0;
  gsl_message.clear();
  const int status = gsl_integration_qags(&F, a, b, opt.epsabs, opt.epsrel, opt.limit, ws.get(), &result, &abserr);
  if (cb.error) std::rethrow_exception(cb.error);
  if (status != GSL_SUCCESS)
    throw QuadratureError("quadrature on [" + std::to_string(a) + ", " + std::to_string(b) +
                          "] failed: " + (gsl_message.empty() ? std::string(gsl_strerror(status)) : gsl_message));
  if (!std::isfinite(result) || !std::isfinite(abserr))
    throw QuadratureError("quadrature on [" + std::to_string(a) + ", " + std::to_string(b) +
                          "] gave a non-finite result");
  return {result, abserr};
}

Estimate integrate_horizon(core::Setting s, double delta, double measure, const HorizonIntegrand& f, const Options& opt) {
  using Eigen::Vector3d;
  // opt.epsabs is meant for the final integral: remove the measure, and give each
  // inner level its share so the inner errors summed by the outer rule stay ≤ epsabs.
  auto level = [&](double share) {
    Options o = opt;
    o.epsabs = opt.epsabs / (std::abs(measure) * share);
    return o;
  };
  switch (dimension(s)) {
    case 1: {
      // Both half-lines separately: |x| has a kink at 0 that would slow QAGS down.
      const Options o = level(2.0);
      Estimate sum{0.0, 0.0};
      for (double sign : {1.0, -1.0}) {
        const Vector3d n(sign, 0.0, 0.0);
        const Estimate e = integrate([&](double r) { return f(r, n); }, 0.0, delta, o);
        sum.value += e.value;
        sum.abserr += e.abserr;
      }
      return scaled(sum, measure);
    }
    case 2: {
      const Options outer = level(1.0), inner = level(2.0 * pi);
      const Estimate e = integrate_nested(
          [&](double phi) {
            const Vector3d n(std::cos(phi), std::sin(phi), 0.0);
            return integrate([&](double r) { return f(r, n) * r; }, 0.0, delta, inner);
          },
          0.0, 2.0 * pi, outer);
      return scaled(e, measure);
    }
    default: {
      const Options outer = level(1.0), middle = level(2.0 * pi), inner = level(2.0 * pi * pi);
      const Estimate e = integrate_nested(
          [&](double phi) {
            return integrate_nested(
                [&](double theta) {
                  const double st = std::sin(theta);
                  const Vector3d n(st * std::cos(phi), st * std::sin(phi), std::cos(theta));
                  return scaled(integrate([&](double r) { return f(r, n) * r * r; }, 0.0, delta, inner), st);
                },
                0.0, pi, middle);
          },
          0.0, 2.0 * pi, outer);
      return scaled(e, measure);  // measure is 1 in 3D
    }
  }
}

Strain isotropic_strain(core::Setting s, double stretch) {
  Strain eps = Strain::Zero();
  for (int a = 0; a < dimension(s); ++a) eps(a, a) = stretch;
  return eps;
}

Estimate pmb_energy_density(Influence w, core::Setting s, double c, const Strain& eps, double delta, double measure,
                            const Options& opt) {
  // Bond energy ½ c ω s² |ξ| per unit volume², half of it assigned to each end.
  return integrate_horizon(
      s, delta, measure,
      [&](double r, const Eigen::Vector3d& n) {
        const double sn = normal_strain(eps, n);
        return 0.25 * c * influence(w, r, delta) * sn * sn * r;
      },
      opt);
}

Estimate pmb_micromodulus(Influence w, core::Setting s, const core::Elastic& m, double delta, double measure, const Options& opt) {
  // W_PD is linear in c and W_classical = k s²; with c = 1 and s = 1 the ratio is c.
  const Estimate unit = pmb_energy_density(w, s, 1.0, isotropic_strain(s, 1.0), delta, measure, opt);
  const double c = m.isotropic_energy_coefficient(s) / unit.value;
  return {c, c * unit.relerr()};
}

Estimate lps_weighted_volume(Influence w, core::Setting s, double delta, double measure, const Options& opt) {
  return integrate_horizon(
      s, delta, measure, [&](double r, const Eigen::Vector3d&) { return influence(w, r, delta) * r * r; }, opt);
}

Estimate lps_energy_density(Influence w, core::Setting s, const core::Elastic& mat, double m, const Strain& eps, double delta,
                            double measure, const Options& opt) {
  const LpsCoefficients k = lps_coefficients(s, mat);
  // θ can vanish by cancellation between directions (pure shear); its accuracy
  // is then measured against the strain's size, ‖ε‖·m, not against θ itself.
  Options theta_opt = opt;
  theta_opt.epsabs = std::max(opt.epsabs, opt.epsrel * eps.norm() * m);
  const Estimate sum_theta = integrate_horizon(
      s, delta, measure,
      [&](double r, const Eigen::Vector3d& n) {
        const double e = r * normal_strain(eps, n);
        return influence(w, r, delta) * r * e;
      },
      theta_opt);
  const double theta = k.d * sum_theta.value / m;
  const double dtheta = k.d * sum_theta.abserr / m;
  // The deviatoric part vanishes (to rounding) under isotropic expansion, so
  // its accuracy too is measured against the strain's size, ‖ε‖²·m.
  Options dev_opt = opt;
  dev_opt.epsabs = std::max(opt.epsabs, opt.epsrel * eps.squaredNorm() * m);
  const Estimate dev = integrate_horizon(
      s, delta, measure,
      [&](double r, const Eigen::Vector3d& n) {
        const double ed = r * normal_strain(eps, n) - k.gamma * theta * r;
        return influence(w, r, delta) * ed * ed;
      },
      dev_opt);
  const double W = 0.5 * k.kappa * theta * theta + 0.5 * k.B / m * dev.value;
  // First-order propagation of the θ error; ∫ω|e_d| r dV ≤ sqrt(∫ω e_d² dV · m) (Cauchy–Schwarz).
  const double err = k.kappa * std::abs(theta) * dtheta + 0.5 * k.B / m * dev.abserr +
                     k.B / m * k.gamma * dtheta * std::sqrt(std::abs(dev.value) * m);
  return {W, err};
}

Estimate fracture_energy(Influence w, core::Setting s, double c, double s0, double delta, double measure,
                         const Options& opt) {
  // A point at distance z below the crack plane; a bond of length ξ at angle φ
  // from the plane's normal crosses the plane iff ξ cos φ > z. Each crossing
  // bond stores ½ c ω s₀² ξ per unit volume² when it breaks; G₀ is their sum
  // per unit crack area. z ∈ (0, δ), ξ ∈ (z, δ), |φ| < acos(z/ξ).
  auto bond_energy = [&](double xi) { return 0.5 * c * influence(w, xi, delta) * s0 * s0 * xi; };
  auto max_angle = [](double z, double xi) { return std::acos(std::clamp(z / xi, -1.0, 1.0)); };
  switch (dimension(s)) {
    case 1:
      // Bar of area A: volumes A dz and A dξ per unit crack area A.
      return scaled(integrate_nested(
                        [&](double z) { return integrate([&](double xi) { return bond_energy(xi); }, z, delta, opt); },
                        0.0, delta, opt),
                    measure);
    case 2:
      // Plate of thickness h: volumes h dA per unit crack area h·(unit length).
      return scaled(integrate_nested(
                        [&](double z) {
                          return integrate_nested(
                              [&](double xi) {
                                const double a = max_angle(z, xi);
                                return scaled(integrate([&](double) { return bond_energy(xi); }, -a, a, opt), xi);
                              },
                              z, delta, opt);
                        },
                        0.0, delta, opt),
                    measure);
    default:
      // The azimuth about the normal contributes 2π (the integrand does not depend on it).
      return integrate_nested(
          [&](double z) {
            return integrate_nested(
                [&](double xi) {
                  const double a = max_angle(z, xi);
                  return scaled(integrate([&](double phi) { return std::sin(phi) * bond_energy(xi); }, 0.0, a, opt),
                                2.0 * pi * xi * xi);
                },
                z, delta, opt);
          },
          0.0, delta, opt);
  }
}

Estimate critical_stretch(Influence w, core::Setting s, const core::Elastic& m, double G0, double delta, double measure,
                          const Options& opt) {
  const Estimate c = pmb_micromodulus(w, s, m, delta, measure, opt);
  // G₀ ∝ s₀², so s₀ = sqrt(G₀ / G₀(s₀ = 1)).
  const Estimate unit = fracture_energy(w, s, c.value, 1.0, delta, measure, opt);
  const double s0 = std::sqrt(G0 / unit.value);
  return {s0, s0 * 0.5 * (c.relerr() + unit.relerr())};
}

}  // namespace pdmpm::pd::quadrature
