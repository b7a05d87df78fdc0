#pragma once
// Homogeneous strain paths through the elastoplastic LPS model (unit tests and the
// lps_plastic gates): a cube (3D) or square (2D) of lattice sites whose centre particle
// is ≥ 2δ from every face, so an affine displacement gives it an exactly homogeneous
// state, and the uniaxial-stress path along any in-plane axis (lateral strain solved so
// the transverse in-plane stress vanishes at the centre).
#include <functional>

#include "solver/core/material.hpp"
#include "solver/pd/lps_plastic.hpp"

namespace pdmpm::test {

// The steel of the lps_plastic unit tests: σ_y = 1e-5 E keeps every strain small,
// E_t ≈ E/11 makes the hardening visible on the scale of σ_y.
inline const core::Elastic kSmallStrainSteel{215e9, 0.33, 7800.0};
inline constexpr double kSmallStrainYield = 2.15e6;
inline const core::J2Hardening kSmallStrainHardening{kSmallStrainYield, 20e9};

struct PlasticBlockSpec {
  core::Elastic material{215e9, 0.33, 7800.0};
  core::J2Hardening hardening{340e6, 1.45e9};
  bool isotropic = true;         // System::isotropic_deviatoric
  double horizon_ratio = 3.015;  // m = δ/Δx
  pd::Influence influence = pd::Influence::constant;
  core::Setting setting = core::Setting::solid3d;  // or plane_stress / plane_strain (D = 2)
  core::DuctileFailure failure{};                  // System::ductile_failure (off by default)
  int sites = 0;  // lattice sites per side; 0: 4δ/Δx + 1 (the centre's and its neighbours' families full)
};

// The ductile criterion along a proportional path (PlasticBlock::load_until_failure).
struct FailureRecord {
  bool centre_failed = false;
  int steps = 0;
  int failures = 0;    // particle failures seen (every particle, every step)
  int mismatches = 0;  // particles whose fate differs from the rule applied to the same evaluation
};

template <int D>
class PlasticBlock {
 public:
  explicit PlasticBlock(const PlasticBlockSpec& spec);

  void apply_affine(const Mat<D>& H);  // u = H x0 for every particle
  // Stress at the centre (force-state stress, in the frame of the loading axis R e_x)
  // for uniaxial stress with axial strain eps; `lateral` is the starting guess and
  // returns the lateral strain found. Evaluates the trial state; the caller accepts.
  Mat<D> uniaxial(double eps, double& lateral, const Mat<D>& R = Mat<D>::Identity());
  // Stress at the centre under the homogeneous strain H (sym) after one evaluation.
  Mat<D> stress_under(const Mat<D>& H);
  // Shear stress σ_xy at the centre under simple shear γ (ε_xy = γ/2).
  double shear(double gamma);
  double eq_plastic_strain() const { return (*model.eq_plastic_strain())[centre]; }
  double dilatation() const;  // θ of the centre (in-plane in 2D)
  // Steps the block along u = path(λ) x0, λ = k·step (k = 1 … max_steps), committing each
  // step, until the centre has failed. Each step is first evaluated on a copy without
  // failure; the rule applied to that state (ε̄_p and η of every particle; the accumulated
  // damage tracked here) says who must fail; then the block takes the step and every
  // particle's fate is compared: a particle that must fail loses every bond side, one that
  // must not loses only bonds to particles that fail.
  FailureRecord load_until_failure(const std::function<Mat<D>(double)>& path, double step, int max_steps);
  // max |f − f_LPS| / max |f_LPS| of one evaluation at the current displacements against
  // elastic LPS on a copy of the body (the below-yield claim).
  double difference_from_elastic_lps();
  int live_sides(Index i) const { return live_sides()[i]; }
  std::vector<int> live_sides() const;  // per particle: its live bond sides and its neighbours' towards it
  // The centre's ε̄_p at the first step where the strain rule holds, ε̄_p ≥ d₀ exp(cη), on the
  // homogeneous path (no bond breaks: the state the rule reads before anything fails); 0 if never.
  double homogeneous_onset(const std::function<Mat<D>(double)>& path, double step, int max_steps);

  PlasticBlockSpec spec;
  pd::System<D> sys;
  pd::LpsPlastic<D> model;
  pd::ForceRequest request;  // what every evaluation asks (bond breaking off by default)
  Index centre = 0;
};

}  // namespace pdmpm::test
