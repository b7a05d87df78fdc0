#include "solver/mpm/nonlocal.hpp"

#include <cmath>
#include <limits>

#include "solver/mpm/parallel.hpp"

namespace pdmpm::mpm {

template <int D>
void nonlocal_average(const std::vector<Vec<D>>& x, const std::vector<double>& volume, const std::vector<double>& a,
                      const std::vector<std::uint8_t>& use, double length, std::vector<double>& out) {
  const Index n = static_cast<Index>(x.size());
  out.assign(x.size(), 0.0);
  const double cutoff = 3.0 * length;
  Vec<D> lo = Vec<D>::Constant(std::numeric_limits<double>::infinity());
  Vec<D> hi = -lo;
  for (Index i = 0; i < n; ++i)
    if (use[i]) {
      lo = lo.cwiseMin(x[i]);
      hi = hi.cwiseMax(x[i]);
    }
  if (!(lo[0] <= hi[0])) return;
  IVec<D> nc;
  Index ncell = 1;
  for (int ax = 0; ax < D; ++ax) {
    nc[ax] = static_cast<std::int32_t>(std::floor((hi[ax] - lo[ax]) / cutoff)) + 1;
    ncell *= nc[ax];
  }
  auto cell_of = [&](const Vec<D>& p) {
    IVec<D> c;
    for (int ax = 0; ax < D; ++ax)
      c[ax] = std::min(nc[ax] - 1, static_cast<std::int32_t>(std::floor((p[ax] - lo[ax]) / cutoff)));
    return c;
  };
  auto flat = [&](const IVec<D>& c) {
    Index f = 0, s = 1;
    for (int ax = 0; ax < D; ++ax) {
      f += c[ax] * s;
      s *= nc[ax];
    }
    return f;
  };
  std::vector<Index> start(static_cast<std::size_t>(ncell) + 1, 0), order;
  for (Index i = 0; i < n; ++i)
    if (use[i]) ++start[flat(cell_of(x[i])) + 1];
  for (Index c = 0; c < ncell; ++c) start[c + 1] += start[c];
  order.resize(static_cast<std::size_t>(start[ncell]));
  std::vector<Index> fill(start.begin(), start.end() - 1);
  for (Index i = 0; i < n; ++i)
    if (use[i]) order[fill[flat(cell_of(x[i]))]++] = i;

#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (Index i = 0; i < n; ++i) {
    if (!use[i]) continue;
    const IVec<D> c = cell_of(x[i]);
    double num = 0.0, den = 0.0;
    IVec<D> d = IVec<D>::Constant(-1);
    while (true) {
      IVec<D> cc = c + d;
      bool ok = true;
      for (int ax = 0; ax < D; ++ax) ok = ok && cc[ax] >= 0 && cc[ax] < nc[ax];
      if (ok) {
        const Index f = flat(cc);
        for (Index k = start[f]; k < start[f + 1]; ++k) {
          const Index j = order[k];
          const double r = (x[j] - x[i]).norm();
          if (r > cutoff) continue;
          const double w = std::exp(-(r / length) * (r / length)) * volume[j];
          num += w * a[j];
          den += w;
        }
      }
      int ax = 0;
      for (; ax < D; ++ax) {
        if (++d[ax] <= 1) break;
        d[ax] = -1;
      }
      if (ax == D) break;
    }
    out[i] = den > 0.0 ? num / den : a[i];
  }
}

template void nonlocal_average<1>(const std::vector<Vec<1>>&, const std::vector<double>&, const std::vector<double>&,
                                  const std::vector<std::uint8_t>&, double, std::vector<double>&);
template void nonlocal_average<2>(const std::vector<Vec<2>>&, const std::vector<double>&, const std::vector<double>&,
                                  const std::vector<std::uint8_t>&, double, std::vector<double>&);
template void nonlocal_average<3>(const std::vector<Vec<3>>&, const std::vector<double>&, const std::vector<double>&,
                                  const std::vector<std::uint8_t>&, double, std::vector<double>&);

}  // namespace pdmpm::mpm
