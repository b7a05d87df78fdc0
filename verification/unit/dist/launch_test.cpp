#include "solver/dist/launch.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

namespace pdmpm::dist {
namespace {

// Sets the launcher variables for one test and restores the environment after it.
class LaunchEnvironment : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* v : kVariables) unsetenv(v);
  }
  void TearDown() override { SetUp(); }
  static constexpr const char* kVariables[] = {"OMPI_COMM_WORLD_SIZE", "OMPI_COMM_WORLD_RANK", "PMI_SIZE", "PMI_RANK"};
};

TEST_F(LaunchEnvironment, WithoutALauncherOneProcess) {
  const auto l = launch_from_environment();
  EXPECT_EQ(l.processes, 1);
  EXPECT_EQ(l.rank, 0);
}

TEST_F(LaunchEnvironment, ReadsOpenMpiThenPmi) {
  setenv("PMI_SIZE", "8", 1);
  setenv("PMI_RANK", "5", 1);
  EXPECT_EQ(launch_from_environment().processes, 8);
  EXPECT_EQ(launch_from_environment().rank, 5);
  setenv("OMPI_COMM_WORLD_SIZE", "3", 1);
  setenv("OMPI_COMM_WORLD_RANK", "2", 1);
  EXPECT_EQ(launch_from_environment().processes, 3);
  EXPECT_EQ(launch_from_environment().rank, 2);
}

TEST_F(LaunchEnvironment, IgnoresWhatIsNotANumber) {
  setenv("OMPI_COMM_WORLD_SIZE", "many", 1);
  EXPECT_EQ(launch_from_environment().processes, 1);
}

}  // namespace
}  // namespace pdmpm::dist
