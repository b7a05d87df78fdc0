#include "solver/core/cell_list.hpp"

#include <cmath>

#include "solver/core/error.hpp"

namespace pdmpm::core {

template <int D>
void CellList<D>::build(const std::vector<Vec<D>>& points, double cell_size) {
  h_ = cell_size;
  if (points.empty()) {
    n_ = IVec<D>::Ones();
    start_.assign(2, 0);
    items_.clear();
    return;
  }
  Vec<D> lo = points[0], hi = points[0];
  for (const auto& x : points) {
    if (!x.allFinite()) throw RunError("non-finite particle position in the cell list");
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  fill(points, lo, hi, nullptr);
}

template <int D>
void CellList<D>::build(const std::vector<Vec<D>>& points, double cell_size, const Vec<D>& lo, const Vec<D>& hi,
                        const std::vector<Index>& order) {
  if (order.size() != points.size()) throw RunError("cell list: the order does not list every point once");
  h_ = cell_size;
  fill(points, lo, hi, &order);
}

template <int D>
void CellList<D>::fill(const std::vector<Vec<D>>& points, const Vec<D>& lo, const Vec<D>& hi,
                       const std::vector<Index>* order) {
  lo_ = lo;
  std::int64_t total = 1;
  for (int a = 0; a < D; ++a) {
    // Cap the grid so a body flying apart cannot ask for unbounded memory; an empty box
    // (no points) is one cell.
    const double cells = hi[a] >= lo[a] ? std::floor((hi[a] - lo[a]) / h_) + 1.0 : 1.0;
    n_[a] = static_cast<std::int32_t>(std::min(cells, 1e6));
    total *= n_[a];
  }
  if (total > std::int64_t{1} << 31) throw RunError("cell list too large: particles spread over too big a region");
  start_.assign(static_cast<std::size_t>(total) + 1, 0);
  std::vector<std::int64_t> cell(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    cell[i] = flat(cell_of(points[i]));
    ++start_[cell[i] + 1];
  }
  for (std::int64_t k = 0; k < total; ++k) start_[k + 1] += start_[k];
  items_.resize(points.size());
  std::vector<std::int64_t> next(start_.begin(), start_.end() - 1);
  for (std::size_t s = 0; s < points.size(); ++s) {
    const auto i = order ? static_cast<std::size_t>((*order)[s]) : s;
    items_[next[cell[i]]++] = static_cast<Index>(i);
  }
}

template class CellList<1>;
template class CellList<2>;
template class CellList<3>;

}  // namespace pdmpm::core
