// The vector G2P (a stencil row per instruction) gives every particle and, with the
// remap, every node the scalar pass's bits: random particles, several to a cell, uGIMP
// stencils from the code that makes them, random grid velocities, FLIP, PIC and a
// blend, with and without the remap; and both report a non-finite grid velocity.
#include "solver/mpm/g2p_rows.hpp"
#include "verification/support/same_bits.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace pdmpm::mpm {
namespace {

using test::same_bits;

// n particles in a grid of nodes^D (h = 1), away from its edges, in a shuffled order.
template <int D>
struct G2PCase {
  int nodes = 0;
  std::vector<Index> order;
  std::vector<Stencil<D>> stencil;
  std::vector<double> mass;
  std::vector<Vec<D>> velocity, displacement, grid_v, grid_v_new;
  int node_count() const { return D == 2 ? nodes * nodes : nodes * nodes * nodes; }
};

template <int D>
G2PCase<D> random_g2p_case(int n, int nodes, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), inside(2.0, nodes - 3.0);
  auto draw = [&](std::uniform_real_distribution<double>& d, double scale) {
    Vec<D> v;
    for (int a = 0; a < D; ++a) v[a] = scale * d(rng);
    return v;
  };
  G2PCase<D> c;
  c.nodes = nodes;
  for (int i = 0; i < n; ++i) {
    c.order.push_back(i);
    c.stencil.push_back(make_stencil<D>(ShapeFunction::gimp, draw(inside, 1.0), 1.0, Vec<D>::Constant(0.25)));
    c.mass.push_back(1.0 + 0.5 * u(rng));
    c.velocity.push_back(draw(u, 1.0));
    c.displacement.push_back(draw(u, 1e-3));
  }
  for (int i = 0; i < c.node_count(); ++i) {
    c.grid_v.push_back(draw(u, 1.0));
    c.grid_v_new.push_back(draw(u, 1.0));
  }
  std::shuffle(c.order.begin(), c.order.end(), rng);
  return c;
}

template <int D>
struct G2PResult {
  std::vector<Vec<D>> velocity, displacement, momentum;
  bool finite = true;
};

// f over the case's particles in two runs, as blocks run.
template <int D, class Function>
G2PResult<D> run_g2p(Function f, const G2PCase<D>& c, G2PParameters q) {
  G2PResult<D> r{c.velocity, c.displacement, std::vector<Vec<D>>(c.node_count(), Vec<D>::Zero())};
  const auto arrays = [&] {
    if constexpr (D == 2)
      return G2PArrays2{c.order.data(),        c.stencil.data(),    c.mass.data(),
                        c.grid_v.data(),       c.grid_v_new.data(), r.velocity.data(),
                        r.displacement.data(), r.momentum.data(),   c.nodes};
    else
      return G2PArrays3{c.order.data(),        c.stencil.data(),    c.mass.data(),
                        c.grid_v.data(),       c.grid_v_new.data(), r.velocity.data(),
                        r.displacement.data(), r.momentum.data(),   IVec<3>(1, c.nodes, c.nodes * c.nodes)};
  }();
  const Index n = static_cast<Index>(c.order.size());
  r.finite = f(arrays, q, 0, n / 3) & f(arrays, q, n / 3, n);
  return r;
}

// Every version against the first (the scalar reference) for FLIP, PIC and a blend, with
// and without the remap.
template <int D, class Variants>
void expect_every_version_gives_the_scalar_bits(const G2PCase<D>& c, const Variants& variants) {
  for (const double flip : {1.0, 0.0, 0.95})
    for (const bool remap : {false, true}) {
      const G2PParameters q{flip, 1e-8, remap};
      const G2PResult<D> reference = run_g2p(variants.front().function, c, q);
      EXPECT_TRUE(reference.finite);
      EXPECT_FALSE(same_bits(reference.velocity, c.velocity)) << "the pass moved nothing";
      for (const auto& v : variants) {
        const G2PResult<D> r = run_g2p(v.function, c, q);
        EXPECT_TRUE(same_bits(r.velocity, reference.velocity)) << v.name << ", flip " << flip << ", remap " << remap;
        EXPECT_TRUE(same_bits(r.displacement, reference.displacement)) << v.name << ", flip " << flip;
        EXPECT_TRUE(same_bits(r.momentum, reference.momentum)) << v.name << ", flip " << flip << ", remap " << remap;
        EXPECT_TRUE(r.finite) << v.name;
      }
    }
}

TEST(G2PRows, EveryVersionGivesTheScalarBits) {
  expect_every_version_gives_the_scalar_bits(random_g2p_case<2>(400, 12, 5), g2p_rows_variants());
}

TEST(G2PRows, EveryVersionReportsANonFiniteVelocity) {
  G2PCase<2> c = random_g2p_case<2>(100, 12, 6);
  const Stencil<2>& st = c.stencil[17];
  c.grid_v_new[(st.first[0] + 1) + (st.first[1] + 1) * 12][1] = std::numeric_limits<double>::infinity();
  for (const auto& v : g2p_rows_variants()) EXPECT_FALSE(run_g2p(v.function, c, {0.95, 1e-8, true}).finite) << v.name;
}

// The 3D rows: several particles to a cell of an 8³ grid.
TEST(G2PRows, Every3dVersionGivesTheScalarBits) {
  expect_every_version_gives_the_scalar_bits(random_g2p_case<3>(700, 8, 7), g2p_rows3_variants());
}

TEST(G2PRows, Every3dVersionReportsANonFiniteVelocity) {
  for (int component = 0; component < 3; ++component) {  // z of node 2 is the row's ninth double
    G2PCase<3> c = random_g2p_case<3>(100, 8, 8);
    const Stencil<3>& st = c.stencil[17];
    c.grid_v_new[(st.first[0] + 2) + (st.first[1] + 1) * 8 + (st.first[2] + 1) * 64][component] =
        std::numeric_limits<double>::infinity();
    for (const auto& v : g2p_rows3_variants())
      EXPECT_FALSE(run_g2p(v.function, c, {0.95, 1e-8, true}).finite) << v.name << ", component " << component;
  }
}

}  // namespace
}  // namespace pdmpm::mpm
