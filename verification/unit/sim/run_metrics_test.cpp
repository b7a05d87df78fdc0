// Run metrics: the busy-machine test `pdmpm check` warns with.
#include "solver/sim/run_metrics.hpp"

#include <gtest/gtest.h>

namespace {

using pdmpm::sim::cores_taken;

TEST(RunMetrics, CoresAreTakenWhenFewerThanTheRunsThreadsAreIdle) {
  EXPECT_FALSE(cores_taken(0, 2, 2)) << "a quiet machine";
  EXPECT_FALSE(cores_taken(1, 2, 1)) << "one core busy, a one-thread run finds the other idle";
  EXPECT_TRUE(cores_taken(1, 2, 2)) << "one core busy, a two-thread run shares it";
  EXPECT_TRUE(cores_taken(2, 2, 1)) << "both cores busy";
  EXPECT_FALSE(cores_taken(-1, 2, 2)) << "unknown: no warning";
}

TEST(RunMetrics, OtherRunningProcessesAreCountedOnLinux) { EXPECT_GE(pdmpm::sim::other_running_processes(), 0.0); }

}  // namespace
