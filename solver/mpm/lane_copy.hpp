#pragma once
// Hands eight lanes from one lane function's output array to the next one's input
// array as whole vectors. Copied lane by lane, the next function's vector load of
// eight fresh scalar stores waits until they retire (store forwarding fails); a
// vector store forwards to the vector load of the same bytes.
#include <vector>

#include "solver/mpm/lane_variant.hpp"

namespace pdmpm::mpm {

inline constexpr int kCopyLanes = 8;

struct LaneCopy {
  double* to;
  const double* from;  // kCopyLanes doubles each
};

void copy_lanes(const LaneCopy* copies, int count);

using CopyLanesFunction = void (*)(const LaneCopy*, int);
std::vector<LaneVariant<CopyLanesFunction>> copy_lanes_variants();

}  // namespace pdmpm::mpm
