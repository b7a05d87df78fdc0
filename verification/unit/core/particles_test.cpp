#include "solver/core/particles.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

namespace pdmpm::core {
namespace {

// Stands in for the other processes: remote ghosts receive 100 + their index, and
// the processes "before" this one have summed 0.5 into every partial sum.
class FakeProcesses final : public OtherProcesses {
 public:
  explicit FakeProcesses(Index n_real) : n_real_(n_real) {}
  void fill(double* data, int width) const override {
    for (int g = 0; g < 2; ++g)
      for (int c = 0; c < width; ++c) data[(n_real_ + 1 + g) * width + c] = 100.0 + g;
  }
  void ordered_sum(double* partial, int n, const std::function<void(double*)>& add_own) const override {
    for (int k = 0; k < n; ++k) partial[k] += 0.5;
    add_own(partial);
  }
  // The others' largest value is 7; this process's particles start at global index 40.
  double max(double local) const override { return std::max(local, 7.0); }
  Index first_global() const override { return 40; }
  void fill_reverse_sides(const double*, double*) const override {}
  int processes() const override { return 2; }
  int rank() const override { return 1; }
  Index ghost_global(Index g) const override { return g; }
  int ghost_owner_rank(Index) const override { return 0; }
  std::vector<std::vector<double>> send_to(const std::vector<std::vector<double>>& to) const override { return to; }

 private:
  Index n_real_;
};

// Three real particles, one mirror ghost of particle 2 (x reflected), two remote ghosts.
Particles<2> store() {
  Particles<2> p;
  p.lattice.spacing = 1.0;
  for (int i = 0; i < 6; ++i) p.push_back(IVec<2>(i, 0), 1.0);
  p.n_real = 3;
  p.ghost_owner = {2, Particles<2>::kRemoteOwner, Particles<2>::kRemoteOwner};
  p.ghost_sign = {Vec<2>(-1.0, 1.0), Vec<2>::Ones(), Vec<2>::Ones()};
  for (Index i = 0; i < 3; ++i) p.u[i] = Vec<2>(1.0 + i, 2.0 + i);
  return p;
}

TEST(Particles, MirrorGhostsCopyTheirOwnerRemoteOnesReceive) {
  auto p = store();
  p.update_ghosts();  // no other processes: remote ghosts keep what they had
  EXPECT_EQ(p.u[3], Vec<2>(-3.0, 4.0));
  EXPECT_EQ(p.u[4], Vec<2>::Zero());
  p.remote = std::make_shared<FakeProcesses>(p.n_real);
  p.update_ghosts();
  EXPECT_EQ(p.u[3], Vec<2>(-3.0, 4.0));
  EXPECT_EQ(p.u[4], Vec<2>(100.0, 100.0));
  EXPECT_EQ(p.u[5], Vec<2>(101.0, 101.0));
  std::vector<double> theta{1.0, 2.0, 3.0, 0.0, 0.0, 0.0};
  p.fill_ghosts(theta);
  EXPECT_EQ(theta, (std::vector<double>{1.0, 2.0, 3.0, 3.0, 100.0, 101.0}));
  EXPECT_EQ(p.source(3), 2);
  EXPECT_EQ(p.source(4), 4);
}

TEST(Particles, SumsContinueThoseOfTheProcessesBefore) {
  auto p = store();
  const auto add = [&](double* s) {
    for (Index i = 0; i < p.n_real; ++i) s[0] += p.u[i][0], s[1] += p.u[i][1];
  };
  EXPECT_EQ((p.sum_in_order<2>(add)), (std::array<double, 2>{6.0, 9.0}));
  EXPECT_EQ((p.sum_in_order<2>(add, {1.0, 1.0})), (std::array<double, 2>{7.0, 10.0}));
  p.remote = std::make_shared<FakeProcesses>(p.n_real);
  EXPECT_EQ((p.sum_in_order<2>(add)), (std::array<double, 2>{6.5, 9.5}));
}

TEST(Particles, MaximaAndGlobalIndicesSpanTheProcesses) {
  auto p = store();
  EXPECT_EQ(p.max_everywhere(3.0), 3.0);
  EXPECT_EQ(p.global_index(2), 2);
  p.remote = std::make_shared<FakeProcesses>(p.n_real);
  EXPECT_EQ(p.max_everywhere(3.0), 7.0);
  EXPECT_EQ(p.max_everywhere(9.0), 9.0);
  EXPECT_EQ(p.global_index(2), 42);
}

}  // namespace
}  // namespace pdmpm::core
