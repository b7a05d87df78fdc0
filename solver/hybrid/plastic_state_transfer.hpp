#pragma once
// The plastic state of one particle in the two languages of the hybrid (Noorian et al.,
// adaptive SBPD–MPM; the paper converts particles both ways but does not say what
// happens to their plastic state — here it is carried, docs/models/hybrid.md):
//   MPM: the plastic log strain ε_p (3×3, traceless, reference frame, solver/mpm/j2_plasticity);
//   PD (lps_plastic): a plastic extension p per bond and, in 2D, the axial deviator q_p
//        per particle (solver/pd/lps_plastic.hpp).
// A homogeneous plastic strain gives each bond the deviatoric extension it would cause:
//   3D: p = |ξ| n·ε_p·n (ε_p is traceless, so this is already deviatoric);
//   2D: p = |ξ| n·(ε_p,2 − ½ tr ε_p,2 I)·n on the in-plane block ε_p,2, and
//       q_p = (tr ε_p,2 − 2 ε_p,zz)/6 = ½ tr ε_p,2 (the 3D deviator's diag(1, 1, −2) part).
// Back: the deviatoric tensor whose bond extensions fit p best in the ω-weighted least-
// squares sense over the given bonds (exact for a homogeneous state whenever the bonds
// span the deviatoric directions), plus q_p in 2D.
#include <optional>
#include <vector>

#include "solver/core/types.hpp"
#include "solver/mpm/material_point.hpp"
#include "solver/pd/lps_plastic.hpp"

namespace pdmpm::hybrid {

// p of a bond of reference vector ξ for the plastic strain ε_p (D = 2 or 3).
template <int D>
double bond_plastic_extension(const Mat<3>& eps_p, const Vec<D>& xi);

// q_p of a 2D particle (0 in 3D, where there is no axial part).
double axial_plastic_strain(const Mat<3>& eps_p);

// ε_p from the plastic extensions p[k] of bonds xi[k] with weights w[k] > 0 (ω β V) and,
// in 2D, q_p. Empty when the bonds do not determine the deviator (fewer independent
// directions than its 2 (2D) or 5 (3D) components, e.g. a particle with one bond left).
template <int D>
std::optional<Mat<3>> fit_plastic_strain(const std::vector<Vec<D>>& xi, const std::vector<double>& w,
                                         const std::vector<double>& p, double q_p);

// MPM → PD: particle i's plastic state (ε_p, ε̄_p) written into the model, on every bond
// side of its family (inactive ones too: a bond that becomes live later carries it).
template <int D>
void carry_plastic_state_into_pd(const pd::System<D>& sys, pd::LpsPlastic<D>& model, Index i,
                                 const mpm::PointHistory& history);

// MPM → PD at the particle's current bond geometry (hybrid.plastic_transfer =
// "elastic_state"): p on every bond side of i and q_p (2D) such that its PD elastic state is
// the grid's elastic strain ε_e (small, reference frame) whatever the finite strain it sits at:
//   e_b − γθ_c|ξ| − p_b = |ξ| n·dev ε_e·n  (dev: the in-plane deviator in 2D),
//   q_e = (tr₂ ε_e − 2 ε_e,zz)/6  (2D). In plane stress that is all of it (ε_zz takes up the
//   geometric dilatation); in plane strain and 3D no plastic volume variable does, so only the
//   deviatoric part is made consistent there;
// ε̄_p as the grid's. θ and θ_c are the model's over the particle's state bonds: call it after
// the bonds' roles are refreshed for the particle's new kind.
template <int D>
void carry_elastic_state_into_pd(const pd::System<D>& sys, pd::LpsPlastic<D>& model, Index i, const Mat<3>& eps_e,
                                 double eq_plastic);

// PD → MPM (elastic_state), the inverse: the elastic strain of particle i's PD state at its
// current bond geometry — the deviator fitted over its live bonds' elastic parts
// e − γθ_c|ξ| − p (with q_e in 2D) plus a third of the volume change θ + ε_zz. Empty when the
// live bonds do not determine the deviator.
template <int D>
std::optional<Mat<3>> elastic_strain_from_pd(const pd::System<D>& sys, const pd::LpsPlastic<D>& model, Index i);

// The share of particle i's deviatoric PD elastic energy (α/2 Σ ω V e_e², over its live
// bonds) that no deformation gradient carries: what the fit above leaves, i.e. what a
// PD → MPM conversion with elastic_state loses (its weights are that energy's). 0 for an
// affine state to first order in the strain (a bond's extension is n·ε·n only to first
// order), 1 when the live bonds do not determine the deviator.
template <int D>
double non_affine_share(const pd::System<D>& sys, const pd::LpsPlastic<D>& model, Index i);

// PD → MPM: particle i's plastic state fitted over its live bonds, with its ε̄_p. Empty
// when its live bonds do not determine the deviator (the caller decides what to carry).
template <int D>
std::optional<mpm::PointHistory> plastic_state_from_pd(const pd::System<D>& sys, const pd::LpsPlastic<D>& model,
                                                       Index i);

}  // namespace pdmpm::hybrid
