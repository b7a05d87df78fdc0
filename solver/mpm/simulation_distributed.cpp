// The parts of the MPM step a distributed run adds (solver/mpm/other_processes.hpp,
// docs/models/distributed.md): ghosts of the other processes' points for the scatter, and
// the grid's sums taken over every process's nodes in one process's order.
#include <algorithm>

#include "solver/mpm/simulation.hpp"

namespace pdmpm::mpm {

namespace {

// Node blocks of the reach: a point in cell c writes to nodes c − 1 … c + 2 per axis
// (scatter_schedule.hpp), so flagging those nodes' blocks covers every stencil.
constexpr Index kReachBlock = 4;  // nodes per axis

template <int D>
IVec<D> reach_blocks(const IVec<D>& nodes) {
  IVec<D> b;
  for (int a = 0; a < D; ++a) b[a] = (nodes[a] + kReachBlock - 1) / kReachBlock;
  return b;
}

// The blocks [lo, hi] per axis the nodes c − 1 … c + 2 of cell c fall in.
template <int D>
void blocks_of_cell(const IVec<D>& cell, const IVec<D>& nodes, IVec<D>& lo, IVec<D>& hi) {
  for (int a = 0; a < D; ++a) {
    lo[a] = std::max<Index>(cell[a] - 1, 0) / kReachBlock;
    hi[a] = std::min<Index>(cell[a] + 2, nodes[a] - 1) / kReachBlock;
  }
}

// fn(index, coordinates) for every cell of the box [lo, hi] of a grid of `dims` (blocks, nodes;
// first axis fastest, as the node index).
template <int D, class Fn>
void for_each_in_box(const IVec<D>& lo, const IVec<D>& hi, const IVec<D>& dims, Fn&& fn) {
  IVec<D> b = lo;
  while (true) {
    Index index = 0;
    for (int a = D - 1; a >= 0; --a) index = index * dims[a] + b[a];
    fn(index, b);
    int a = 0;
    for (; a < D && ++b[a] > hi[a]; ++a) b[a] = lo[a];
    if (a == D) return;
  }
}

// Ghost records: global index, position, GIMP half-widths, mass, velocity, volume, τ
// (the D × D block the scatter reads), external force, failed.
template <int D>
constexpr int kRecordWidth = 4 + 4 * D + D* D;

}  // namespace

template <int D>
void Simulation<D>::set_ghost_count(Index n) {
  auto& p = particles_;
  const auto size = static_cast<std::size_t>(p.n_real + n);
  p.site.resize(size, IVec<D>::Zero());
  p.x0.resize(size);
  p.u.resize(size, Vec<D>::Zero());
  p.v.resize(size);
  p.f.resize(size, Vec<D>::Zero());
  p.b.resize(size, Vec<D>::Zero());
  p.volume.resize(size);
  p.kind.resize(size, core::ParticleKind::mpm);
  p.ghost_owner.assign(static_cast<std::size_t>(n), core::Particles<D>::kRemoteOwner);
  p.ghost_sign.assign(static_cast<std::size_t>(n), Vec<D>::Ones());
  state_.resize(p.n_real + n);
  ext_force_.resize(size, Vec<D>::Zero());
  ghost_global_.resize(static_cast<std::size_t>(n));
}

template <int D>
void Simulation<D>::receive_ghosts() {
  const Index n_real = particles_.n_real;
  const IVec<D> nodes = grid_.n, blocks = reach_blocks<D>(nodes);
  Index block_count = 1;
  for (int a = 0; a < D; ++a) block_count *= blocks[a];
  // The blocks each own point reaches (in the order of active_), and their union.
  const std::size_t na = active_.size();
  std::vector<IVec<D>> lo(na), hi(na);
  std::vector<std::uint8_t> reach(static_cast<std::size_t>(block_count), 0);
  for (std::size_t k = 0; k < na; ++k) {
    const Vec<D> xr = particles_.position(active_[k]) - grid_.node0;
    IVec<D> cell;
    for (int a = 0; a < D; ++a)  // as compute_stencils clamps it (a point off the grid fails there)
      cell[a] = static_cast<std::int32_t>(std::clamp(xr[a] / grid_.h, 0.0, static_cast<double>(nodes[a] - 2)));
    blocks_of_cell<D>(cell, nodes, lo[k], hi[k]);
    for_each_in_box<D>(lo[k], hi[k], blocks, [&](Index b, const IVec<D>&) { reach[b] = 1; });
  }
  // Each other process needs the own points that reach a block it flags; the box around
  // its flags rules out most points at once.
  const std::vector<std::uint8_t> all = others_->all_reach(reach);
  const int processes = static_cast<int>(all.size() / reach.size()), me = others_->rank();
  std::vector<std::vector<Index>> send(static_cast<std::size_t>(processes));
  for (int q = 0; q < processes; ++q) {
    if (q == me) continue;
    const std::uint8_t* theirs = &all[static_cast<std::size_t>(q) * reach.size()];
    IVec<D> box_lo = blocks, box_hi = IVec<D>::Constant(-1);
    for_each_in_box<D>(IVec<D>::Zero(), blocks - IVec<D>::Ones(), blocks, [&](Index b, const IVec<D>& at) {
      if (theirs[b]) box_lo = box_lo.cwiseMin(at), box_hi = box_hi.cwiseMax(at);
    });
    for (std::size_t k = 0; k < na; ++k) {
      if ((hi[k].array() < box_lo.array()).any() || (lo[k].array() > box_hi.array()).any()) continue;
      bool reaches = false;
      for_each_in_box<D>(lo[k], hi[k], blocks, [&](Index b, const IVec<D>&) { reaches = reaches || theirs[b]; });
      if (reaches) send[q].push_back(active_[k]);
    }
  }
  others_->plan(std::move(send));
  // A process books, in the grid's sums, the nodes of the blocks it flags and no lower process
  // flags. It holds every point that reaches such a node: a point reaching a node reaches its
  // block, so every process flagging the block received it.
  owned_node_.assign(static_cast<std::size_t>(grid_.size()), 0);
  for_each_in_box<D>(IVec<D>::Zero(), blocks - IVec<D>::Ones(), blocks, [&](Index b, const IVec<D>& at) {
    int lowest = 0;
    while (lowest < processes && !all[static_cast<std::size_t>(lowest) * reach.size() + b]) ++lowest;
    if (lowest != me) return;
    const IVec<D> first = at * kReachBlock,
                  last = (first + IVec<D>::Constant(kReachBlock - 1)).cwiseMin(nodes - IVec<D>::Ones());
    for_each_in_box<D>(first, last, nodes, [&](Index node, const IVec<D>&) { owned_node_[node] = 1; });
  });
  const std::vector<double> in = others_->send(kRecordWidth<D>, [&](Index p, double* r) {
    *r++ = static_cast<double>(others_->first_global() + p);
    const Vec<D> x = particles_.position(p);
    const Mat<3> tau = state_.kirchhoff.get(p);
    for (int a = 0; a < D; ++a) *r++ = x[a];
    for (int a = 0; a < D; ++a) *r++ = state_.half_width[p][a];
    *r++ = state_.mass[p];
    for (int a = 0; a < D; ++a) *r++ = particles_.v[p][a];
    *r++ = particles_.volume[p];
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) *r++ = tau(i, j);
    for (int a = 0; a < D; ++a) *r++ = ext_force_[p][a];
    *r++ = state_.failed[p];
  });
  const Index n = static_cast<Index>(in.size()) / kRecordWidth<D>;
  set_ghost_count(n);
  ghosts_seen_ = n;
  bool external = false;
  for (Index g = 0; g < n; ++g) {
    const double* r = &in[static_cast<std::size_t>(g) * kRecordWidth<D>];
    const Index p = n_real + g;
    ghost_global_[g] = static_cast<Index>(*r++);
    for (int a = 0; a < D; ++a) particles_.x0[p][a] = *r++;  // u = 0: x0 + u is the position, exactly
    for (int a = 0; a < D; ++a) state_.half_width[p][a] = *r++;
    state_.mass[p] = *r++;
    for (int a = 0; a < D; ++a) particles_.v[p][a] = *r++;
    particles_.volume[p] = *r++;
    Mat<3> tau = Mat<3>::Zero();
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) tau(i, j) = *r++;
    state_.kirchhoff.set(p, tau);
    for (int a = 0; a < D; ++a) ext_force_[p][a] = *r++;
    state_.failed[p] = static_cast<std::uint8_t>(*r++);
    external = external || !ext_force_[p].isZero(0.0);
  }
  any_external_force_ = any_external_force_ || external;
}

template <int D>
std::vector<Index> Simulation<D>::own_and_ghosts() const {
  // The ghosts of lower processes (global index below this process's first), the own points,
  // the ghosts of higher processes.
  const Index first = others_->first_global(), n_real = particles_.n_real;
  const auto ghosts = static_cast<Index>(ghost_global_.size());
  const auto lower =
      static_cast<Index>(std::lower_bound(ghost_global_.begin(), ghost_global_.end(), first) - ghost_global_.begin());
  std::vector<Index> points;
  points.reserve(active_.size() + ghost_global_.size());
  for (Index g = 0; g < lower; ++g) points.push_back(n_real + g);
  points.insert(points.end(), active_.begin(), active_.end());
  for (Index g = lower; g < ghosts; ++g) points.push_back(n_real + g);
  return points;
}

template <int D>
void Simulation<D>::build_shared_scatter() {
  compute_stencils(own_and_ghosts(), shared_);
  const std::vector<Index>& order = shared_.schedule.order();
  // The own points' stencils, in their schedule's order: the same blocks, each in global
  // order, so the shared order with the ghosts left out.
  own_.stencil.resize(own_.schedule.order().size());
  std::size_t own = 0;
  for (std::size_t k = 0; k < order.size(); ++k)
    if (order[k] < particles_.n_real) own_.stencil[own++] = shared_.stencil[k];
}

template <int D>
void Simulation<D>::refresh_ghosts(GhostField field) {
  const int width = field == GhostField::velocity ? D : D * D;
  const std::vector<double> in = others_->send(width, [&](Index p, double* r) {
    if (field == GhostField::velocity) {
      for (int a = 0; a < D; ++a) *r++ = particles_.v[p][a];
      return;
    }
    const Mat<3> tau = state_.kirchhoff.get(p);
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) *r++ = tau(i, j);
  });
  const Index n_real = particles_.n_real;
  for (Index g = 0; g < static_cast<Index>(ghost_global_.size()); ++g) {
    const double* r = &in[static_cast<std::size_t>(g) * width];
    const Index p = n_real + g;
    if (field == GhostField::velocity) {
      for (int a = 0; a < D; ++a) particles_.v[p][a] = r[a];
      continue;
    }
    Mat<3> tau = Mat<3>::Zero();
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) tau(i, j) = r[i * D + j];
    state_.kirchhoff.set(p, tau);
  }
}

template <int D>
void Simulation<D>::drop_ghosts() {
  set_ghost_count(0);
}

template <int D>
void Simulation<D>::sum_node_terms(const std::vector<typename GridBoundary<D>::NodeTerm>& terms,
                                   std::vector<Vec<D>>* out, double* power) const {
  // Records: boundary, node, the D components; the nodes this process books only.
  constexpr int width = 2 + D;
  std::vector<double> mine;
  for (const auto& t : terms) {
    if (!owned_node_[t.node]) continue;
    mine.push_back(static_cast<double>(t.boundary));
    mine.push_back(static_cast<double>(t.node));
    mine.insert(mine.end(), t.value.data(), t.value.data() + D);
  }
  const std::vector<double> all = others_->all_gather(mine);
  const std::size_t records = all.size() / width;
  std::vector<std::size_t> order(records);
  for (std::size_t r = 0; r < records; ++r) order[r] = r;
  // One process's order: boundary by boundary, each over its nodes in index order.
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const double* x = &all[a * width];
    const double* y = &all[b * width];
    return x[0] != y[0] ? x[0] < y[0] : x[1] < y[1];
  });
  if (out) out->assign(boundary_.count(), Vec<D>::Zero());
  if (power) *power = 0.0;
  for (std::size_t r : order) {
    const double* x = &all[r * width];
    const Eigen::Map<const Vec<D>> value(x + 2);
    if (out) (*out)[static_cast<std::size_t>(x[0])] += value;
    if (power)  // a free component's term is 0, which leaves the sum as it is
      for (int a = 0; a < D; ++a) *power -= value[a];
  }
}

#define PDMPM_DISTRIBUTED_MEMBERS(D)                                                                  \
  template void Simulation<D>::set_ghost_count(Index);                                                \
  template void Simulation<D>::receive_ghosts();                                                      \
  template std::vector<Index> Simulation<D>::own_and_ghosts() const;                                  \
  template void Simulation<D>::build_shared_scatter();                                                \
  template void Simulation<D>::refresh_ghosts(GhostField);                                            \
  template void Simulation<D>::drop_ghosts();                                                         \
  template void Simulation<D>::sum_node_terms(const std::vector<typename GridBoundary<D>::NodeTerm>&, \
                                              std::vector<Vec<D>>*, double*) const;
PDMPM_DISTRIBUTED_MEMBERS(1)
PDMPM_DISTRIBUTED_MEMBERS(2)
PDMPM_DISTRIBUTED_MEMBERS(3)
#undef PDMPM_DISTRIBUTED_MEMBERS

}  // namespace pdmpm::mpm
