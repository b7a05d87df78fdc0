// The vector scatter (a stencil row per instruction) gives every node the scalar
// scatter's bits: random particles on a lattice, several to a cell so that nodes sum
// many contributions in order, uGIMP stencils from the code that makes them, random
// stresses, velocities and external forces, each combination of the fields.
#include "solver/mpm/scatter_rows.hpp"
#include "verification/support/same_bits.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

namespace pdmpm::mpm {
namespace {

using test::same_bits;

struct ScatterParticles {
  std::vector<Index> order;
  std::vector<Stencil<2>> stencil;
  std::vector<double> mass, volume;
  std::vector<Vec<2>> velocity, external;
  MatrixArrays<3, 3> tau;  // in-plane τ, by particle
};

// n particles in a grid of `nodes` × `nodes` (h = 1), away from its edges, in a shuffled order.
ScatterParticles random_scatter_particles(int n, int nodes, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), inside(2.0, nodes - 3.0);
  ScatterParticles s;
  s.tau.resize(n, Mat<3>::Zero());
  for (int i = 0; i < n; ++i) {
    s.order.push_back(i);
    const Vec<2> x(inside(rng), inside(rng));
    s.stencil.push_back(make_stencil<2>(ShapeFunction::gimp, x, 1.0, Vec<2>::Constant(0.25)));
    s.mass.push_back(1.0 + 0.5 * u(rng));
    s.volume.push_back(0.25 + 0.1 * u(rng));
    s.velocity.emplace_back(u(rng), u(rng));
    s.external.emplace_back(u(rng), u(rng));
    Mat<3> t = Mat<3>::Zero();
    t(0, 0) = 1e8 * u(rng), t(1, 1) = 1e8 * u(rng), t(0, 1) = t(1, 0) = 1e8 * u(rng);
    s.tau.set(i, t);
  }
  std::shuffle(s.order.begin(), s.order.end(), rng);  // stencils stay in position order
  return s;
}

struct ScatterGrid {
  std::vector<double> mass;
  std::vector<Vec<2>> momentum, force_internal, force_external;
  explicit ScatterGrid(int nodes)
      : mass(nodes * nodes, 0.0),
        momentum(nodes * nodes, Vec<2>::Zero()),
        force_internal(nodes * nodes, Vec<2>::Zero()),
        force_external(nodes * nodes, Vec<2>::Zero()) {}
};

TEST(ScatterRows, EveryVersionGivesTheScalarBitsForEveryCombinationOfFields) {
  const int nodes = 12, n = 400;  // ≈ 4 particles per cell: nodes sum up to ~36 contributions
  const ScatterParticles s = random_scatter_particles(n, nodes, 3);
  const ScatterSource2 source{s.order.data(),  s.stencil.data(), s.mass.data(),    s.velocity.data(),
                              s.volume.data(), in_plane(s.tau),  s.external.data()};
  const auto variants = scatter_rows_variants();
  ASSERT_GE(variants.size(), 1u);
  for (int bits = 1; bits < 16; ++bits) {
    const ScatterFields what{(bits & 1) != 0, (bits & 2) != 0, (bits & 4) != 0, (bits & 8) != 0};
    if (!what.mass && !what.momentum && !what.forces) continue;  // the external force goes with the forces
    ScatterGrid reference(nodes);
    ScatterTarget2 target{reference.mass.data(), reference.momentum.data(), reference.force_internal.data(),
                          reference.force_external.data(), nodes};
    variants.front().function(source, target, what, 0, n);
    EXPECT_TRUE(reference.mass[5 * nodes + 5] != 0.0 || reference.momentum[5 * nodes + 5].norm() > 0.0 ||
                reference.force_internal[5 * nodes + 5].norm() > 0.0)
        << "fields " << bits << ": the scatter reached no node";
    for (const auto& v : variants) {
      ScatterGrid grid(nodes);
      target = {grid.mass.data(), grid.momentum.data(), grid.force_internal.data(), grid.force_external.data(), nodes};
      v.function(source, target, what, 0, n / 3);  // in two runs, as blocks run
      v.function(source, target, what, n / 3, n);
      EXPECT_TRUE(same_bits(grid.mass, reference.mass)) << v.name << ", fields " << bits;
      EXPECT_TRUE(same_bits(grid.momentum, reference.momentum)) << v.name << ", fields " << bits;
      EXPECT_TRUE(same_bits(grid.force_internal, reference.force_internal)) << v.name << ", fields " << bits;
      EXPECT_TRUE(same_bits(grid.force_external, reference.force_external)) << v.name << ", fields " << bits;
    }
  }
}

// The 3D rows: random particles in a cube of nodes³, several to a cell, uGIMP stencils,
// random symmetric stresses, velocities and external forces (some zero, which the
// scatter skips), each combination of the fields.
TEST(ScatterRows, Every3dVersionGivesTheScalarBitsForEveryCombinationOfFields) {
  const int nodes = 8, n = 700;  // ≈ 2 particles per cell: nodes sum up to ~50 contributions
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0), inside(2.0, nodes - 3.0);
  std::vector<Index> order;
  std::vector<Stencil<3>> stencil;
  std::vector<double> mass, volume;
  std::vector<Vec<3>> velocity, external;
  std::vector<Mat<3>> tau;
  for (int i = 0; i < n; ++i) {
    order.push_back(i);
    const Vec<3> x(inside(rng), inside(rng), inside(rng));
    stencil.push_back(make_stencil<3>(ShapeFunction::gimp, x, 1.0, Vec<3>::Constant(0.25)));
    mass.push_back(1.0 + 0.5 * u(rng));
    volume.push_back(0.25 + 0.1 * u(rng));
    velocity.emplace_back(u(rng), u(rng), u(rng));
    external.push_back(i % 3 == 0 ? Vec<3>::Zero() : Vec<3>(u(rng), u(rng), u(rng)));
    Mat<3> t;
    for (int a = 0; a < 3; ++a)
      for (int b = a; b < 3; ++b) t(a, b) = t(b, a) = 1e8 * u(rng);
    tau.push_back(t);
  }
  std::shuffle(order.begin(), order.end(), rng);  // stencils stay in position order
  MatrixArrays<3, 3> tau_entries;
  tau_entries.unpack(tau);
  const ScatterSource3 source{order.data(),  stencil.data(), mass.data(),    velocity.data(),
                              volume.data(), &tau_entries,   external.data()};
  const IVec<3> stride(1, nodes, nodes * nodes);
  const int N = nodes * nodes * nodes;
  struct Grid3 {
    std::vector<double> mass;
    std::vector<Vec<3>> momentum, force_internal, force_external;
    explicit Grid3(int N)
        : mass(N, 0.0),
          momentum(N, Vec<3>::Zero()),
          force_internal(N, Vec<3>::Zero()),
          force_external(N, Vec<3>::Zero()) {}
    ScatterTarget3 target(const IVec<3>& stride) {
      return {mass.data(), momentum.data(), force_internal.data(), force_external.data(), stride};
    }
  };
  const auto variants = scatter_rows3_variants();
  ASSERT_GE(variants.size(), 1u);
  for (int bits = 1; bits < 16; ++bits) {
    const ScatterFields what{(bits & 1) != 0, (bits & 2) != 0, (bits & 4) != 0, (bits & 8) != 0};
    if (!what.mass && !what.momentum && !what.forces) continue;
    Grid3 reference(N);
    variants.front().function(source, reference.target(stride), what, 0, n);
    const Index middle = 4 + 4 * nodes + 4 * nodes * nodes;
    EXPECT_TRUE(reference.mass[middle] != 0.0 || reference.momentum[middle].norm() > 0.0 ||
                reference.force_internal[middle].norm() > 0.0)
        << "fields " << bits << ": the scatter reached no node";
    for (const auto& v : variants) {
      Grid3 grid(N);
      v.function(source, grid.target(stride), what, 0, n / 3);  // in two runs, as blocks run
      v.function(source, grid.target(stride), what, n / 3, n);
      EXPECT_TRUE(same_bits(grid.mass, reference.mass)) << v.name << ", fields " << bits;
      EXPECT_TRUE(same_bits(grid.momentum, reference.momentum)) << v.name << ", fields " << bits;
      EXPECT_TRUE(same_bits(grid.force_internal, reference.force_internal)) << v.name << ", fields " << bits;
      EXPECT_TRUE(same_bits(grid.force_external, reference.force_external)) << v.name << ", fields " << bits;
    }
  }
}

}  // namespace
}  // namespace pdmpm::mpm
