#pragma once
// Pre-cracks: bonds whose reference segment crosses a crack segment (2D) or a
// crack parallelogram (3D) are broken before the run. A particle lying exactly
// on the crack counts as being on its positive side, so it keeps its bonds on
// one side instead of losing them all.
#include <vector>

#include "solver/pd/system.hpp"

namespace pdmpm::pd {

template <int D>
struct CrackSurface {
  std::vector<Vec<D>> points;  // 2D: two segment ends; 3D: corners p0, p1, p2 (p0 + s(p1−p0) + t(p2−p0))
};

// Marks the crossing bonds broken; returns how many bond sides were cut.
template <int D>
std::int64_t cut_bonds(System<D>& sys, const CrackSurface<D>& crack);

}  // namespace pdmpm::pd
