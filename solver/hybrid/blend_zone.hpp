#pragma once
// The band of the blended coupling (hybrid.coupling = "blended"; docs/models/hybrid.md,
// "A grid that sees no hole"). The body's energy is
//   Σ_p (1 − β_p) V_p W_grid(F_p) + Σ_i β_i V_i W_PD,i,
// the two blended over a band around each PD region (Badia et al. 2008, "On
// atomistic-to-continuum coupling by blending"): β = 1 on PD particles and on the
// grid-moved particles within one bond reach r_b of them, then falling linearly to 0
// over `width` horizons, 0 beyond. Every particle within r_b of one with β > 0 is
// transition (moved by the grid, in the PD evaluation with its whole family), so each
// weighted force state is measured over a whole family; under an affine motion the two
// weighted forces, σ∇β from PD and −σ∇β from the grid, cancel in the continuum limit; on
// the lattice a fraction of either is left, falling as 1/width.
//
// Distances are the regions' (reference configuration, lattice offsets, regions.hpp).
#include <cstdint>
#include <span>
#include <vector>

#include "solver/hybrid/regions.hpp"

namespace pdmpm::hybrid {

// Lattice lengths of the band: the layer where β = 1 (the bond reach r_b), the ramp and
// the outer layer (r_b again), in lattice spacings.
struct BlendBand {
  double reach = 0.0;  // r_b/Δx
  double ramp = 0.0;   // width · δ/Δx
  double zone() const { return 2.0 * reach + ramp; }
  // β at a distance d (lattice spacings) from the nearest PD particle.
  double weight(double d) const { return d <= reach ? 1.0 : d >= reach + ramp ? 0.0 : 1.0 - (d - reach) / ramp; }
};

// Marks every non-PD, non-removed real particle within the band's zone of a PD particle
// transition (the others MPM) and writes β of every particle (PD 1, MPM 0). Replaces
// classify's transition set (one bond reach) with the zone.
template <int D>
void classify_blended(const RegionMap<D>& map, const BlendBand& band, std::span<core::ParticleKind> kind,
                      std::span<const std::uint8_t> removed, std::vector<double>& beta);

}  // namespace pdmpm::hybrid
