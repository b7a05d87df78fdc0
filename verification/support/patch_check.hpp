#pragma once
// Patch tests (docs/models/lps.md) on a lattice block, shared by the patch and stability
// gates: an affine displacement u = H x must give zero force on interior
// particles at any magnitude of H; for small H the energy density and the
// dilatation must match their linear predictions; a rigid rotation must give
// zero force at every particle.
//
// Small-strain quantities are measured symmetrised in ±H: W_sym = (W(H) + W(−H))/2
// and θ_sym = (θ(H) − θ(−H))/2 drop every odd (resp. even) order of the
// geometrically exact kinematics, so what is left differs from the linear
// theory by O(|H|²) relative instead of O(|H|).
#include <Eigen/Dense>
#include <limits>
#include <memory>
#include <string>

#include "solver/pd/model.hpp"
#include "solver/pd/system.hpp"

namespace pdmpm::test {

struct PatchConfig {
  std::string model = "pmb";
  core::Setting setting = core::Setting::solid3d;
  pd::Influence influence = pd::Influence::constant;
  pd::PartialVolume partial_volume = pd::PartialVolume::seed001;
  double horizon_ratio = 3.015;
  core::Elastic material{200e9, 0.25, 7850.0};
  double spacing = 1e-3;
  // Body: a cube of lattice sites (default) or, for large horizons in 3D, a ball
  // just large enough to hold one interior particle at its centre.
  bool ball = false;
};

// Margin that makes a particle "interior": its force depends only on particles
// within δ (bond-based) or 2δ (state-based: θ_j of every neighbour j enters).
// Models other than "pmb" get the state-based margin, which is safe for both.
double interior_margin(const std::string& model, double delta);

// Thickness (2D) / area (1D) used by the gates: h = 1 mm, A = 1 mm².
double default_measure(core::Setting s);

// Classical small-strain energy density ½ ε:C:ε of the setting (ε symmetric, D×D).
double classical_energy(const Eigen::Matrix3d& eps, int dim, core::Setting s, const core::Elastic& m);

constexpr double not_measured = std::numeric_limits<double>::quiet_NaN();

struct PatchResult {
  double interior_force = 0.0;  // max |f_i| over interior particles / force scale
  double largest_force = 0.0;   // max |f_i| over all particles / force scale (what a boundary feels)
  double force_scale = 0.0;     // M |H|_max / Δx  (M: longitudinal modulus of the setting), N/m³
  int interior = 0;             // number of interior particles
  // Small-strain quantities (symmetrised in ±H), worst over interior particles:
  double theta_error = not_measured;       // |θ − tr ε| / |ε|_max
  double energy_error = not_measured;      // W / W_classical − 1 (signed, largest magnitude)
  double predicted_error = not_measured;   // the same from the lattice moments of the family
  double prediction_mismatch = not_measured;  // |W − W_lattice| / W_classical
};

// A lattice block sized so that it has interior particles, with its model.
template <int D>
class PatchBlock {
 public:
  explicit PatchBlock(const PatchConfig& cfg);

  // Affine field u = H x (top-left D×D block of H). `small` adds the ±H
  // energy and dilatation measurements.
  PatchResult affine(const Eigen::Matrix3d& H, bool small);

  // Deviatoric energy bound for LPS: the largest |W_lattice/W_classical − 1|
  // over unit deviatoric strains, from the fourth moment Σ ω β |ξ|² n⊗n⊗n⊗n V / m
  // of an interior family (the volumetric part is exact with the discrete m).
  // NaN for models without a lattice prediction.
  double deviatoric_bound() const;

  const pd::System<D>& system() const { return sys_; }
  Index sites() const { return sites_; }

 private:
  double lattice_energy(Index i, const Eigen::Matrix3d& eps) const;
  void evaluate(const Eigen::Matrix3d& H, std::vector<double>& W, std::vector<double>& theta);

  PatchConfig cfg_;
  Index sites_ = 0;
  pd::System<D> sys_;
  std::unique_ptr<pd::Model<D>> model_;
  std::vector<Index> interior_;
};

}  // namespace pdmpm::test
