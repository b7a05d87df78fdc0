#pragma once
// The MPM's lane functions written on Lanes<W> (lanes.hpp), one set per instruction
// set, each set compiled in its own translation unit with that instruction set's flags
// (lanes_sse2.cpp, lanes_avx2.cpp, lanes_avx512.cpp; CMakeLists.txt), as the PD bond
// kernels are. One file with a target attribute per version is not enough with GCC 12:
// a template compiled for the baseline instruction set and inlined into the AVX-512
// version afterwards turns a combination of lane comparisons ((a < b) & (c < d)) into
// eight scalar compares and inserts. The plane-stress law's Newton loop spent half its
// time in those (issue 19: 37 → 19 ns per point on a mix of yielding points; the same bits).
// Each version's entry point is reached through the function that picks the widest
// version the machine runs (choose_lane_variant), e.g. plane_stress_lanes().
#include <vector>

#include "solver/mpm/deformation_lanes.hpp"
#include "solver/mpm/ductile_lanes.hpp"
#include "solver/mpm/gimp_lanes.hpp"
#include "solver/mpm/lane_copy.hpp"
#include "solver/mpm/lane_variant.hpp"
#include "solver/mpm/plane_stress_lanes.hpp"
#include "solver/mpm/polar_lanes.hpp"

namespace pdmpm::mpm {

struct LaneSet {
  GimpLanesFunction gimp;
  PolarLanesFunction polar_log;
  PlaneStressLanesFunction plane_stress;
  DeformationLanesFunction advance_deformation;
  CopyLanesFunction copy;
  FractureStrainLanesFunction fracture_strain;
};

extern const LaneSet lanes_sse2, lanes_avx2, lanes_avx512;

// Every instruction set's version of one lane function that this machine runs.
template <class Function>
std::vector<LaneVariant<Function>> lane_variants(Function LaneSet::*f) {
  return lane_variants<Function>(lanes_sse2.*f, lanes_avx2.*f, lanes_avx512.*f);
}

}  // namespace pdmpm::mpm
