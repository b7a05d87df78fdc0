#pragma once
// R × C matrices of many particles stored entry by entry: one array per entry
// (structure of arrays), so the lane passes read and write eight particles' entry
// (i, j) with vector loads and stores where the schedule visits consecutive
// particles. A matrix is read and written whole through get / set.
#include <array>
#include <cstddef>
#include <vector>

#include "solver/core/types.hpp"

namespace pdmpm::mpm {

template <int R, int C>
class MatrixArrays {
 public:
  using Matrix = Eigen::Matrix<double, R, C>;

  Index size() const { return static_cast<Index>(entries_[0].size()); }
  void resize(Index n, const Matrix& fill) {
    for (int j = 0; j < C; ++j)
      for (int i = 0; i < R; ++i) entries_[i + R * j].resize(static_cast<std::size_t>(n), fill(i, j));
  }
  Matrix get(Index p) const {
    Matrix m;
    for (int j = 0; j < C; ++j)
      for (int i = 0; i < R; ++i) m(i, j) = entries_[i + R * j][p];
    return m;
  }
  void set(Index p, const Matrix& m) {
    for (int j = 0; j < C; ++j)
      for (int i = 0; i < R; ++i) entries_[i + R * j][p] = m(i, j);
  }
  double* entry(int i, int j) { return entries_[i + R * j].data(); }
  const double* entry(int i, int j) const { return entries_[i + R * j].data(); }

  // The matrices as one array (a checkpoint's layout) and back.
  std::vector<Matrix> packed() const {
    std::vector<Matrix> all(static_cast<std::size_t>(size()));
    for (Index p = 0; p < size(); ++p) all[p] = get(p);
    return all;
  }
  void unpack(const std::vector<Matrix>& all) {
    resize(static_cast<Index>(all.size()), Matrix::Zero());
    for (Index p = 0; p < size(); ++p) set(p, all[p]);
  }

 private:
  std::array<std::vector<double>, R * C> entries_;  // column-major: entry (i, j) at i + R j
};

// The in-plane block's entries (0, 0), (1, 0), (0, 1), (1, 1).
template <int R, int C>
std::array<const double*, 4> in_plane(const MatrixArrays<R, C>& m) {
  return {m.entry(0, 0), m.entry(1, 0), m.entry(0, 1), m.entry(1, 1)};
}

}  // namespace pdmpm::mpm
