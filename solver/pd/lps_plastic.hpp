#pragma once
// Elastoplastic ordinary state-based PD: the LPS solid with von Mises plasticity and
// linear isotropic hardening in equivalent plastic strain (docs/models/lps_plastic.md).
// The deviatoric return on the force state follows Mitchell 2011; the norm, the
// flow rule and the hardening variable are chosen so that any homogeneous state
// follows the classical J2 law exactly. 3D (small strain, any influence function ω):
//
//   t_ij   = ω (3K θ_i |ξ|)/m_i + t^d_ij                    (LPS with a plastic extension p)
//   t^d_ij = (B/m_i) ω ε_ij,  ε = e^d − p,  e^d = e − θ|ξ|/3  (deviatoric force state, B = 15G)
//   (with the isotropy correction below, θ in e^d is θ_c, measured with the deviatoric weights)
//   ‖t‖²_ω = Σ_j (t_ij²/ω) β V_j                             (ω-weighted norm)
// (with p = 0 this is LPS: 3Kθ|ξ|/m + B(e − θ|ξ|/3)/m = ((3K − 5G)θ|ξ| + 15G e)/m).
//
// For a homogeneous deviatoric strain ∫ ω r² (n·ε·n)² dV = (2/15) m ε:ε, so
// ‖t^d‖²_ω = 5 σ_eq² / m with σ_eq the classical von Mises stress: the PD equivalent
// stress is σ̄_i = √(m_i/5) ‖t^d‖_ω. Yield: σ̄ ≤ σ_y + H ε̄_p, H = E E_t/(E − E_t).
// Flow Δp = Δλ t^d/ω (weighted by 1/ω so the return is radial for every ω), and the
// dissipation Σ t^d Δp β V = σ̄ Δε̄_p defines ε̄_p. Backward Euler then gives the
// classical radial return: Δε̄_p = (σ̄_tr − σ_y − H ε̄_n)/(3G + H) with 3G = B/5,
// and ε scales by r = 1 − 3G Δε̄_p/σ̄_tr. Plastic flow is deviatoric: p of a
// homogeneous plastic strain adds nothing to θ.
//
// Optional isotropy correction (System::isotropic_deviatoric): on a cubic lattice the
// fourth bond moment Σ ωβV r² n⊗n⊗n⊗n is cubic, not isotropic, so the deviatoric
// response depends on direction (E_[100] = 0.886 E at δ = 3.015Δx, ω = 1). Weighting the
// deviatoric term of each bond by c(n) = 1 + κ g(n), g = n_x⁴ + n_y⁴ + n_z⁴ − 3/5, with κ
// from the full stencil's moments, and replacing m by m_d = Σ ωβc r² V there, makes it
// isotropic for every interior particle; ω becomes ωc in the norm and the flow rule, and the
// deviatoric split uses θ_c = (d/m_d) Σ ωβc|ξ|eV so that Σ ωβcV|ξ|ε = 0 and the force stays
// the gradient of W = ½κθ² + (B/2m_d) Σ ωβcV ε² (without it Verlet is unstable).
//
// State: p per bond side and ε̄_p per particle, trial/committed (accept/reject).
// 1D bar (uniaxial stress: A = 0, B = E, no volumetric split; ‖t‖²_ω = σ̄²/m, stiffness E).
//
// 2D (plane strain, plane stress): the out-of-plane strain ε_zz is not a PD degree of
// freedom, so each particle carries one more deviatoric component. The 3D deviator of a
// state with in-plane strain ε (2×2, trace θ) and ε_zz splits orthogonally into the 2D
// deviator (what the bonds see, e^d = e − θ|ξ|/2) and q·diag(1, 1, −2), q = (θ − 2ε_zz)/6;
// the plastic strain likewise into p per bond and q_p per particle. With q_e = q − q_p:
//   W = ½K (θ + ε_zz)² + G (4/m Σ ωβV ε² + 6 q_e²),   σ̄² = 6G² (4/m Σ ωβV ε² + 6 q_e²),
//   t_ij = ω (2P_i|ξ|/m_i + cB ε_ij/m_d,i),  B = 8G,  P = K(θ + ε_zz) + 2G q_e (in-plane mean stress).
// Plane strain: ε_zz = 0, the return is radial as in 3D. Plane stress: ε_zz follows from
// σ_zz = K(θ + ε_zz) − 4G q_e = 0, so q_e = (θ/2 − q_p)/(1 + x + 4G/3K) while the bonds scale
// by 1/(1 + x): the return solves one scalar equation for x (Newton, monotone on a convex
// function), and P = 6G q_e. Below yield both equal elastic 2D LPS (P = κ₂θ).
// No mirror ghosts (symmetry planes): the reverse bond of a ghost is not in any family.
// Remote ghosts (a distributed run, solver/dist/): the reverse side of a bond to one is on
// its owner's process, whose committed p arrives after every accept (fill_reverse_sides);
// the force pass's per-particle rows and the failing particles come with the halo.
//
// Ductile failure (optional, System::ductile_failure; Noorian et al. eqs 8–9): ε_f = d₀ exp(cη)
// with η the triaxiality of the particle's own stress; rule "strain" fails when ε̄_p ≥ ε_f,
// "accumulated" when ∫ dε̄_p/ε_f ≥ 1. A particle that fails loses every bond, both sides, at
// the end of the evaluation that found it (its bonds act once more, as with LAMMPS' rule for
// the critical stretch), so the check reads the state the forces came from.
#include <limits>
#include <memory>
#include <optional>

#include "solver/pd/constants.hpp"
#include "solver/pd/model.hpp"

namespace pdmpm::pd {

template <int D>
class LpsPlastic final : public Model<D> {
 public:
  std::string name() const override { return "lps_plastic"; }
  void initialise(const System<D>& sys) override;
  void refresh(const System<D>& sys, const std::vector<Index>& changed) override;
  std::int64_t compute_forces(System<D>& sys, const ForceRequest& req) override;
  void dilatation(const System<D>& sys, std::vector<double>& theta) const override;
  double stiffness_row_sum(const System<D>& sys, Index i) const override;
  void accept() override;
  void reject() override;
  void checkpoint(core::StateArchive& a) override;
  const std::vector<double>* eq_plastic_strain() const override { return &eq_plastic_.trial; }
  double plastic_work() const override { return plastic_work_trial_; }
  bool has_own_stress() const override { return true; }
  Tensor6 own_stress(const System<D>& sys, Index i) const override;
  const std::vector<double>* out_of_plane_strain() const override {
    return setting_ == core::Setting::plane_stress ? &out_of_plane_ : nullptr;
  }

  // Stress of particle i from its own force state, Σ_j t_ij (ξ ⊗ y/|y|) β V_j over the
  // bonds of its state (= λθI + 2Gε for an elastic homogeneous state), from the last evaluation.
  Mat<D> force_state_stress(const System<D>& sys, Index i) const;
  // σ_zz of particle i in the 2D settings (0 in plane stress), from the last evaluation.
  double out_of_plane_stress(Index i) const;
  // σ̄_i of the last evaluation.
  double equivalent_stress(Index i) const { return sigma_eq_[i]; }

  // The committed plastic state, read and written when the hybrid converts a particle
  // between MPM and PD (solver/hybrid/plastic_state_transfer): p per bond side, q_p (2D)
  // and ε̄_p per particle. The setters write trial and committed alike.
  double plastic_extension(BondIndex b) const { return plastic_ext_.committed[b]; }
  double axial_plastic_strain(Index i) const { return D == 2 ? axial_plastic_.committed[i] : 0.0; }
  double committed_eq_plastic_strain(Index i) const { return eq_plastic_.committed[i]; }
  void set_plastic_extension(BondIndex b, double p) {
    plastic_ext_.trial[b] = plastic_ext_.committed[b] = reverse_plastic_[reverse_[b]] = p;
  }
  // Particle i's dilatations at the current positions over the bonds of its state, as the
  // next evaluation forms them: θ (the volumetric term's) and θ_c (the deviatoric split's).
  std::pair<double, double> current_dilatations(const System<D>& sys, Index i) const;
  // γ of the deviatoric extension e^d = e − γθ_c|ξ| (1/3 in 3D, 1/2 in 2D).
  double split_factor() const { return k_.gamma; }
  // 2D: the q_p that gives the elastic axial deviator q_e at dilatation θ (the elastic
  // q_e = (cθ − q_p)/(1 + a), c = ½ and a = 4G/3K in plane stress, c = ⅙ and a = 0 in
  // plane strain); 0 in 3D.
  double axial_plastic_for(double theta, double q_e) const;
  // Its inverse: the elastic q_e at dilatation θ with plastic q_p (0 in 3D).
  double axial_elastic_for(double theta, double q_p) const;
  // The elastic volume change θ + ε_zz at dilatation θ and elastic axial deviator q_e:
  // 4G q_e/K in plane stress (σ_zz = 0), θ in plane strain and 3D.
  double volumetric_elastic_for(double theta, double q_e) const;
  void set_particle_plastic_state(Index i, double q_p, double eq_plastic) {
    if constexpr (D == 2) axial_plastic_.trial[i] = axial_plastic_.committed[i] = q_p;
    eq_plastic_.trial[i] = eq_plastic_.committed[i] = eq_plastic;
  }

 private:
  LpsCoefficients k_{};
  core::Setting setting_ = core::Setting::solid3d;
  std::optional<core::J2Hardening> hardening_;  // none: never yields
  double zeta_ = 5.0, three_g_ = 0.0, plastic_modulus_ = 0.0;
  double bulk_ = 0.0, shear_ = 0.0;        // K and G (3D moduli; the 2D settings use them)
  std::vector<double> m_, inv_m_, theta_;  // weighted volume, 1/m, dilatation (real particles)
  std::vector<double> theta_c_;            // θ_c = (d/m_d) Σ ωβcV|ξ|e, the deviatoric split's dilatation
  std::vector<double> inv_md_;             // 1/m_d, m_d = Σ ωβc r² V (deviatoric weighted volume)
  std::vector<double> shell_;       // c per stencil offset (1 without the isotropy correction), padded for the kernels
  std::vector<BondIndex> reverse_;  // bond j→i of each bond i→j (kRemoteSide: on another process)
  static constexpr BondIndex kRemoteSide = std::numeric_limits<BondIndex>::max();
  std::shared_ptr<const core::OtherProcesses> remote_;    // a distributed run's other processes
  Committed<double> plastic_ext_;                         // p per bond side (padded for the kernels)
  Committed<double> eq_plastic_;                          // ε̄_p per particle
  std::vector<double> dissipation_;                       // V_i σ̄ Δε̄_p of the last evaluation (J)
  double plastic_work_ = 0.0, plastic_work_trial_ = 0.0;  // Σ_i V_i ∫ σ̄ dε̄_p (J), committed / trial
  std::vector<double> sigma_eq_;                          // σ̄ per particle, last evaluation
  std::vector<double> reverse_plastic_;  // committed p of each bond side's reverse bond (padded): the force pass's copy
  std::vector<BondIndex> offsets_;       // the families' offsets (accept() updates reverse_plastic_ by particle)
  std::vector<double> norm2_;            // Σ ωβcV ε² per particle, last evaluation
  std::vector<std::uint8_t> trial_flowed_;  // 1 where the trial p differs from the committed one
  std::vector<double> scale_;               // r per particle: the elastic part is r ε after the return
  std::vector<double> particle_rows_;       // (mean term/m, r B/m_d, γθ_c, 0) per particle, the force pass's gather
  std::vector<double> mean_term_;           // 3Kθ (3D), 2P (2D), 0 (bar): t_ij's volumetric term is this ω|ξ|/m
  std::vector<double> volumetric_energy_;   // ½Kθ² (3D), ½K(θ + ε_zz)² + 6G q_e² (2D)
  // 2D only: q_p per particle (committed/trial), q_e and ε_zz of the last evaluation.
  Committed<double> axial_plastic_;
  // Ductile failure: ∫ dε̄_p/ε_f per particle (rule "accumulated"), and who failed in this evaluation.
  Committed<double> ductile_damage_;
  std::vector<std::uint8_t> failing_;
  std::vector<double> axial_elastic_, out_of_plane_;

  void return_map(const System<D>& sys, Index i, const double* eps);
  std::int64_t fail_particles(System<D>& sys);
  double planar_return(Index i, double norm2, double radius, double live, double& x, double& on_family);
  double live_bond_ratio(const System<D>& sys, Index i) const;
  // ωβc|ξ|²V_j of the bond to j at stencil offset k: its share of m_d.
  double deviatoric_moment(const System<D>& sys, Index j, int k) const {
    return sys.table.weight[k] * shell_[k] * sys.table.length[k] * sys.table.length[k] * sys.particles.volume[j];
  }
  void set_weighted_volumes(const System<D>& sys, Index i);
  static std::vector<double> isotropy_weights(const System<D>& sys);
  double scalar_force_state(Index i, BondIndex b, int k, double e, double L) const;
};

}  // namespace pdmpm::pd
