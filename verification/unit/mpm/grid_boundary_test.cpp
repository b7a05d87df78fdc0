// A moving velocity constraint carries its node box with the prescribed velocity
// (trapezoid rule: exact for a constant speed and a linear ramp whose end falls on a
// step), along its prescribed components only, and holds the nodes near the faces it
// moves across in proportion to where the face lies in their cell; a box fixed in
// space keeps its nodes; a restored offset gives the same nodes as the run that reached it.
#include "solver/mpm/grid_boundary.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace pdmpm::mpm {
namespace {

Grid<2> grid_10mm() { return Grid<2>(Vec<2>(0.0, 0.0), 1e-3, IVec<2>(21, 11)); }  // 20 × 10 cells of 1 mm

// Node x-coordinates (in cells) of bc b, once per distinct value.
std::vector<int> node_columns(const GridBoundary<2>& gb, std::size_t b, const Grid<2>& g) {
  std::vector<int> cols;
  for (Index i : gb.nodes(b)) {
    const int c = g.coords(i)[0];
    if (cols.empty() || cols.back() != c) cols.push_back(c);
  }
  std::sort(cols.begin(), cols.end());
  cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
  return cols;
}

TEST(GridBoundary, AMovingBoxTravelsWithItsPrescribedVelocity) {
  const Grid<2> g = grid_10mm();
  GridBc<2> grip;
  grip.kind = BcKind::velocity;
  grip.min = Vec<2>(15.5e-3, -1.0);
  grip.max = Vec<2>(17.5e-3, 1.0);
  grip.velocity = Vec<2>(10.0, 3.0);
  grip.components = {true, false};  // y is free: the box does not move along it
  grip.ramp_time = 1e-4;
  grip.moving = true;
  GridBc<2> fixed_in_space = grip;
  fixed_in_space.moving = false;
  GridBoundary<2> gb({grip, fixed_in_space}, g);
  EXPECT_EQ(node_columns(gb, 0, g), (std::vector<int>{16, 17}));
  const double dt = 1e-6;
  const int steps = 250;  // 0.25 ms: ramp (0.1 ms, mean speed 5 m/s) then 0.15 ms at 10 m/s
  for (int s = 0; s < steps; ++s) gb.advance(s * dt, dt);
  const double expected = 10.0 * (steps * dt - 0.5 * grip.ramp_time);  // 2 mm
  EXPECT_NEAR(gb.box_offsets()[0][0], expected, 1e-12 * expected) << "trapezoid rule, exact here";
  EXPECT_EQ(gb.box_offsets()[0][1], 0.0);
  EXPECT_EQ(gb.box_offsets()[1], Vec<2>::Zero());
  EXPECT_EQ(node_columns(gb, 0, g), (std::vector<int>{18, 19})) << "the box now spans 17.5 … 19.5 mm";
  EXPECT_EQ(node_columns(gb, 1, g), (std::vector<int>{16, 17}));
  EXPECT_EQ(gb.nodes(0).size(), 2u * 11u);

  // A quarter cell on (box 17.75 … 19.75 mm), the nodes at 18 and 20 mm are held with
  // w = 0.75 and 0.25: v = w v_grip + (1 − w) v, the grip's speed 10 m/s, the free one 0.
  for (int s = steps; s < steps + 25; ++s) gb.advance(s * dt, dt);
  std::vector<Vec<2>> v(static_cast<std::size_t>(g.size()), Vec<2>(0.0, -1.0));
  gb.constrain(v, 1.0);
  EXPECT_EQ(node_columns(gb, 0, g), (std::vector<int>{18, 19, 20}));
  const Index row = 5 * g.stride[1];
  EXPECT_NEAR(v[row + 18][0], 7.5, 1e-9);
  EXPECT_NEAR(v[row + 19][0], 10.0, 1e-12);
  EXPECT_NEAR(v[row + 20][0], 2.5, 1e-9);
  EXPECT_EQ(v[row + 21][0], 0.0);
  EXPECT_EQ(v[row + 19][1], -1.0) << "y is free";

  GridBoundary<2> restored({grip, fixed_in_space}, g);  // a checkpoint's offsets, then refresh()
  restored.box_offsets() = gb.box_offsets();
  restored.refresh();
  EXPECT_EQ(restored.nodes(0), gb.nodes(0));
  EXPECT_EQ(restored.nodes(1), gb.nodes(1));
}

// A field that does not depend on position is evaluated once per call: the constrained
// velocities are the per-node evaluation's, bit for bit.
TEST(GridBoundary, AUniformFieldGivesThePerNodeVelocities) {
  const Grid<2> g = grid_10mm();
  GridBc<2> per_node;
  per_node.kind = BcKind::velocity;
  per_node.min = Vec<2>(15.5e-3, -1.0);
  per_node.max = Vec<2>(1.0, 1.0);
  per_node.components = {true, true};
  per_node.velocity_field = [](const Vec<2>&, double t) { return Vec<2>(0.3 * std::cos(1e3 * t), -0.1); };
  GridBc<2> uniform = per_node;
  uniform.field_depends_on_position = false;
  std::vector<Vec<2>> a(static_cast<std::size_t>(g.size()), Vec<2>(1.0, 2.0)), b = a;
  GridBoundary<2>({per_node}, g).constrain(a, 7e-4);
  GridBoundary<2>({uniform}, g).constrain(b, 7e-4);
  EXPECT_EQ(a, b);
  EXPECT_EQ(a[5 * g.stride[1] + 18][0], 0.3 * std::cos(0.7));
}

}  // namespace
}  // namespace pdmpm::mpm
