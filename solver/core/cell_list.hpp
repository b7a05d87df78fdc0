#pragma once
// Uniform-grid binning of points (counting sort, O(N), deterministic order) for
// searches in the deformed configuration, e.g. short-range contact.
#include <vector>

#include "solver/core/types.hpp"

namespace pdmpm::core {

template <int D>
class CellList {
 public:
  // Cells over the points' bounding box; a cell's points in index order.
  void build(const std::vector<Vec<D>>& points, double cell_size);
  // Cells over [lo, hi] (a box that holds every point, e.g. a distributed body's, agreed by
  // every process); a cell's points in the order of `order` (a permutation of the indices).
  void build(const std::vector<Vec<D>>& points, double cell_size, const Vec<D>& lo, const Vec<D>& hi,
             const std::vector<Index>& order);

  // Calls f(j) for every point in the 3^D cells around x (a superset of the
  // points within one cell size of x), in a fixed order.
  template <class F>
  void for_each_near(const Vec<D>& x, F&& f) const {
    IVec<D> c = cell_of(x);
    IVec<D> o = IVec<D>::Constant(-1);
    while (true) {
      const IVec<D> q = c + o;
      bool inside = true;
      for (int a = 0; a < D; ++a) inside = inside && q[a] >= 0 && q[a] < n_[a];
      if (inside) {
        const std::int64_t k = flat(q);
        for (std::int64_t s = start_[k]; s < start_[k + 1]; ++s) f(items_[s]);
      }
      int a = 0;
      for (; a < D; ++a) {
        if (++o[a] <= 1) break;
        o[a] = -1;
      }
      if (a == D) break;
    }
  }

 private:
  IVec<D> cell_of(const Vec<D>& x) const {
    IVec<D> c;
    for (int a = 0; a < D; ++a) {
      const double f = (x[a] - lo_[a]) / h_;
      c[a] = f < 0 ? 0 : f >= n_[a] ? n_[a] - 1 : static_cast<std::int32_t>(f);
    }
    return c;
  }
  std::int64_t flat(const IVec<D>& c) const {
    std::int64_t k = 0;
    for (int a = D - 1; a >= 0; --a) k = k * n_[a] + c[a];
    return k;
  }

  void fill(const std::vector<Vec<D>>& points, const Vec<D>& lo, const Vec<D>& hi, const std::vector<Index>* order);

  Vec<D> lo_ = Vec<D>::Zero();
  double h_ = 1.0;
  IVec<D> n_ = IVec<D>::Ones();
  std::vector<std::int64_t> start_{0, 0};
  std::vector<Index> items_;
};

}  // namespace pdmpm::core
