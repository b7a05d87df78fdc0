#pragma once
// Bodies for the benchmarks: a cube (3D) or square (2D) of n^D lattice particles
// with families built, in a small non-affine deformation so every bond works.
#include "solver/pd/model.hpp"
#include "solver/pd/system.hpp"

namespace pdmpm::bench {

template <int D>
pd::System<D> lattice_body(int n, double horizon_ratio = 3.015);

// Fills u with a smooth field of strain ~1e-4.
template <int D>
void deform(pd::System<D>& sys);

}  // namespace pdmpm::bench
