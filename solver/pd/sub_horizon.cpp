#include "solver/pd/sub_horizon.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <sstream>

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

// The live bond of particle j with stencil index r, or −1 (families are in stencil order).
template <int D>
BondIndex live_bond_at(const System<D>& sys, Index j, int r) {
  const auto& f = sys.families;
  const auto first = f.shape.begin() + f.begin(j), last = f.shape.begin() + f.end(j);
  const auto it = std::lower_bound(first, last, static_cast<std::uint16_t>(r));
  if (it == last || *it != r) return -1;
  const BondIndex b = it - f.shape.begin();
  return sys.bonds.live(b) ? b : -1;
}

// The sub-horizon of live bond b = i→j (stencil index s): i, j and every point live-bonded to both.
template <int D>
void gather_points(const System<D>& sys, const std::vector<int>& diff, Index i, BondIndex b, double end_weight,
                   std::vector<Point<D>>& pts) {
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
    if (c == b || r < 0 || !sys.bonds.live(c) || live_bond_at(sys, j, r) < 0) continue;
    pts.push_back({t.xi[q], vol[f.neighbor[c]], f.neighbor[c]});
  }
}

}  // namespace

template <int D>
SubHorizon<D> SubHorizon<D>::build(const System<D>& sys, int min_points, double end_weight) {
  if (sys.particles.n_ghost() > 0)
    throw std::invalid_argument("hpd does not support ghost particles (symmetry planes) yet");
  const auto& f = sys.families;
  const BondIndex nb = f.n_bonds();
  const Index n = sys.particles.n_real;
  const auto diff = difference_table(f.stencil);
  SubHorizon h;
  h.axial.assign(nb, 0);
  h.built_live.assign(nb, 0);
  std::vector<BondIndex> count(nb, 0);
  // Pass 1: how many entries each live bond side has (its own particle's loop: no races).
#pragma omp parallel
  {
    std::vector<Point<D>> pts;
    std::vector<Vec<D>> coef;
#pragma omp for schedule(static)
    for (Index i = 0; i < n; ++i)
      for (BondIndex b = f.begin(i); b < f.end(i); ++b) {
        h.built_live[b] = sys.bonds.live(b);
        if (!h.built_live[b]) continue;
        gather_points(sys, diff, i, b, end_weight, pts);
        const bool full = fit(pts, min_points, coef);
        h.axial[b] = !full;
        count[b] = full ? static_cast<BondIndex>(pts.size()) : 2;
      }
  }
  h.begin.assign(nb + 1, 0);
  for (BondIndex b = 0; b < nb; ++b) h.begin[b + 1] = h.begin[b] + count[b];
  h.point.resize(h.begin[nb]);
  h.coef.resize(h.begin[nb]);
  h.entry_bond.resize(h.begin[nb]);
  // Pass 2: the entries.
#pragma omp parallel
  {
    std::vector<Point<D>> pts;
    std::vector<Vec<D>> coef;
#pragma omp for schedule(static)
    for (Index i = 0; i < n; ++i)
      for (BondIndex b = f.begin(i); b < f.end(i); ++b) {
        if (!h.built_live[b]) continue;
        gather_points(sys, diff, i, b, end_weight, pts);
        if (h.axial[b]) {
          const Vec<D>& xi = sys.table.xi[f.shape[b]];
          pts.resize(2);
          coef = {-xi / xi.squaredNorm(), xi / xi.squaredNorm()};
        } else {
          fit(pts, min_points, coef);
        }
        for (std::size_t l = 0; l < pts.size(); ++l) {
          h.point[h.begin[b] + l] = pts[l].id;
          h.coef[h.begin[b] + l] = coef[l];
          h.entry_bond[h.begin[b] + l] = b;
        }
      }
  }
  for (BondIndex b = 0; b < nb; ++b) h.n_axial += h.built_live[b] && h.axial[b];
  // The entries by point: a counting sort in entry order (deterministic).
  h.at_begin.assign(static_cast<std::size_t>(n) + 1, 0);
  for (Index l : h.point) ++h.at_begin[l + 1];
  for (Index k = 0; k < n; ++k) h.at_begin[k + 1] += h.at_begin[k];
  h.at_point.resize(h.point.size());
  std::vector<BondIndex> next(h.at_begin.begin(), h.at_begin.end() - 1);
  for (BondIndex e = 0; e < static_cast<BondIndex>(h.point.size()); ++e) h.at_point[next[h.point[e]]++] = e;
  return h;
}

template <int D>
bool SubHorizon<D>::stale(const System<D>& sys) const {
  const BondIndex nb = sys.families.n_bonds();
  for (BondIndex b = 0; b < nb; ++b)
    if (built_live[b] != static_cast<std::uint8_t>(sys.bonds.live(b))) return true;
  return false;
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
