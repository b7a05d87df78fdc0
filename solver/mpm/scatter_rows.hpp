#pragma once
// The particle-to-grid scatter of the 2D step with a 3 × 3 stencil (uGIMP, quadratic
// B-spline) for a run of particles in the scatter schedule's order: each particle's
// mass, momentum, internal force −V₀ τ ∇S and external force onto its nine nodes. The
// vector version does a stencil row — three nodes, their mass and the interleaved x, y
// of the vectors — per instruction, with the per-node arithmetic of the scalar one,
// and adds to every node in the same particle order, so the bits are the scalar
// version's (the scalar one is the reference: Simulation's scatter before the rows).
// verification/unit/mpm/scatter_rows_test.cpp compares them bit for bit.
#include <array>
#include <vector>

#include "solver/core/types.hpp"
#include "solver/mpm/lane_variant.hpp"
#include "solver/mpm/matrix_arrays.hpp"
#include "solver/mpm/shape_function.hpp"

namespace pdmpm::mpm {

// The particles' data, read as source.array[order[k]] for the run's positions k (the
// stencil as stencil[k]).
struct ScatterSource2 {
  const Index* order = nullptr;
  const Stencil<2>* stencil = nullptr;  // stencil[k], in schedule order
  const double* mass = nullptr;
  const Vec<2>* velocity = nullptr;
  const double* volume = nullptr;
  std::array<const double*, 4> tau{};  // Kirchhoff stress τ₀₀, τ₁₀, τ₀₁, τ₁₁ by particle
  const Vec<2>* external = nullptr;    // external force of the particle
};

struct ScatterTarget2 {
  double* mass = nullptr;
  Vec<2>* momentum = nullptr;
  Vec<2>* force_internal = nullptr;
  Vec<2>* force_external = nullptr;
  Index row_stride = 0;  // nodes per grid row
};

struct ScatterFields {
  bool mass = false, momentum = false, forces = false;
  bool external = false;  // with forces: the external force too (else it stays as it is)
};

// Scatters the particles at schedule positions [k_begin, k_end).
void scatter_rows(const ScatterSource2& source, const ScatterTarget2& grid, ScatterFields what, Index k_begin,
                  Index k_end);

using ScatterRowsFunction = void (*)(const ScatterSource2&, const ScatterTarget2&, ScatterFields, Index, Index);
std::vector<LaneVariant<ScatterRowsFunction>> scatter_rows_variants();

// The 3D scatter with a 3 × 3 × 3 stencil, a stencil row (three nodes along x, nine
// doubles of a vector field) in one eight-lane instruction and its ninth double apart.
// The scalar version is Simulation's generic scatter, Eigen's V₀τ∇S included (its x and
// y rows sum (a + b) + c, its z row a + (b + c)); the vector one gives its bits.
struct ScatterSource3 {
  const Index* order = nullptr;
  const Stencil<3>* stencil = nullptr;  // stencil[k], in schedule order
  const double* mass = nullptr;
  const Vec<3>* velocity = nullptr;
  const double* volume = nullptr;
  const MatrixArrays<3, 3>* tau = nullptr;  // Kirchhoff stress of the particles (by particle, not order)
  const Vec<3>* external = nullptr;
};

struct ScatterTarget3 {
  double* mass = nullptr;
  Vec<3>* momentum = nullptr;
  Vec<3>* force_internal = nullptr;
  Vec<3>* force_external = nullptr;
  IVec<3> stride = IVec<3>::Zero();  // node index steps along x (1), y and z
};

void scatter_rows3(const ScatterSource3& source, const ScatterTarget3& grid, ScatterFields what, Index k_begin,
                   Index k_end);
using ScatterRows3Function = void (*)(const ScatterSource3&, const ScatterTarget3&, ScatterFields, Index, Index);
std::vector<LaneVariant<ScatterRows3Function>> scatter_rows3_variants();

}  // namespace pdmpm::mpm
