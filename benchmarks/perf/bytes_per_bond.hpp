#pragma once
// Bytes a force evaluation must move between memory and the core per bond side,
// from the data layout: the roofline's denominator.
//
// The account counts the arrays the kernels stream, once per evaluation:
//  - per bond side: neighbour index (int32, 4 B), broken flag (uint8, 1 B) and, only
//    for a family that is not the whole stencil, its stencil index (uint16, 2 B; a
//    whole-stencil family reads ξ, |ξ|, ωβ as contiguous rows of the small table);
//  - per particle, spread over its bonds: CSR offset (8 B), u_i (24 B), V_i (8 B),
//    f_i written (24 B), and for LPS m, θ, Aθ/m, B/m as read or written.
// LPS makes two passes over the bonds (θ, then forces), so its bond arrays count twice.
// Gathered neighbour data (u_j, V_j, LPS α_j, β_j) is not counted: particles are in
// lattice order, so a family's neighbours were loaded for the particles before it,
// and the ~3 MB these arrays take at 10⁵ particles stay in the last-level cache.
// Counting them would make the bound lower, not higher. The bond shape table
// (a few kB) stays in L1/L2. Write-allocate reads are not counted (as in STREAM).
#include <string>
#include <utility>
#include <vector>

#include "solver/pd/system.hpp"

namespace pdmpm::perf {

struct ByteAccount {
  std::vector<std::pair<std::string, double>> items;  // name, bytes per bond side
  double total = 0.0;
};

ByteAccount bytes_per_bond(const pd::System<3>& sys, const std::string& model);

}  // namespace pdmpm::perf
