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

struct G2PCase {
  std::vector<Index> order;
  std::vector<Stencil<2>> stencil;
  std::vector<double> mass;
  std::vector<Vec<2>> velocity, displacement, grid_v, grid_v_new;
};

G2PCase random_g2p_case(int n, int nodes, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), inside(2.0, nodes - 3.0);
  G2PCase c;
  for (int i = 0; i < n; ++i) {
    c.order.push_back(i);
    const Vec<2> x(inside(rng), inside(rng));
    c.stencil.push_back(make_stencil<2>(ShapeFunction::gimp, x, 1.0, Vec<2>::Constant(0.25)));
    c.mass.push_back(1.0 + 0.5 * u(rng));
    c.velocity.emplace_back(u(rng), u(rng));
    c.displacement.emplace_back(1e-3 * u(rng), 1e-3 * u(rng));
  }
  for (int i = 0; i < nodes * nodes; ++i) {
    c.grid_v.emplace_back(u(rng), u(rng));
    c.grid_v_new.emplace_back(u(rng), u(rng));
  }
  std::shuffle(c.order.begin(), c.order.end(), rng);
  return c;
}

struct G2PResult {
  std::vector<Vec<2>> velocity, displacement, momentum;
  bool finite = true;
};

G2PResult run_g2p(G2PRowsFunction f, const G2PCase& c, int nodes, G2PParameters q) {
  G2PResult r{c.velocity, c.displacement, std::vector<Vec<2>>(nodes * nodes, Vec<2>::Zero())};
  const G2PArrays2 a{c.order.data(),        c.stencil.data(),    c.mass.data(),
                     c.grid_v.data(),       c.grid_v_new.data(), r.velocity.data(),
                     r.displacement.data(), r.momentum.data(),   nodes};
  const Index n = static_cast<Index>(c.order.size());
  r.finite = f(a, q, 0, n / 3) & f(a, q, n / 3, n);  // in two runs, as blocks run
  return r;
}

TEST(G2PRows, EveryVersionGivesTheScalarBits) {
  const int nodes = 12, n = 400;
  const G2PCase c = random_g2p_case(n, nodes, 5);
  const auto variants = g2p_rows_variants();
  for (const double flip : {1.0, 0.0, 0.95})
    for (const bool remap : {false, true}) {
      const G2PParameters q{flip, 1e-8, remap};
      const G2PResult reference = run_g2p(variants.front().function, c, nodes, q);
      EXPECT_TRUE(reference.finite);
      EXPECT_FALSE(same_bits(reference.velocity, c.velocity)) << "the pass moved nothing";
      for (const auto& v : variants) {
        const G2PResult r = run_g2p(v.function, c, nodes, q);
        EXPECT_TRUE(same_bits(r.velocity, reference.velocity)) << v.name << ", flip " << flip << ", remap " << remap;
        EXPECT_TRUE(same_bits(r.displacement, reference.displacement)) << v.name << ", flip " << flip;
        EXPECT_TRUE(same_bits(r.momentum, reference.momentum)) << v.name << ", flip " << flip << ", remap " << remap;
        EXPECT_TRUE(r.finite) << v.name;
      }
    }
}

TEST(G2PRows, EveryVersionReportsANonFiniteVelocity) {
  const int nodes = 12;
  G2PCase c = random_g2p_case(100, nodes, 6);
  const Stencil<2>& st = c.stencil[17];
  c.grid_v_new[(st.first[0] + 1) + (st.first[1] + 1) * nodes][1] = std::numeric_limits<double>::infinity();
  for (const auto& v : g2p_rows_variants())
    EXPECT_FALSE(run_g2p(v.function, c, nodes, {0.95, 1e-8, true}).finite) << v.name;
}

// The 3D rows: random particles in a cube of nodes³, several to a cell, uGIMP stencils,
// random grid velocities; FLIP, PIC and a blend, with and without the remap; and a
// non-finite grid velocity reported.
struct G2PCase3 {
  int nodes = 8;
  std::vector<Index> order;
  std::vector<Stencil<3>> stencil;
  std::vector<double> mass;
  std::vector<Vec<3>> velocity, displacement, grid_v, grid_v_new;
};

G2PCase3 random_g2p_case3(int n, int nodes, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), inside(2.0, nodes - 3.0);
  G2PCase3 c;
  c.nodes = nodes;
  for (int i = 0; i < n; ++i) {
    c.order.push_back(i);
    const Vec<3> x(inside(rng), inside(rng), inside(rng));
    c.stencil.push_back(make_stencil<3>(ShapeFunction::gimp, x, 1.0, Vec<3>::Constant(0.25)));
    c.mass.push_back(1.0 + 0.5 * u(rng));
    c.velocity.emplace_back(u(rng), u(rng), u(rng));
    c.displacement.emplace_back(1e-3 * u(rng), 1e-3 * u(rng), 1e-3 * u(rng));
  }
  for (int i = 0; i < nodes * nodes * nodes; ++i) {
    c.grid_v.emplace_back(u(rng), u(rng), u(rng));
    c.grid_v_new.emplace_back(u(rng), u(rng), u(rng));
  }
  std::shuffle(c.order.begin(), c.order.end(), rng);
  return c;
}

struct G2PResult3 {
  std::vector<Vec<3>> velocity, displacement, momentum;
  bool finite = true;
};

G2PResult3 run_g2p3(G2PRows3Function f, const G2PCase3& c, G2PParameters q) {
  const int N = c.nodes * c.nodes * c.nodes;
  G2PResult3 r{c.velocity, c.displacement, std::vector<Vec<3>>(N, Vec<3>::Zero())};
  const G2PArrays3 a{c.order.data(),        c.stencil.data(),    c.mass.data(),
                     c.grid_v.data(),       c.grid_v_new.data(), r.velocity.data(),
                     r.displacement.data(), r.momentum.data(),   IVec<3>(1, c.nodes, c.nodes * c.nodes)};
  const Index n = static_cast<Index>(c.order.size());
  r.finite = f(a, q, 0, n / 3) & f(a, q, n / 3, n);  // in two runs, as blocks run
  return r;
}

TEST(G2PRows, Every3dVersionGivesTheScalarBits) {
  const G2PCase3 c = random_g2p_case3(700, 8, 7);
  const auto variants = g2p_rows3_variants();
  for (const double flip : {1.0, 0.0, 0.95})
    for (const bool remap : {false, true}) {
      const G2PParameters q{flip, 1e-8, remap};
      const G2PResult3 reference = run_g2p3(variants.front().function, c, q);
      EXPECT_TRUE(reference.finite);
      EXPECT_FALSE(same_bits(reference.velocity, c.velocity)) << "the pass moved nothing";
      for (const auto& v : variants) {
        const G2PResult3 r = run_g2p3(v.function, c, q);
        EXPECT_TRUE(same_bits(r.velocity, reference.velocity)) << v.name << ", flip " << flip << ", remap " << remap;
        EXPECT_TRUE(same_bits(r.displacement, reference.displacement)) << v.name << ", flip " << flip;
        EXPECT_TRUE(same_bits(r.momentum, reference.momentum)) << v.name << ", flip " << flip << ", remap " << remap;
        EXPECT_TRUE(r.finite) << v.name;
      }
    }
}

TEST(G2PRows, Every3dVersionReportsANonFiniteVelocity) {
  for (int component = 0; component < 3; ++component) {  // z of node 2 is the ninth double
    G2PCase3 c = random_g2p_case3(100, 8, 8);
    const Stencil<3>& st = c.stencil[17];
    c.grid_v_new[(st.first[0] + 2) + (st.first[1] + 1) * 8 + (st.first[2] + 1) * 64][component] =
        std::numeric_limits<double>::infinity();
    for (const auto& v : g2p_rows3_variants())
      EXPECT_FALSE(run_g2p3(v.function, c, {0.95, 1e-8, true}).finite) << v.name << ", component " << component;
  }
}

}  // namespace
}  // namespace pdmpm::mpm
