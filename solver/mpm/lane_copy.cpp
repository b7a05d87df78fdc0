#include "solver/mpm/lane_copy.hpp"

#include "solver/mpm/lanes.hpp"

namespace pdmpm::mpm {

namespace {

template <int W>
__attribute__((always_inline)) inline void copy_lanes_by(const LaneCopy* copies, int count) {
  using V = Lanes<W>;
  for (int i = 0; i < count; ++i)
    for (int c0 = 0; c0 < kCopyLanes; c0 += W) V::store(copies[i].to + c0, V::load(copies[i].from + c0));
}

void copy_lanes_sse2(const LaneCopy* c, int n) { copy_lanes_by<2>(c, n); }
__attribute__((target("avx2"))) void copy_lanes_avx2(const LaneCopy* c, int n) { copy_lanes_by<4>(c, n); }
__attribute__((target("avx512f"))) void copy_lanes_avx512(const LaneCopy* c, int n) { copy_lanes_by<8>(c, n); }

}  // namespace

std::vector<LaneVariant<CopyLanesFunction>> copy_lanes_variants() {
  return lane_variants<CopyLanesFunction>(copy_lanes_sse2, copy_lanes_avx2, copy_lanes_avx512);
}

void copy_lanes(const LaneCopy* copies, int count) {
  static const CopyLanesFunction chosen = choose_lane_variant(copy_lanes_variants());
  chosen(copies, count);
}

}  // namespace pdmpm::mpm
