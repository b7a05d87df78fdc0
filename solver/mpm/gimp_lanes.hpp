#pragma once
// uGIMP weights and gradients of eight particles along one axis at once. Each
// lane does gimp_weight's and gimp_gradient's arithmetic (shape_function.hpp)
// without their branches: the region of |r| selects the numerator and the
// denominator of the one division, so the bits are the scalar functions' and the
// divisions share vector instructions (2, 4 or 8 per instruction by the machine). The branches were the cost: on a
// regular lattice the particles sit on the region boundaries (|r| = lp, h − lp
// for a cell of 2Δx), and which side a particle falls on flips with round-off.
// verification/unit/mpm/gimp_lanes_test.cpp compares the lanes with the scalar
// functions bit for bit.
#include <vector>

#include "solver/mpm/lane_variant.hpp"

namespace pdmpm::mpm {

inline constexpr int kGimpLanes = 8;

struct GimpLanes {
  int first[kGimpLanes];                       // first node of each lane's 3
  double w[3][kGimpLanes], dw[3][kGimpLanes];  // [node][lane]; dw = ∂S/∂x (1/m)
};

// x_rel: particle coordinates relative to the grid origin; lp: GIMP half-widths; h: cell size.
void gimp_lanes(const double* x_rel, const double* lp, double h, GimpLanes& out);

// Every instruction set's version this machine can run (the tests compare them
// all); gimp_lanes calls the widest, or the one PDMPM_SIMD names.
using GimpLanesFunction = void (*)(const double*, const double*, double, GimpLanes&);
std::vector<LaneVariant<GimpLanesFunction>> gimp_lanes_variants();

}  // namespace pdmpm::mpm
