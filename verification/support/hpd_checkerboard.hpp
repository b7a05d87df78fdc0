#pragma once
// The checkerboard (zero-energy) mode u = a (−1)^(Σ lattice indices) e_x on a block, and the mean
// restoring force on the particles 2δ inside it under HPD (the defaults, without the fit-residual
// stabilisation, and a plain fit without it),
// under a particle-centred correspondence gradient (Silling et al. 2007; blind to the mode), each
// divided by LPS's force for the same mode (a model without zero-energy modes: the mode's bulk
// scale). docs/models/hpd.md "Zero-energy modes"; used by the unit test and the hpd gate.
#include "solver/core/material.hpp"

namespace pdmpm::test {

struct CheckerboardForces {
  double hpd = 0.0;               // HPD (HpdOptions' defaults: end weight, stabilization) / LPS
  double hpd_unstabilized = 0.0;  // the same with stabilization 0: the bond-midpoint fit alone
  double hpd_plain = 0.0;         // HPD with end weight 1 (a plain least-squares fit), no stabilization / LPS
  double correspondence = 0.0;    // particle-centred gradient / LPS
};

// A block of `sites`^D particles, ν = 0.3, δ = horizon_ratio Δx (2D: the given setting).
template <int D>
CheckerboardForces checkerboard_forces(core::Setting setting, int sites, double horizon_ratio);

}  // namespace pdmpm::test
