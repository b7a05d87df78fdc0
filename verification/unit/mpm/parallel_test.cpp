// for_each_group_gathered_ahead computes every group once, each from the buffer its own
// gather filled, on one and two threads and for group counts that split unevenly; the
// lowest bad particle any group reports comes back.
#include "solver/mpm/parallel.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <vector>

namespace pdmpm::mpm {
namespace {

TEST(GroupsGatheredAhead, ComputeEachGroupOnceFromItsOwnGather) {
  const int before = omp_get_max_threads();
  for (const int threads : {1, 2})
    for (const Index groups : {0, 1, 2, 7, 64}) {
      omp_set_num_threads(threads);
      struct Buffer {
        Index group = -1;
      };
      std::vector<int> computed(static_cast<std::size_t>(groups), 0), wrong(static_cast<std::size_t>(groups), 0);
      const Index bad = for_each_group_gathered_ahead<Buffer>(
          groups, true, [](Index g, Buffer& b) { b.group = g; },
          [&](Index g, Buffer& b) {
            ++computed[g];
            wrong[g] += b.group != g;
            return g % 3 == 2 ? 100 - g : kNoParticle;
          });
      Index expected = kNoParticle;
      for (Index g = 0; g < groups; ++g) {
        EXPECT_EQ(computed[g], 1) << "group " << g << " of " << groups << ", " << threads << " threads";
        EXPECT_EQ(wrong[g], 0) << "group " << g << " of " << groups;
        if (g % 3 == 2) expected = std::min(expected, 100 - g);
      }
      EXPECT_EQ(bad, expected) << groups << " groups, " << threads << " threads";
    }
  omp_set_num_threads(before);
}

}  // namespace
}  // namespace pdmpm::mpm
