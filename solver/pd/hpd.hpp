#pragma once
// Stabilized hybrid peridynamics (HPD; "A stabilized hybrid peridynamic method compatible with
// constitutive models of different dimensions", Soil Dyn. Earthq. Eng. 2023; docs/models/hpd.md).
// Every bond i→j carries the state of a constitutive model at its midpoint. Two laws
// (System::hpd.law):
//
// axial_1d — the paper's reduction to bond-based PD: a 1D law σ = E_b s on the bond's stretch
// s = (|y| − |ξ|)/|ξ|, no shear, acting along the deformed bond y/|y| over the bond area
// A_ij = 2ωβ|ξ|V_j/m (m = Σ ωβ|ξ|V of a full family). The force density
//   f_i = Σ_j (2E_b/m) ω β s V_j y/|y|
// is PMB's with c = 2E_b/m; HPD takes PMB's calibrated c (solver/pd/constants.hpp), so ν is
// PMB's (¼, ⅓ in plane stress) and this law equals PMB (verification/unit/pd/hpd_test.cpp).
//
// linear_elastic — the nD law on the midpoint deformation. The deformation gradient of bond
// i→j is the least-squares fit over its sub-horizon (the overlap of the two horizons,
// solver/pd/sub_horizon.hpp): F_ij = I + Σ_l u_l ⊗ c_l. The stored energy is
//   E = Σ_i V_i W_i,   W_i = Σ_j a_ij ψ(F_ij),   a_ij = ω β |ξ| V_j / m_i,  m_i = Σ_j ω β |ξ| V_j
// (sums over live bonds; m_i over the reference family), with ψ the Saint Venant–Kirchhoff
// energy ½ S:Ẽ, Ẽ = ½(FᵀF − I), S = C:Ẽ, C Hooke's tensor of the setting (plane stress:
// λ* = 2λG/(λ + 2G)); for small strains this is Hooke's law, and ψ(RF) = ψ(F), so rigid
// rotations cost nothing and angular momentum is kept. The force is the exact gradient,
//   f_k = −(1/V_k) ∂E/∂u_k = −(1/V_k) Σ_{bonds i→j whose sub-horizon holds k} V_i a_ij P_ij c_k,
// P = F S: each bond spreads its force over its sub-horizon, the paper's "stress times the
// bond's direction and area" distributed so that Verlet conserves energy (the paper applies
// it at the two ends only, which makes the stiffness non-symmetric: docs/models/hpd.md).
//
// Area normalisation (why a_ij): a homogeneous deformation F gives F_ij = F on every bond
// (the fit is exact for affine fields), so W_i = ψ(F) Σ_j a_ij; W_i = ψ(F), the constitutive
// energy, exactly when Σ_j a_ij = 1 over the intact family, which m_i achieves for every
// particle, at boundaries too. The stress follows: the virial of the bond's forces about its
// sub-horizon is Σ_l (V_i a_ij P c_l) ⊗ (x_l − x̄) = V_i a_ij P (Σ_l c_l ⊗ (x_l − x̄) = K⁻¹K = I),
// so particle i's PD stress Σ_j a_ij P_ij = P(F), the constitutive stress, to round-off; the
// weight ω β |ξ| is the one under which axial_1d above is the same sum with the 1D law.
// Interior force of an affine field: the bonds through k come in pairs mirrored through x_k with
// opposite c_k and equal a (the same m), so f_k = 0 for particles 2δ inside the body.
//
// Zero-energy modes: for a bond with an odd lattice offset the checkerboard u = (−1)^Σx a is
// odd about the bond midpoint, so its sub-horizon fit sees a gradient and the bond resists;
// a particle-centred (correspondence) gradient sees the mode even about x_i and gives zero.
// A plain fit averages the mode over the sub-horizon and resists weakly; weighting the bond's
// ends (HpdOptions::end_weight) ties the fit to the bond's own stretch, as in the 1D law. That
// alone gives 3D 0.43 of the bulk scale; each bond side also stores ½ G Σ_l V_l |r_l|² of its
// plain fit's residual r (HpdOptions::stabilization; force −G V_k r_k, since the fit is a
// V-orthogonal projection): no force, stress or energy for affine fields, objective, momentum-free.
//
// j2 — MPM's J2 law with linear hardening (solver/mpm/constitutive.hpp: log strain, radial return,
// plane stress by its own return map) on each bond's midpoint deformation F_ij = I + H, with a
// plastic state (ε_p, ε̄_p) per bond side, trial/committed like the bond flags. The bond's stress
// P_ij = τ F⁻ᵀ spreads over its sub-horizon exactly as linear_elastic's F S does, so a homogeneous
// deformation gives every interior particle the law's own stress and plastic state; there is no
// energy to differentiate (plastic flow dissipates), the energy output is the law's elastic
// energy Σ_j a_ij W_e and the plastic work is booked per bond side. Axial-fallback bonds stay
// elastic (½ E₁ Ẽ_nn²): few, at boundaries and cracks.
//
// Damage: a bond breaks at the critical stretch as in the other models; when the live bonds
// change, the sub-horizons they reach are fitted again, so points across a crack leave every
// fit. Bonds whose
// sub-horizon is too small or flat use the axial fallback: ψ = ½ E₁ Ẽ_nn², Ẽ_nn = n·Ẽ·n, with
// E₁ the setting's uniaxial-stress modulus (E, or E/(1 − ν²) in plane strain).
// Ghost particles (symmetry planes) are not supported yet.
#include <memory>

#include "solver/mpm/constitutive.hpp"
#include "solver/pd/bond_state.hpp"
#include "solver/pd/model.hpp"
#include "solver/pd/sub_horizon.hpp"

namespace pdmpm::pd {

template <int D>
class Hpd final : public Model<D> {
 public:
  std::string name() const override { return "hpd"; }
  void initialise(const System<D>& sys) override;
  void refresh(const System<D>& sys, const std::vector<Index>& changed) override;
  std::int64_t compute_forces(System<D>& sys, const ForceRequest& req) override;
  // A Gershgorin bound on the linearised stiffness (for the Silling–Askari step and ADR):
  // ½ Σ_k' |∂f_i/∂u_k'| ≤ ½ Σ_{bonds b whose sub-horizon holds i} (V a_b/V_i) C |c_i| Σ_l |c_l|,
  // C the largest eigenvalue of Hooke's tensor (or E₁ on an axial bond); PMB's for axial_1d.
  double stiffness_row_sum(const System<D>& sys, Index i) const override;

  // The model's stress of particle i, Σ_j a_ij P_ij (first Piola–Kirchhoff), of the last
  // evaluation (linear_elastic).
  Mat<D> bond_averaged_stress(const System<D>& sys, Index i) const;
  const SubHorizon<D>& sub_horizon() const { return sub_; }

  // j2: trial/committed plastic state per bond side; per particle the bond-weighted ε̄_p
  // (Σ_j a_ij ε̄_p,ij of the last evaluation) and the plastic work so far (J).
  void accept() override;
  void reject() override;
  void checkpoint(core::StateArchive& a) override;
  const std::vector<double>* eq_plastic_strain() const override { return law_ == HpdLaw::j2 ? &eq_plastic_ : nullptr; }
  double plastic_work() const override;
  // j2: the stress output is the model's own, the bond average Σ_j a_ij σ_ij of the bonds'
  // Cauchy stresses σ = τ/J (the law's J, thickness change included; exact for a homogeneous
  // deformation); the elastic laws leave it to the deformation-gradient stress of pd/stress.hpp.
  bool has_own_stress() const override { return law_ == HpdLaw::j2; }
  Tensor6 own_stress(const System<D>& sys, Index i) const override;

 private:
  HpdLaw law_ = HpdLaw::linear_elastic;
  core::Setting setting_ = core::Setting::solid3d;
  int min_points_ = D + 1;
  double end_weight_ = 1.0;
  double lambda_ = 0.0, shear_ = 0.0, young_ = 0.0, axial_modulus_ = 0.0;
  double c_ = 0.0;                   // axial_1d: PMB's micromodulus
  std::vector<double> inv_m_;        // 1/m_i (reference family)
  std::vector<double> bond_weight_;  // V_i a_ij per bond side
  std::vector<Mat<D>> bond_p_;       // V_i a_ij P_ij per bond side, last evaluation
  // Stabilisation: g, 2gμ, and the residual forces −G V_l r_l of the last evaluation, in the
  // sub-horizon slots' order by point (SubHorizon::at_bond).
  double stabilization_ = 0.0, residual_modulus_ = 0.0;
  std::vector<Vec<D>> residual_force_;
  SubHorizon<D> sub_;
  std::unique_ptr<mpm::Constitutive<D>> j2_;  // j2: the law
  Committed<mpm::PointHistory> history_;      // j2: per bond side
  Committed<double> dissipation_;             // j2: plastic work per bond side, V_i a_ij ∫ τ : dε_p (J)
  std::vector<double> eq_plastic_;            // j2: per real particle, last evaluation
  std::vector<Mat<3>> bond_cauchy_;           // j2: V_i a_ij σ_ij (3×3, σ_zz of plane strain) per bond side

  std::int64_t break_bonds(System<D>& sys, double s0, bool after_force) const;
  void set_weighted_volume(const System<D>& sys, Index i);
  void axial_forces(System<D>& sys, const ForceRequest& req) const;
  void midpoint_forces(System<D>& sys, const ForceRequest& req);
  // S(Ẽ) and ψ of bond b with F = I + H.
  Mat<D> second_piola(const System<D>& sys, BondIndex b, const Mat<D>& H, double& psi) const;
  Mat<D> j2_stress(BondIndex b, const Mat<D>& H, double& psi);  // P; writes bond_cauchy_[b]
  double fit_and_residual(const System<D>& sys, Index i, BondIndex b, Mat<D>& H);
  void clear_residual(BondIndex b);
  // Slot q's (by point, point i) terms of the Gershgorin row: the bond's and the residual's.
  std::pair<double, double> slot_stiffness(const System<D>& sys, Index i, BondIndex q) const;

  // A distributed run (docs/models/distributed.md). A bond i→j ending in the halo has a
  // sub-horizon that reads j's bonds (halo_bonds: every halo particle's flags, from its owner),
  // and a halo point k is in sub-horizons of this process's bonds, whose forces on k (−P c, then
  // the residual force) and Gershgorin terms go to k's owner as records, slot by slot. An own
  // point's spans say where its records from each other process are: by rank, so that with its
  // own slots between the lower and the higher processes' they come in one process's order (by
  // the bond's owner, a global index).
  struct RemoteSpan {
    int process;
    BondIndex first, count;  // records [first, first + count) of that process's message
  };
  std::shared_ptr<const core::OtherProcesses> remote_;
  std::vector<BondIndex> span_begin_;  // per own point: its spans [span_begin_[i], span_begin_[i + 1])
  std::vector<RemoteSpan> spans_;
  std::vector<std::vector<double>> remote_forces_, remote_rows_;  // the records received, per process
  HaloBonds halo_bonds(const System<D>& sys) const;
  void index_remote_slots(const System<D>& sys);
  void exchange_stiffness_rows(const System<D>& sys);  // the halo slots' Gershgorin terms to their owners
  // Records of `width` values for the halo points' slots (fn(point, slot, out)), to their owners.
  template <class Fn>
  std::vector<std::vector<double>> send_halo_slots(const System<D>& sys, int width, Fn&& fn) const;
  // fn(record) for own point i's records from processes below (lower) or above this one.
  template <class Fn>
  void for_each_remote_record(Index i, bool lower, const std::vector<std::vector<double>>& records, int width,
                              Fn&& fn) const;
};

}  // namespace pdmpm::pd
