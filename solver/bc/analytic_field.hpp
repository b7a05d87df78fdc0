#pragma once
// Named analytic displacement fields u(x, t) for verification boundary
// conditions (kind = "analytic"): the particles of the region follow the field
// exactly. Parameters come from the scene's [boundary.parameters] table.
//   affine          u = H x with H from h_xx, h_xy, … (missing entries 0)
//   spherical_wave  u = (x/r) u_r(r, t) of the outgoing spherical wave (docs/verification/analytic_solutions.md);
//                   parameters r0, period, amplitude; wave speed from the material
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "solver/core/types.hpp"
#include "solver/core/material.hpp"

namespace pdmpm::bc {

template <int D>
class AnalyticField {
 public:
  virtual ~AnalyticField() = default;
  virtual void evaluate(const Vec<D>& x, double t, Vec<D>& u, Vec<D>& v) const = 0;
};

std::vector<std::string> analytic_field_names();
// Throws std::invalid_argument naming a missing, unknown or out-of-range parameter.
void check_analytic_parameters(const std::string& name, const std::map<std::string, double>& p);

template <int D>
std::unique_ptr<AnalyticField<D>> make_analytic_field(const std::string& name, const std::map<std::string, double>& p,
                                                      const core::Elastic& material, core::Setting setting);

}  // namespace pdmpm::bc
