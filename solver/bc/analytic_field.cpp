#include "solver/bc/analytic_field.hpp"

#include <cmath>
#include <set>
#include <stdexcept>

#include "solver/analytic/spherical_wave.hpp"

namespace pdmpm::bc {
namespace {

const char* axes = "xyz";

template <int D>
class Affine final : public AnalyticField<D> {
 public:
  explicit Affine(const std::map<std::string, double>& p) {
    H_.setZero();
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) {
        const std::string key = std::string("h_") + axes[a] + axes[b];
        if (auto it = p.find(key); it != p.end()) H_(a, b) = it->second;
      }
  }
  void evaluate(const Vec<D>& x, double, Vec<D>& u, Vec<D>& v) const override {
    u = H_ * x;
    v.setZero();
  }

 private:
  Mat<D> H_;
};

template <int D>
class SphericalWaveField final : public AnalyticField<D> {
 public:
  SphericalWaveField(const std::map<std::string, double>& p, double cp) {
    w_.r0 = p.at("r0");
    w_.period = p.at("period");
    w_.amplitude = p.at("amplitude");
    w_.cp = cp;
  }
  void evaluate(const Vec<D>& x, double t, Vec<D>& u, Vec<D>& v) const override {
    const double r = x.norm();
    if (r == 0.0) {
      u.setZero();
      v.setZero();
      return;
    }
    u = (w_.radial_displacement(r, t) / r) * x;
    v = (w_.radial_velocity(r, t) / r) * x;
  }

 private:
  analytic::SphericalWave w_;
};

}  // namespace

std::vector<std::string> analytic_field_names() { return {"affine", "spherical_wave"}; }

void check_analytic_parameters(const std::string& name, const std::map<std::string, double>& p) {
  std::set<std::string> allowed;
  if (name == "affine") {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) allowed.insert(std::string("h_") + axes[a] + axes[b]);
  } else if (name == "spherical_wave") {
    allowed = {"r0", "period", "amplitude"};
    for (const auto& k : allowed) {
      auto it = p.find(k);
      if (it == p.end()) throw std::invalid_argument("spherical_wave needs parameter '" + k + "' (> 0)");
      if (!(it->second > 0.0)) throw std::invalid_argument("parameter '" + k + "' must be > 0");
    }
  }
  for (const auto& [k, v] : p)
    if (!allowed.count(k)) throw std::invalid_argument("unknown parameter '" + k + "' for " + name);
}

template <int D>
std::unique_ptr<AnalyticField<D>> make_analytic_field(const std::string& name, const std::map<std::string, double>& p,
                                                      const core::Elastic& material, core::Setting setting) {
  check_analytic_parameters(name, p);
  if (name == "affine") return std::make_unique<Affine<D>>(p);
  if (name == "spherical_wave")
    return std::make_unique<SphericalWaveField<D>>(p, std::sqrt(material.wave_modulus(setting) / material.rho));
  throw std::invalid_argument("unknown analytic field '" + name + "'");
}

template std::unique_ptr<AnalyticField<1>> make_analytic_field<1>(const std::string&, const std::map<std::string, double>&,
                                                                  const core::Elastic&, core::Setting);
template std::unique_ptr<AnalyticField<2>> make_analytic_field<2>(const std::string&, const std::map<std::string, double>&,
                                                                  const core::Elastic&, core::Setting);
template std::unique_ptr<AnalyticField<3>> make_analytic_field<3>(const std::string&, const std::map<std::string, double>&,
                                                                  const core::Elastic&, core::Setting);

}  // namespace pdmpm::bc
