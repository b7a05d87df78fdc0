#include "solver/pd/contact_ghosts.hpp"

#include <limits>

#include "solver/core/error.hpp"

namespace pdmpm::pd {
namespace {

// Values per ghost record at a rebuild: global index, reference position, volume, position.
template <int D>
constexpr std::size_t kRecord = 2 + 2 * D;

}  // namespace

template <int D>
void ContactGhosts<D>::find(const core::Particles<D>& p, const std::vector<Vec<D>>& own, double radius) {
  const auto& others = *p.remote;
  const int processes = others.processes(), me = others.rank();
  // This process's box (empty: lo > hi), to every other process.
  constexpr double inf = std::numeric_limits<double>::infinity();
  Vec<D> lo = Vec<D>::Constant(inf), hi = Vec<D>::Constant(-inf);
  for (Index i = 0; i < p.n_real; ++i) {
    if (!own[i].allFinite()) throw RunError("non-finite particle position in the contact search");
    lo = lo.cwiseMin(own[i]);
    hi = hi.cwiseMax(own[i]);
  }
  std::vector<std::vector<double>> to(static_cast<std::size_t>(processes));
  for (int q = 0; q < processes; ++q)
    if (q != me) {
      to[q].assign(lo.data(), lo.data() + D);
      to[q].insert(to[q].end(), hi.data(), hi.data() + D);
    }
  const auto boxes = others.send_to(to);
  lo_ = lo, hi_ = hi;
  // Own particles within `radius` of another process's box (a superset of those within
  // `radius` of its particles), as records in global order.
  send_start_.assign(static_cast<std::size_t>(processes) + 1, 0);
  send_.clear();
  for (int q = 0; q < processes; ++q) {
    to[q].clear();
    if (q != me) {
      const Vec<D> qlo = Eigen::Map<const Vec<D>>(boxes[q].data()), qhi = Eigen::Map<const Vec<D>>(boxes[q].data() + D);
      lo_ = lo_.cwiseMin(qlo), hi_ = hi_.cwiseMax(qhi);
      const Vec<D> near_lo = qlo - Vec<D>::Constant(radius), near_hi = qhi + Vec<D>::Constant(radius);
      for (Index i = 0; i < p.n_real; ++i) {
        if ((own[i].array() < near_lo.array()).any() || (own[i].array() > near_hi.array()).any()) continue;
        send_.push_back(i);
        to[q].push_back(static_cast<double>(p.global_index(i)));
        to[q].insert(to[q].end(), p.x0[i].data(), p.x0[i].data() + D);
        to[q].push_back(p.volume[i]);
        to[q].insert(to[q].end(), own[i].data(), own[i].data() + D);
      }
    }
    send_start_[q + 1] = static_cast<std::int64_t>(send_.size());
  }
  const auto from = others.send_to(to);
  receive_start_.assign(static_cast<std::size_t>(processes) + 1, 0);
  global_.clear(), x0_.clear(), volume_.clear(), y_.clear();
  for (int q = 0; q < processes; ++q) {
    for (std::size_t k = 0; k < from[q].size(); k += kRecord<D>) {
      const double* r = from[q].data() + k;
      global_.push_back(static_cast<Index>(r[0]));
      x0_.push_back(Eigen::Map<const Vec<D>>(r + 1));
      volume_.push_back(r[1 + D]);
      y_.push_back(Eigen::Map<const Vec<D>>(r + 2 + D));
    }
    receive_start_[q + 1] = static_cast<std::int64_t>(global_.size());
  }
  lower_ = static_cast<Index>(receive_start_[me]);
}

template <int D>
void ContactGhosts<D>::refresh(const core::Particles<D>& p, const std::vector<Vec<D>>& own) {
  const auto& others = *p.remote;
  const int processes = others.processes();
  std::vector<std::vector<double>> to(static_cast<std::size_t>(processes));
  for (int q = 0; q < processes; ++q)
    for (std::int64_t s = send_start_[q]; s < send_start_[q + 1]; ++s)
      to[q].insert(to[q].end(), own[send_[s]].data(), own[send_[s]].data() + D);
  const auto from = others.send_to(to);
  for (int q = 0; q < processes; ++q) {
    const std::int64_t n = receive_start_[q + 1] - receive_start_[q];
    if (static_cast<std::int64_t>(from[q].size()) != n * D)
      throw RunError("contact: process " + std::to_string(q) + " sent positions for another ghost list");
    for (std::int64_t k = 0; k < n; ++k) y_[receive_start_[q] + k] = Eigen::Map<const Vec<D>>(from[q].data() + k * D);
  }
}

template <int D>
void ContactGhosts<D>::checkpoint(core::StateArchive& a) {
  a.sync("contact_ghosts/send_start", send_start_);
  a.sync("contact_ghosts/send", send_);
  a.sync("contact_ghosts/receive_start", receive_start_);
  a.sync("contact_ghosts/positions", y_);
  a.sync("contact_ghosts/reference_positions", x0_);
  a.sync("contact_ghosts/volume", volume_);
  a.sync("contact_ghosts/global", global_);
  a.sync("contact_ghosts/lower", lower_);
  a.sync("contact_ghosts/lo", lo_);
  a.sync("contact_ghosts/hi", hi_);
}

template class ContactGhosts<1>;
template class ContactGhosts<2>;
template class ContactGhosts<3>;

}  // namespace pdmpm::pd
