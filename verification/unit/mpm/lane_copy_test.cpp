// Every instruction set's lane copy hands each array's eight doubles over bit for bit
// (signed zeros, NaN payloads, infinities, subnormals) and touches nothing else.
#include "solver/mpm/lane_copy.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <limits>

namespace pdmpm::mpm {
namespace {

std::uint64_t bits(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

TEST(LaneCopy, EveryVersionCopiesTheBitsOfEachArray) {
  double from[3][kCopyLanes];
  for (int a = 0; a < 3; ++a)
    for (int l = 0; l < kCopyLanes; ++l) from[a][l] = (a + 1) * 1.25 + l * 1e-300;
  from[0][1] = -0.0, from[1][2] = std::numeric_limits<double>::infinity();
  from[2][3] = std::numeric_limits<double>::denorm_min();
  const std::uint64_t payload = 0x7ff8'0000'0000'1234ULL;
  std::memcpy(&from[2][7], &payload, sizeof payload);
  for (const auto& variant : copy_lanes_variants()) {
    double to[4][kCopyLanes];  // the fourth is not a target
    for (auto& row : to)
      for (double& x : row) x = 7.0;
    const LaneCopy copies[] = {{to[0], from[0]}, {to[1], from[1]}, {to[2], from[2]}};
    variant.function(copies, 3);
    for (int a = 0; a < 3; ++a)
      for (int l = 0; l < kCopyLanes; ++l) EXPECT_EQ(bits(to[a][l]), bits(from[a][l])) << variant.name;
    for (double x : to[3]) EXPECT_EQ(x, 7.0) << variant.name;
  }
}

}  // namespace
}  // namespace pdmpm::mpm
