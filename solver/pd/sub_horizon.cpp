#include "solver/pd/sub_horizon.hpp"

#include <omp.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <sstream>
#include <utility>

namespace pdmpm::pd {
namespace {

// One sub-horizon point: position relative to the bond's first end, weight, particle.
template <int D>
struct Point {
  Vec<D> x;
  double w;
  Index id;
};

// The least-squares coefficients c_l = w_l K⁻¹ (x_l − x̄) of the points, or false if they
// are fewer than min_points or K is singular (points on a line or plane).
template <int D>
bool fit(const std::vector<Point<D>>& pts, int min_points, std::vector<Vec<D>>& coef) {
  if (static_cast<int>(pts.size()) < min_points) return false;
  double W = 0.0;
  Vec<D> centre = Vec<D>::Zero();
  for (const auto& p : pts) W += p.w, centre += p.w * p.x;
  centre /= W;
  Mat<D> K = Mat<D>::Zero();
  for (const auto& p : pts) K += p.w * (p.x - centre) * (p.x - centre).transpose();
  const auto ev = Eigen::SelfAdjointEigenSolver<Mat<D>>(K, Eigen::EigenvaluesOnly).eigenvalues();
  // A numerical-rank test, not a tuning: collinear points give λ_min/λ_max ~ 1e-16.
  if (!(ev.minCoeff() > 1e-10 * ev.maxCoeff())) return false;
  const Mat<D> Kinv = K.inverse();
  coef.clear();
  for (const auto& p : pts) coef.push_back(p.w * (Kinv * (p.x - centre)));
  return true;
}

// Stencil index of every difference offset_q − offset_s (−1 outside the stencil): the bond of
// j = i + offset_s to the point i + offset_q.
template <int D>
std::vector<int> difference_table(const core::Stencil<D>& st) {
  const int n = st.size();
  std::vector<int> diff(static_cast<std::size_t>(n) * n, -1);
  for (int s = 0; s < n; ++s)
    for (int q = 0; q < n; ++q) {
      const IVec<D> d = st.offset[q] - st.offset[s];
      const auto it = std::find(st.offset.begin(), st.offset.end(), d);
      if (it != st.offset.end()) diff[static_cast<std::size_t>(s) * n + q] = static_cast<int>(it - st.offset.begin());
    }
  return diff;
}

// Whether a bond with these trial flags counts: live (the current sub-horizon), or in the
// reference family (the largest it can be, the slots of the layout).
bool live_flags(std::uint8_t flags) { return flags == 0; }
bool reference_flags(std::uint8_t flags) { return !(flags & (kBondInactive | kBondCut)); }

// Whether particle j has a bond with stencil index r whose flags satisfy `linked`: from its
// family (in stencil order), or for a halo particle from the halo's table.
template <int D, class Linked>
bool bonded_at(const System<D>& sys, const HaloBonds& halo, Index j, int r, Linked linked) {
  const Index n = sys.particles.n_real;
  if (j >= n) {
    const std::uint8_t flags = halo.flags[static_cast<std::size_t>(j - n) * halo.stencil + r];
    return flags != HaloBonds::kNoBond && linked(flags);
  }
  const auto& f = sys.families;
  const auto first = f.shape.begin() + f.begin(j), last = f.shape.begin() + f.end(j);
  const auto it = std::lower_bound(first, last, static_cast<std::uint16_t>(r));
  return it != last && *it == r && linked(sys.bonds.flags.trial[it - f.shape.begin()]);
}

// The sub-horizon of bond b = i→j (stencil index s): i, j and every point bonded to both, a bond
// counting when `linked` says so (live: the current sub-horizon; in the reference family: the
// largest it can be, the slots of the layout).
template <int D, class Linked>
void gather_points(const System<D>& sys, const HaloBonds& halo, const std::vector<int>& diff, Index i, BondIndex b,
                   double end_weight, Linked linked, std::vector<Point<D>>& pts) {
  const auto& f = sys.families;
  const auto& t = sys.table;
  const auto& vol = sys.particles.volume;
  const int n = f.stencil.size();
  const Index j = f.neighbor[b];
  const int s = f.shape[b];
  pts.clear();
  pts.push_back({Vec<D>::Zero(), end_weight * vol[i], i});
  pts.push_back({t.xi[s], end_weight * vol[j], j});
  for (BondIndex c = f.begin(i); c < f.end(i); ++c) {
    const int q = f.shape[c];
    const int r = diff[static_cast<std::size_t>(s) * n + q];
    if (c == b || r < 0 || !linked(sys.bonds.flags.trial[c]) || !bonded_at(sys, halo, j, r, linked)) continue;
    pts.push_back({t.xi[q], vol[f.neighbor[c]], f.neighbor[c]});
  }
}

// Stencil index of −offset_s for every s (the stencil is symmetric).
template <int D>
std::vector<int> reverse_table(const core::Stencil<D>& st) {
  std::vector<int> rev(st.size());
  for (int s = 0; s < st.size(); ++s)
    rev[s] =
        static_cast<int>(std::find(st.offset.begin(), st.offset.end(), IVec<D>(-st.offset[s])) - st.offset.begin());
  return rev;
}

// Which bond sides to fit again since the live bits were `built_live`. The sub-horizon of b = i→j
// (offset s) reads (gather_points) the live bits of b, of i's sides i→k to points k that are in
// j's stencil too (diff[s][·] ≥ 0), and of j's sides j→k to those same points, i.e. to points in
// i's stencil (diff[−s][·] ≥ 0); everything else it reads (reference positions, volumes) is fixed
// once the families are built. A bond none of whose read bits changed keeps its coefficients,
// which are what a full build computes, bit for bit: the fit is a deterministic function of the
// same inputs (verification/unit/pd/sub_horizon_test.cpp).
template <int D>
std::vector<std::uint8_t> bonds_to_refit(const System<D>& sys, const std::vector<int>& diff,
                                         const std::vector<int>& reverse, const std::vector<std::uint8_t>& built_live,
                                         const HaloBonds& halo, const std::vector<std::uint8_t>& built_halo) {
  const auto& f = sys.families;
  const Index n = sys.particles.n_real;
  const int ns = f.stencil.size();
  std::vector<std::uint8_t> refit(f.n_bonds()), changed(f.n_bonds()), owner_changed(n);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    bool any = false;
    for (BondIndex b = f.begin(i); b < f.end(i); ++b) {
      changed[b] = built_live[b] != static_cast<std::uint8_t>(sys.bonds.live(b));
      any = any || changed[b];
    }
    owner_changed[i] = any;
  }
  // Whether a changed side of `owner` leads to a point of the overlap of bond offset s (a halo
  // particle's sides: from the halo's table, against the one last fitted).
  auto reads_a_change = [&](Index owner, int s) {
    if (owner >= n) {
      if (built_halo.size() != halo.flags.size()) return true;
      const std::size_t first = static_cast<std::size_t>(owner - n) * halo.stencil;
      for (int r = 0; r < ns; ++r)
        if ((halo.flags[first + r] == 0) != (built_halo[first + r] == 0) &&
            diff[static_cast<std::size_t>(s) * ns + r] >= 0)
          return true;
      return false;
    }
    if (!owner_changed[owner]) return false;
    for (BondIndex c = f.begin(owner); c < f.end(owner); ++c)
      if (changed[c] && diff[static_cast<std::size_t>(s) * ns + f.shape[c]] >= 0) return true;
    return false;
  };
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i)
    for (BondIndex b = f.begin(i); b < f.end(i); ++b) {
      const int s = f.shape[b];
      refit[b] = changed[b] || reads_a_change(i, s) || reads_a_change(f.neighbor[b], reverse[s]);
    }
  return refit;
}

// The slots by point, in slot order within each point: a stable counting sort in which each
// thread counts, then places, a contiguous range of bond sides, the ranges in order, so the
// result does not depend on the number of threads.
template <int D>
void sort_by_point(SubHorizon<D>& h, Index n) {
  const BondIndex nb = static_cast<BondIndex>(h.begin.size()) - 1;
  h.at_begin.assign(static_cast<std::size_t>(n) + 1, 0);
  h.at_bond.resize(h.point.size());
  h.at_coef.assign(h.point.size(), Vec<D>::Zero());
  h.entry_at.resize(h.point.size());
  std::vector<std::vector<BondIndex>> next;  // per thread: count, then the next slot, of each point
#pragma omp parallel
  {
    const int t = omp_get_thread_num(), threads = omp_get_num_threads();
#pragma omp single
    next.assign(threads, std::vector<BondIndex>(n, 0));
    const BondIndex lo = nb * t / threads, hi = nb * (t + 1) / threads;
    auto& mine = next[t];
    for (BondIndex e = h.begin[lo]; e < h.begin[hi]; ++e) ++mine[h.point[e]];
#pragma omp barrier
#pragma omp single
    {
      BondIndex at = 0;
      for (Index k = 0; k < n; ++k) {
        h.at_begin[k] = at;
        for (auto& slots : next) at += std::exchange(slots[k], at);
      }
      h.at_begin[n] = at;
    }
    for (BondIndex b = lo; b < hi; ++b)
      for (BondIndex e = h.begin[b]; e < h.begin[b + 1]; ++e) {
        const BondIndex q = mine[h.point[e]]++;
        h.at_bond[q] = b;
        h.entry_at[e] = q;
      }
  }
}

// The coefficients of bond side b for the current live bonds, written into its slots (and their
// copies by point); zero in the slots of points not in the sub-horizon now, all zero if b is not
// live. The live points are a subsequence of the slots' (both in the same order).
template <int D>
void fill(SubHorizon<D>& h, const System<D>& sys, const std::vector<int>& diff, Index i, BondIndex b, int min_points,
          double end_weight, std::vector<Point<D>>& pts, std::vector<Vec<D>>& coef) {
  const BondIndex first = h.begin[b], last = h.begin[b + 1];
  // A slot's coefficient (and its copy by point) and, for the residual, the point's volume.
  auto put = [&](BondIndex e, const Vec<D>& c, double v) {
    h.coef[e] = h.at_coef[h.entry_at[e]] = c;
    h.volume[e] = v;
  };
  h.axial[b] = 0;
  h.centroid[b] = Vec<D>::Zero();
  h.volume_inverse[b] = Mat<D>::Zero();
  h.inv_volume[b] = h.inv_second_moment[b] = 0.0;
  if (!sys.bonds.live(b)) {
    for (BondIndex e = first; e < last; ++e) put(e, Vec<D>::Zero(), 0.0);
    return;
  }
  gather_points(sys, h.halo, diff, i, b, end_weight, live_flags, pts);
  const bool residual = fit(pts, min_points, coef);
  if (!residual) {  // the axial fallback: the two ends, the first two slots
    h.axial[b] = 1;
    const Vec<D>& xi = sys.table.xi[sys.families.shape[b]];
    pts.resize(2);
    coef = {-xi / xi.squaredNorm(), xi / xi.squaredNorm()};
  } else {  // the plain fit's centroid and K⁻¹ (weights V_l, relative to x_i)
    double volume = 0.0;
    Vec<D> centre = Vec<D>::Zero();
    for (const auto& pt : pts) volume += sys.particles.volume[pt.id], centre += sys.particles.volume[pt.id] * pt.x;
    centre /= volume;
    Mat<D> K = Mat<D>::Zero();
    for (const auto& pt : pts) K += sys.particles.volume[pt.id] * (pt.x - centre) * (pt.x - centre).transpose();
    h.centroid[b] = centre;
    h.volume_inverse[b] = K.inverse();  // the same points as the weighted fit's K: not singular
    h.inv_volume[b] = 1.0 / volume;
    h.inv_second_moment[b] = 1.0 / K.trace();
  }
  std::size_t l = 0;
  for (BondIndex e = first; e < last; ++e) {
    const bool in = l < pts.size() && pts[l].id == h.point[e];
    put(e, in ? coef[l] : Vec<D>::Zero(), in && residual ? sys.particles.volume[h.point[e]] : 0.0);
    l += in;
  }
}

}  // namespace

template <int D>
SubHorizon<D> SubHorizon<D>::build(const System<D>& sys, int min_points, double end_weight, const HaloBonds& halo) {
  for (const Index owner : sys.particles.ghost_owner)
    if (owner != core::Particles<D>::kRemoteOwner)
      throw std::invalid_argument("hpd does not support ghost particles (symmetry planes) yet");
  const auto& f = sys.families;
  const BondIndex nb = f.n_bonds();
  const Index n = sys.particles.n_real;
  SubHorizon h;
  h.diff = difference_table(f.stencil);
  h.reverse = reverse_table(f.stencil);
  const auto& diff = h.diff;
  auto in_family = [&](BondIndex c) { return sys.bonds.in_reference_family(c); };
  h.halo = halo;
  h.begin.assign(nb + 1, 0);
  // The slots: per bond side of the reference family, its largest sub-horizon.
#pragma omp parallel
  {
    std::vector<Point<D>> pts;
#pragma omp for schedule(static)
    for (Index i = 0; i < n; ++i)
      for (BondIndex b = f.begin(i); b < f.end(i); ++b)
        if (in_family(b)) {
          gather_points(sys, h.halo, diff, i, b, end_weight, reference_flags, pts);
          h.begin[b + 1] = static_cast<BondIndex>(pts.size());
        }
#pragma omp single
    {
      for (BondIndex b = 0; b < nb; ++b) h.begin[b + 1] += h.begin[b];
      h.point.resize(h.begin[nb]);
      h.coef.assign(h.begin[nb], Vec<D>::Zero());
      h.volume.assign(h.begin[nb], 0.0);
    }
#pragma omp for schedule(static)
    for (Index i = 0; i < n; ++i)
      for (BondIndex b = f.begin(i); b < f.end(i); ++b)
        if (in_family(b)) {
          gather_points(sys, h.halo, diff, i, b, end_weight, reference_flags, pts);
          for (std::size_t l = 0; l < pts.size(); ++l) h.point[h.begin[b] + static_cast<BondIndex>(l)] = pts[l].id;
        }
  }
  sort_by_point(h, sys.particles.size());
  h.axial.assign(nb, 0);
  h.centroid.assign(nb, Vec<D>::Zero());
  h.volume_inverse.assign(nb, Mat<D>::Zero());
  h.inv_volume.assign(nb, 0.0);
  h.inv_second_moment.assign(nb, 0.0);
  h.built_live.assign(nb, 0);  // every live side differs: update fits them all
  h.update(sys, min_points, end_weight);
  return h;
}

template <int D>
void SubHorizon<D>::update(const System<D>& sys, int min_points, double end_weight) {
  const auto& f = sys.families;
  const BondIndex nb = f.n_bonds();
  const auto refit = bonds_to_refit(sys, diff, reverse, built_live, halo, built_halo);
  // Each side writes its own slots and their copies by point: no two sides share a slot.
#pragma omp parallel
  {
    std::vector<Point<D>> pts;
    std::vector<Vec<D>> fitted;
#pragma omp for schedule(static)
    for (Index i = 0; i < sys.particles.n_real; ++i)
      for (BondIndex b = f.begin(i); b < f.end(i); ++b)
        if (refit[b]) fill(*this, sys, diff, i, b, min_points, end_weight, pts, fitted);
  }
  built_halo = halo.flags;
  n_axial = 0;
  for (BondIndex b = 0; b < nb; ++b) {
    built_live[b] = sys.bonds.live(b);
    n_axial += axial[b];
  }
}

template <int D>
bool SubHorizon<D>::stale(const System<D>& sys) const {
  const BondIndex nb = sys.families.n_bonds();
  for (BondIndex b = 0; b < nb; ++b)
    if (built_live[b] != static_cast<std::uint8_t>(sys.bonds.live(b))) return true;
  return halo.flags != built_halo;
}

template <int D>
std::string sub_horizon_shortfall(const core::Stencil<D>& st, int min_points) {
  const auto diff = difference_table(st);
  const int n = st.size();
  std::vector<Point<D>> pts;
  std::vector<Vec<D>> coef;
  for (int s = 0; s < n; ++s) {
    pts = {{Vec<D>::Zero(), 1.0, 0}, {st.offset[s].template cast<double>(), 1.0, 0}};
    for (int q = 0; q < n; ++q)
      if (q != s && diff[static_cast<std::size_t>(s) * n + q] >= 0)
        pts.push_back({st.offset[q].template cast<double>(), 1.0, 0});
    if (!fit(pts, min_points, coef)) {
      std::ostringstream out;
      out << "the sub-horizon of the bond with offset (" << st.offset[s].transpose() << ") Δx holds " << pts.size()
          << " points" << (static_cast<int>(pts.size()) < min_points ? "" : ", all on one line or plane")
          << " (at least " << min_points << " spanning " << D << " dimensions needed)";
      return out.str();
    }
  }
  return {};
}

template struct SubHorizon<1>;
template struct SubHorizon<2>;
template struct SubHorizon<3>;
template std::string sub_horizon_shortfall<1>(const core::Stencil<1>&, int);
template std::string sub_horizon_shortfall<2>(const core::Stencil<2>&, int);
template std::string sub_horizon_shortfall<3>(const core::Stencil<3>&, int);

}  // namespace pdmpm::pd
