#include "solver/mpm/grid_boundary.hpp"

#include <algorithm>
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
GridBoundary<D>::GridBoundary(const std::vector<GridBc<D>>& bcs, const Grid<D>& grid)
    : bcs_(bcs), node0_(grid.node0), h_(grid.h), n_(grid.n) {
  nodes_.resize(bcs.size());
  positions_.resize(bcs.size());
  weight_.resize(bcs.size());
  offset_.assign(bcs.size(), Vec<D>::Zero());
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
    collect_nodes(b);
  }
}

template <int D>
void GridBoundary<D>::collect_nodes(std::size_t b) {
  const GridBc<D>& bc = bcs_[b];
  const double tol = 1e-9 * h_;
  const Vec<D> lo = bc.min + offset_[b], hi = bc.max + offset_[b];
  const bool moving = bc.moving && bc.kind == BcKind::velocity;
  nodes_[b].clear();
  positions_[b].clear();
  weight_[b].clear();
  // Only the nodes of the box's index range (a node of margin covers the tolerance and
  // the moving box's one-cell hold ramp): a moving box is collected every step.
  IVec<D> first, last;
  Index count = 1;
  for (int a = 0; a < D; ++a) {
    const double top = static_cast<double>(n_[a] - 1);
    const double from = std::floor((lo[a] - node0_[a]) / h_) - 1.0, to = std::ceil((hi[a] - node0_[a]) / h_) + 1.0;
    first[a] = from > 0.0 ? static_cast<Index>(std::min(from, top)) : 0;  // NaN: the whole axis
    last[a] = to < top ? static_cast<Index>(std::max(to, 0.0)) : n_[a] - 1;
    count *= std::max<Index>(0, last[a] - first[a] + 1);
  }
  IVec<D> k = first;
  for (Index visited = 0; visited < count; ++visited) {
    Index i = 0;
    for (int a = D - 1; a >= 0; --a) i = i * n_[a] + k[a];     // x fastest, as the node index
    const Vec<D> x = node0_ + h_ * k.template cast<double>();  // Grid::position(i)
    bool inside = true;
    double w = 1.0;
    for (int a = 0; a < D; ++a) {
      if (moving && bc.components[a]) {  // faces it moves across: the hold ramps over a cell
        w *= std::clamp((x[a] - lo[a]) / h_ + 0.5, 0.0, 1.0) * std::clamp((hi[a] - x[a]) / h_ + 0.5, 0.0, 1.0);
        inside = inside && w > 1e-9;  // a face on a node lets it go (round-off of the travel aside)
      } else {
        inside = inside && x[a] >= lo[a] - tol && x[a] <= hi[a] + tol;
      }
    }
    if (inside) {
      nodes_[b].push_back(i);
      positions_[b].push_back(x);
      if (moving) weight_[b].push_back(w);
    }
    for (int a = 0; a < D && ++k[a] > last[a]; ++a) k[a] = first[a];
  }
}

template <int D>
void GridBoundary<D>::advance(double t, double dt) {
  for (std::size_t b = 0; b < bcs_.size(); ++b) {
    const GridBc<D>& bc = bcs_[b];
    if (!bc.moving || bc.kind != BcKind::velocity) continue;
    auto velocity = [&](double time) {
      const Vec<D> centre = 0.5 * (bc.min + bc.max) + offset_[b];
      const Vec<D> v = bc.velocity_field ? bc.velocity_field(centre, time) : bc.velocity;
      Vec<D> out = Vec<D>::Zero();
      for (int a = 0; a < D; ++a)
        if (bc.components[a]) out[a] = ramp(time, bc.ramp_time) * v[a];
      return out;
    };
    offset_[b] += 0.5 * dt * (velocity(t) + velocity(t + dt));
    collect_nodes(b);
  }
}

template <int D>
void GridBoundary<D>::refresh() {
  for (std::size_t b = 0; b < bcs_.size(); ++b)
    if (bcs_[b].kind != BcKind::symmetry) collect_nodes(b);
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
                                std::vector<Vec<D>>* reactions, std::vector<NodeTerm>* terms) const {
  if (reactions) reactions->assign(bcs_.size(), Vec<D>::Zero());
  for (std::size_t b = 0; b < bcs_.size(); ++b) {
    const GridBc<D>& bc = bcs_[b];
    if (bc.kind == BcKind::symmetry) continue;
    const double r = ramp(t, bc.ramp_time);
    const std::optional<Vec<D>> uniform = bc.kind == BcKind::velocity ? uniform_velocity(b, t) : std::nullopt;
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
          const Vec<D> target = prescribed(b, n, t, uniform);
          if (weight_[b].empty()) {
            for (int a = 0; a < D; ++a)
              if (bc.components[a]) v[i][a] = r * target[a];
          } else {
            const double w = weight_[b][n];
            for (int a = 0; a < D; ++a)
              if (bc.components[a]) v[i][a] = w * (r * target[a]) + (1.0 - w) * v[i][a];
          }
        } break;
        case BcKind::symmetry:
          break;
      }
      if (reactions && mass && dt > 0.0) {
        const Vec<D> term = real_share(i) * (*mass)[i] * (v[i] - before) / dt;
        if (terms)
          terms->push_back({b, i, term});
        else
          (*reactions)[b] += term;
      }
    }
  }
}

template <int D>
std::optional<Vec<D>> GridBoundary<D>::uniform_velocity(std::size_t b, double t) const {
  const GridBc<D>& bc = bcs_[b];
  if (!bc.velocity_field) return bc.velocity;
  if (bc.field_depends_on_position) return std::nullopt;
  return bc.velocity_field(Vec<D>::Zero(), t);
}

template <int D>
Vec<D> GridBoundary<D>::prescribed(std::size_t b, std::size_t n, double t, const std::optional<Vec<D>>& uniform) const {
  return uniform ? *uniform : bcs_[b].velocity_field(positions_[b][n], t);
}

template <int D>
double GridBoundary<D>::constraint_power(const std::vector<Vec<D>>& f, double t, std::vector<NodeTerm>* terms) const {
  double power = 0.0;
  for (std::size_t b = 0; b < bcs_.size(); ++b) {
    const GridBc<D>& bc = bcs_[b];
    if (bc.kind != BcKind::velocity) continue;  // fixed, roller and symmetry do no work
    const double r = ramp(t, bc.ramp_time);
    const std::optional<Vec<D>> uniform = uniform_velocity(b, t);
    for (std::size_t n = 0; n < nodes_[b].size(); ++n) {
      const Index i = nodes_[b][n];
      const Vec<D> target = prescribed(b, n, t, uniform);
      const double w = weight_[b].empty() ? 1.0 : weight_[b][n];  // the held share of the node
      Vec<D> term = Vec<D>::Zero();
      for (int a = 0; a < D; ++a)
        if (bc.components[a]) term[a] = w * real_share(i) * f[i][a] * r * target[a];
      if (terms) {
        terms->push_back({b, i, term});
        continue;
      }
      for (int a = 0; a < D; ++a)
        if (bc.components[a]) power -= term[a];
    }
  }
  return power;
}

template class GridBoundary<1>;
template class GridBoundary<2>;
template class GridBoundary<3>;

}  // namespace pdmpm::mpm
