#pragma once
// The lane arithmetic of lane_copy.hpp, compiled once per instruction set (lane_set.hpp;
// lanes.hpp stops any other includer).
#include "solver/mpm/lane_copy.hpp"
#include "solver/mpm/lanes.hpp"

namespace pdmpm::mpm {
namespace {

template <int W>
inline void copy_lanes_by(const LaneCopy* copies, int count) {
  using V = Lanes<W>;
  for (int i = 0; i < count; ++i)
    for (int c0 = 0; c0 < kCopyLanes; c0 += W) V::store(copies[i].to + c0, V::load(copies[i].from + c0));
}

}  // namespace
}  // namespace pdmpm::mpm
