#include "solver/core/stencil.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace pdmpm::core {

template <int D>
Stencil<D> Stencil<D>::build(double ratio) {
  Stencil st;
  const double limit = ratio * ratio * (1.0 + 1e-10);
  const int reach = static_cast<int>(std::floor(ratio * (1.0 + 1e-10)));
  IVec<D> o = IVec<D>::Constant(-reach);
  std::vector<IVec<D>> found;
  while (true) {
    const int n2 = o.squaredNorm();
    if (n2 > 0 && n2 <= limit) found.push_back(o);
    int a = 0;
    for (; a < D; ++a) {
      if (++o[a] <= reach) break;
      o[a] = -reach;
    }
    if (a == D) break;
  }
  std::sort(found.begin(), found.end(), [](const IVec<D>& x, const IVec<D>& y) {
    const int nx = x.squaredNorm(), ny = y.squaredNorm();
    if (nx != ny) return nx < ny;
    return std::lexicographical_compare(x.data(), x.data() + D, y.data(), y.data() + D);
  });
  st.offset = std::move(found);
  for (const auto& off : st.offset) st.length2.push_back(off.squaredNorm());
  return st;
}

template struct Stencil<1>;
template struct Stencil<2>;
template struct Stencil<3>;

}  // namespace pdmpm::core
