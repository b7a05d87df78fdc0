#pragma once
// Homogeneous strain paths through the elastoplastic LPS model (unit tests and the
// lps_plastic gates): a cube of lattice sites whose centre particle is ≥ 2δ from every
// face, so an affine displacement gives it an exactly homogeneous state, and the
// uniaxial-stress path along any axis (lateral strain solved so the transverse stress
// vanishes at the centre).
#include "solver/core/material.hpp"
#include "solver/pd/lps_plastic.hpp"

namespace pdmpm::test {

struct PlasticBlockSpec {
  core::Elastic material{215e9, 0.33, 7800.0};
  core::J2Hardening hardening{340e6, 1.45e9};
  bool isotropic = true;           // System::isotropic_deviatoric
  double horizon_ratio = 3.015;    // m = δ/Δx
  pd::Influence influence = pd::Influence::constant;
};

class PlasticBlock {
 public:
  explicit PlasticBlock(const PlasticBlockSpec& spec);

  void apply_affine(const Mat<3>& H);  // u = H x0 for every particle
  // Stress at the centre (force-state stress, in the frame of the loading axis R e_x)
  // for uniaxial stress with axial strain eps; `lateral` is the starting guess and
  // returns the lateral strain found. Evaluates the trial state; the caller accepts.
  Mat<3> uniaxial(double eps, double& lateral, const Mat<3>& R = Mat<3>::Identity());
  // Shear stress σ_xy at the centre under simple shear γ (ε_xy = γ/2).
  double shear(double gamma);
  double eq_plastic_strain() const { return (*model.eq_plastic_strain())[centre]; }
  double dilatation() const;  // θ of the centre

  PlasticBlockSpec spec;
  pd::System<3> sys;
  pd::LpsPlastic<3> model;
  Index centre = 0;
};

}  // namespace pdmpm::test
