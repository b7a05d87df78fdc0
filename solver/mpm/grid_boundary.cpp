#include "solver/mpm/grid_boundary.hpp"

#include <cmath>

namespace pdmpm::mpm {

namespace {

// Mirror folding reaches this many node layers beyond a plane; a particle touches
// nodes at most 1.5 h from itself (GIMP with lp ≤ h/2), so 2 would do.
constexpr int kFoldLayers = 3;

template <int D>
Vec<D> reflect(Vec<D> v, int axis) {
  v[axis] = -v[axis];
  return v;
}

}  // namespace

template <int D>
GridBoundary<D>::GridBoundary(const std::vector<GridBc<D>>& bcs, const Grid<D>& grid) : bcs_(bcs) {
  nodes_.resize(bcs.size());
  positions_.resize(bcs.size());
  const double tol = 1e-9 * grid.h;
  for (std::size_t b = 0; b < bcs.size(); ++b) {
    const GridBc<D>& bc = bcs[b];
    if (bc.kind == BcKind::symmetry) {
      const int a = bc.axis;
      const int k0 = static_cast<int>(std::lround((bc.position - grid.node0[a]) / grid.h));
      std::vector<MirrorPair> pairs;
      std::vector<Index> on_plane;
      for (Index i = 0; i < grid.size(); ++i) {
        const IVec<D> k = grid.coords(i);
        const int offset = (k[a] - k0) * bc.side;  // > 0 inside the body's half-space
        if (offset == 0) on_plane.push_back(i);
        if (offset < 0 && offset >= -kFoldLayers) {
          IVec<D> m = k;
          m[a] = k0 - (k[a] - k0);
          if (m[a] >= 0 && m[a] < grid.n[a]) pairs.push_back({i, grid.index(m), a});
        }
      }
      if (share_.empty()) share_.assign(static_cast<std::size_t>(grid.size()), 1.0);
      for (Index i : on_plane) share_[i] *= 0.5;
      pairs_.push_back(std::move(pairs));
      plane_nodes_.push_back({std::move(on_plane), a});
      continue;
    }
    for (Index i = 0; i < grid.size(); ++i) {
      const Vec<D> x = grid.position(i);
      bool inside = true;
      for (int a = 0; a < D; ++a) inside = inside && x[a] >= bc.min[a] - tol && x[a] <= bc.max[a] + tol;
      if (inside) {
        nodes_[b].push_back(i);
        positions_[b].push_back(x);
      }
    }
  }
}

template <int D>
void GridBoundary<D>::fold(std::vector<double>* mass, std::vector<Vec<D>>* vec1, std::vector<Vec<D>>* vec2,
                           std::vector<Vec<D>>* vec3) const {
  std::vector<Vec<D>>* vecs[3] = {vec1, vec2, vec3};
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    for (const MirrorPair& mp : pairs_[p]) {
      if (mass) {
        (*mass)[mp.inside] += (*mass)[mp.outside];
        (*mass)[mp.outside] = 0.0;
      }
      for (auto* v : vecs)
        if (v) {
          (*v)[mp.inside] += reflect<D>((*v)[mp.outside], mp.axis);
          (*v)[mp.outside] = Vec<D>::Zero();
        }
    }
    const int axis = plane_nodes_[p].second;
    for (Index i : plane_nodes_[p].first) {
      if (mass) (*mass)[i] *= 2.0;
      for (auto* v : vecs)
        if (v) (*v)[i] += reflect<D>((*v)[i], axis);
    }
  }
}

template <int D>
void GridBoundary<D>::mirror(std::vector<Vec<D>>& v) const {
  for (const auto& pairs : pairs_)
    for (const MirrorPair& mp : pairs) v[mp.outside] = reflect<D>(v[mp.inside], mp.axis);
}

template <int D>
void GridBoundary<D>::constrain(std::vector<Vec<D>>& v, double t, const std::vector<double>* mass, double dt,
                                std::vector<Vec<D>>* reactions) const {
  if (reactions) reactions->assign(bcs_.size(), Vec<D>::Zero());
  for (std::size_t b = 0; b < bcs_.size(); ++b) {
    const GridBc<D>& bc = bcs_[b];
    if (bc.kind == BcKind::symmetry) continue;
    const double r = ramp(t, bc.ramp_time);
    for (std::size_t n = 0; n < nodes_[b].size(); ++n) {
      const Index i = nodes_[b][n];
      const Vec<D> before = v[i];
      switch (bc.kind) {
        case BcKind::fixed:
          v[i].setZero();
          break;
        case BcKind::roller:
          v[i][bc.axis] = 0.0;
          break;
        case BcKind::velocity: {
          const Vec<D> target = prescribed(b, n, t);
          for (int a = 0; a < D; ++a)
            if (bc.components[a]) v[i][a] = r * target[a];
        } break;
        case BcKind::symmetry:
          break;
      }
      if (reactions && mass && dt > 0.0) (*reactions)[b] += real_share(i) * (*mass)[i] * (v[i] - before) / dt;
    }
  }
}

template <int D>
Vec<D> GridBoundary<D>::prescribed(std::size_t b, std::size_t n, double t) const {
  const GridBc<D>& bc = bcs_[b];
  return bc.velocity_field ? bc.velocity_field(positions_[b][n], t) : bc.velocity;
}

template <int D>
double GridBoundary<D>::constraint_power(const std::vector<Vec<D>>& f, double t) const {
  double power = 0.0;
  for (std::size_t b = 0; b < bcs_.size(); ++b) {
    const GridBc<D>& bc = bcs_[b];
    if (bc.kind != BcKind::velocity) continue;  // fixed, roller and symmetry do no work
    const double r = ramp(t, bc.ramp_time);
    for (std::size_t n = 0; n < nodes_[b].size(); ++n) {
      const Index i = nodes_[b][n];
      const Vec<D> target = prescribed(b, n, t);
      for (int a = 0; a < D; ++a)
        if (bc.components[a]) power -= real_share(i) * f[i][a] * r * target[a];
    }
  }
  return power;
}

template class GridBoundary<1>;
template class GridBoundary<2>;
template class GridBoundary<3>;

}  // namespace pdmpm::mpm
