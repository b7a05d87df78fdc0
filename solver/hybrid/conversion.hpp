#pragma once
// A particle's state when the hybrid changes its method (Noorian et al., adaptive
// SBPD–MPM, §2: converted particles inherit position, velocity and acceleration; the
// paper is silent on stress and plastic state, docs/models/hybrid.md says what is carried).
// Position and velocity live in the shared particle store and need nothing. The
// acceleration is not carried: the force evaluation that ends the conversion step
// gives a new PD particle its own. What is carried:
//   MPM → PD  the plastic state (plastic strain → bond plastic extensions, ε̄_p),
//             when the PD model is plastic (plastic_state_transfer.hpp);
//   PD → MPM  a deformation gradient from the particle's live bonds,
//             F = (Σ V_j η_j ⊗ ξ_j)(Σ V_j ξ_j ⊗ ξ_j)⁻¹ (η = current bond vector; exact for an
//             affine motion), and the plastic state fitted from the bond plastic
//             extensions; MPM's constitutive law then gives the stress. A particle whose
//             live bonds do not determine F (or ε_p) keeps what MPM last had.
// Call to_mpm before the PD side refreshes its bonds: it reads the live bonds.
#include <optional>

#include "solver/hybrid/settings.hpp"
#include "solver/mpm/simulation.hpp"
#include "solver/pd/model.hpp"
#include "solver/pd/system.hpp"

namespace pdmpm::hybrid {

// F of particle i from its live bonds; empty when they do not span D dimensions.
template <int D>
std::optional<Mat<D>> bond_deformation_gradient(const pd::System<D>& sys, Index i);

template <int D>
void to_pd(const mpm::Simulation<D>& mpm, const pd::System<D>& sys, pd::Model<D>& model, Index i);

// The grid's elastic strain of particle i (3×3, reference frame): ln U − ε_p, with ε_zz the
// grid's out-of-plane strain in 2D.
template <int D>
Mat<3> grid_elastic_strain(const mpm::Simulation<D>& mpm, Index i);

// MPM → PD with hybrid.plastic_transfer = "elastic_state" (plastic_state_transfer.hpp); after
// the bonds' roles are refreshed for the particle's new kind.
template <int D>
void to_pd_elastic_state(const mpm::Simulation<D>& mpm, const pd::System<D>& sys, pd::Model<D>& model, Index i);

// PD → MPM: F from the live bonds (what MPM last had when they do not span the plane) and
// the plastic history in the grid's terms — strain: fitted from the bond plastic
// extensions; elastic_state: ε_p = ln U(F) − ε_e with ε_e the PD state's elastic strain
// (plastic_state_transfer.hpp; in plane, ε_p,zz from tr ε_p = 0), so the grid's law
// returns the PD state's stress. Where the bonds do not determine the plastic state, the
// history MPM last had.
template <int D>
void to_mpm(const pd::System<D>& sys, const pd::Model<D>& model, mpm::Simulation<D>& mpm, Index i,
            PlasticTransfer transfer = PlasticTransfer::strain);

}  // namespace pdmpm::hybrid
