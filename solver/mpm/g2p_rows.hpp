#pragma once
// The grid-to-particle pass of the 2D step with a 3 × 3 stencil (uGIMP, quadratic
// B-spline) for a run of particles in the scatter schedule's order: the PIC velocity
// Σ S v_I and the FLIP increment Σ S (v_I − v_Iⁿ) from the grid, the particle's new
// velocity (FLIP/PIC blend) and displacement, and, for MUSL's remap, its new momentum
// back onto the nodes. The vector version reads and writes a stencil row — three
// nodes' x, y — per instruction and sums the nodes in the scalar version's order, so
// the bits are the scalar version's (the scalar one is the reference: Simulation's G2P
// before the rows). verification/unit/mpm/g2p_rows_test.cpp compares them bit for bit.
#include <vector>

#include "solver/core/types.hpp"
#include "solver/mpm/lane_variant.hpp"
#include "solver/mpm/shape_function.hpp"

namespace pdmpm::mpm {

struct G2PArrays2 {
  const Index* order = nullptr;               // particle at schedule position k
  const Stencil<2>* stencil = nullptr;        // stencil[k], in schedule order
  const double* mass = nullptr;               // of the particles (for the remap)
  const Vec<2>* grid_velocity = nullptr;      // vⁿ of the nodes
  const Vec<2>* grid_velocity_new = nullptr;  // vⁿ⁺¹ of the nodes
  Vec<2>* velocity = nullptr;                 // of the particles, updated
  Vec<2>* displacement = nullptr;             // of the particles, updated
  Vec<2>* grid_momentum = nullptr;            // the remap's target (remap only)
  Index row_stride = 0;                       // nodes per grid row
};

struct G2PParameters {
  double flip = 1.0;  // FLIP fraction of the blend
  double dt = 0.0;
  bool remap = false;  // MUSL: scatter m v of the new velocity
};

// Moves the particles at schedule positions [k_begin, k_end); false if one of them got
// a non-finite velocity or displacement.
bool g2p_rows(const G2PArrays2& arrays, G2PParameters parameters, Index k_begin, Index k_end);

using G2PRowsFunction = bool (*)(const G2PArrays2&, G2PParameters, Index, Index);
std::vector<LaneVariant<G2PRowsFunction>> g2p_rows_variants();

// The 3D pass with a 3 × 3 × 3 stencil: a stencil row (three nodes' x, y, z, nine
// doubles) in one eight-lane instruction and its ninth double apart; the nodes are
// added one by one in the scalar version's order (Simulation's generic G2P).
struct G2PArrays3 {
  const Index* order = nullptr;
  const Stencil<3>* stencil = nullptr;
  const double* mass = nullptr;
  const Vec<3>* grid_velocity = nullptr;
  const Vec<3>* grid_velocity_new = nullptr;
  Vec<3>* velocity = nullptr;
  Vec<3>* displacement = nullptr;
  Vec<3>* grid_momentum = nullptr;
  IVec<3> stride = IVec<3>::Zero();  // node index steps along x (1), y and z
};

bool g2p_rows3(const G2PArrays3& arrays, G2PParameters parameters, Index k_begin, Index k_end);
using G2PRows3Function = bool (*)(const G2PArrays3&, G2PParameters, Index, Index);
std::vector<LaneVariant<G2PRows3Function>> g2p_rows3_variants();

}  // namespace pdmpm::mpm
