#pragma once
// Small ready-made peridynamic bodies for unit tests and gates.
#include <memory>
#include <string>

#include "solver/pd/model.hpp"
#include "solver/pd/system.hpp"

namespace pdmpm::test {

struct BlockSpec {
  int sites = 12;                 // lattice sites per side
  double spacing = 1e-3;          // Δx
  double horizon_ratio = 3.015;   // m = δ / Δx
  core::Setting setting = core::Setting::solid3d;
  pd::Influence influence = pd::Influence::constant;
  pd::PartialVolume partial_volume = pd::PartialVolume::seed001;
  core::Elastic material{200e9, 0.25, 7850.0};
  double measure = 1.0;           // thickness (2D) / area (1D); 1 in 3D
};

// A cube/square/segment of sites^D lattice particles with families built.
template <int D>
pd::System<D> make_block(const BlockSpec& spec);

// Distance of particle i from the block's boundary (in metres).
template <int D>
double distance_to_boundary(const pd::System<D>& sys, Index i);

}  // namespace pdmpm::test
