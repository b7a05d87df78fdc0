#pragma once
// The material response of one MPM point: from its deformation gradient F (D×D)
// and history to the Kirchhoff stress τ (3×3, current frame). Chooses the law by
// model and the out-of-plane kinematics by setting; every law is objective:
// τ(QF) = Q τ(F) Qᵀ for any rotation Q.
#include <optional>

#include "solver/core/types.hpp"
#include "solver/mpm/j2_plasticity.hpp"
#include "solver/mpm/kinematics.hpp"
#include "solver/mpm/material_point.hpp"
#include "solver/mpm/plane_stress_lanes.hpp"
#include "solver/mpm/settings.hpp"

namespace pdmpm::mpm {

template <int D>
class Constitutive {
 public:
  Constitutive(const Material& material, core::Setting setting)
      : m_(material), setting_(setting), j2_(material.elastic, material.j2) {}

  // hardening_offset: ε̂_p − ε̄_p used by J2 hardening (non-local correction; 0 = local).
  StressResult update(const Mat<D>& F, PointHistory& history, double hardening_offset = 0.0) const;
  // The log-strain laws (all but neo-Hookean) need F only through its polar
  // decomposition: update(F) = update(polar_log(F)). The MPM step computes the
  // decompositions in a pass of their own (simulation.cpp).
  bool log_strain() const { return m_.model != MaterialModel::neo_hookean; }
  StressResult update(const PolarLog<D>& polar, PointHistory& history, double hardening_offset = 0.0) const;
  // The constants for plane_stress_lanes (the elastic path of this law eight points at a
  // time), or none if the law is not a plane-stress J2 or linear elastic one.
  std::optional<PlaneStressLaw> plane_stress_law() const;

  const Material& material() const { return m_; }
  core::Setting setting() const { return setting_; }

 private:
  Material m_;
  core::Setting setting_;
  J2Constants j2_;
};

// 3×3 embedding of a D×D tensor (zeros elsewhere) and of a deformation gradient
// (identity elsewhere).
template <int D>
Mat<3> embed(const Mat<D>& A);
template <int D>
Mat<3> embed_deformation(const Mat<D>& F);

}  // namespace pdmpm::mpm
