#include "solver/mpm/simulation.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <cstdint>
#include <limits>

#include "solver/core/error.hpp"
#include "solver/mpm/deformation_lanes.hpp"
#include "solver/mpm/deterministic_sum.hpp"
#include "solver/mpm/ductile_lanes.hpp"
#include "solver/mpm/g2p_rows.hpp"
#include "solver/mpm/gimp_lanes.hpp"
#include "solver/mpm/j2_plasticity.hpp"
#include "solver/mpm/kinematics.hpp"
#include "solver/mpm/lane_copy.hpp"
#include "solver/mpm/nonlocal.hpp"
#include "solver/mpm/parallel.hpp"
#include "solver/mpm/plane_stress_lanes.hpp"
#include "solver/mpm/polar_lanes.hpp"
#include "solver/mpm/scatter_rows.hpp"
#include "solver/mpm/stress_measures.hpp"

namespace pdmpm::mpm {

namespace {

bool is_mpm(core::ParticleKind k) { return k == core::ParticleKind::mpm || k == core::ParticleKind::transition; }

// A plastic flow lane l returned into particle p's history, element by element as the
// scalar law's matrix += adds it. The out-of-plane shears are left alone: the law adds +0
// there to entries that are +0 (every writer of a plane-stress history writes +0 there:
// the laws' zero-filled increments, the hybrid's fit from PD), which leaves them +0.
template <int D>
void add_plastic_increment(ParticleState<D>& state, Index p, const PlaneStressLanes& lanes, int l) {
  MatrixArrays<3, 3>& e = state.plastic_strain;
  e.entry(0, 0)[p] += lanes.d00[l], e.entry(1, 1)[p] += lanes.d11[l], e.entry(2, 2)[p] += lanes.d22[l];
  e.entry(0, 1)[p] += lanes.d01[l], e.entry(1, 0)[p] += lanes.d01[l];
  state.eq_plastic_strain[p] += lanes.d_alpha[l];
}

static_assert(kLawLanes == 8 && ScatterSchedule<2>::kLaneGroup == kLawLanes,
              "copy_run and prefetch_run handle groups of eight, the stress update's");

// The n ≤ 8 doubles of a run from one array to another (a lane buffer and a run of particles).
__attribute__((always_inline)) inline void copy_run(double* to, const double* from, Index n) {
  if (n == kLawLanes) return (void)std::memcpy(to, from, kLawLanes * sizeof(double));
  for (Index l = 0; l < n; ++l) to[l] = from[l];
}

// Lane l from array[group[l]] for the n particles of a group (a short group repeats its
// last particle); one copy if they are a run of consecutive particles.
__attribute__((always_inline)) inline void gather_lanes(double* lanes, const double* array, const Index* group, Index n,
                                                        bool run) {
  if (run)
    copy_run(lanes, array + group[0], n);
  else
    for (Index l = 0; l < n; ++l) lanes[l] = array[group[l]];
  for (Index l = n; l < kLawLanes; ++l) lanes[l] = lanes[n - 1];
}

// array[group[l]] = lane l for the n particles of a group.
__attribute__((always_inline)) inline void scatter_lanes(double* array, const double* lanes, const Index* group,
                                                         Index n, bool run) {
  if (run) return copy_run(array + group[0], lanes, n);
  for (Index l = 0; l < n; ++l) array[group[l]] = lanes[l];
}

// Particle p's τ of plane stress (τ₃₃ and the out-of-plane shears zero).
void store_plane_tau(MatrixArrays<3, 3>& tau, Index p, double k00, double k01, double k10, double k11) {
  tau.set(p, (Mat<3>() << k00, k01, 0.0, k10, k11, 0.0, 0.0, 0.0, 0.0).finished());
}

// Wall time between successive calls of lap().
class PhaseClock {
 public:
  double lap() {
    const double now = omp_get_wtime(), elapsed = now - last_;
    last_ = now;
    return elapsed;
  }

 private:
  double last_ = omp_get_wtime();
};

// Every cache line of a[p]: an entry of 72 or 80 bytes (τ, the plastic history) can
// span three lines, and its first and last byte name only two of them.
template <class T>
void prefetch(const std::vector<T>& a, Index p) {
  constexpr std::uintptr_t kLine = 64;
  const auto first = reinterpret_cast<std::uintptr_t>(a.data() + p) & ~(kLine - 1);
  const auto last = reinterpret_cast<std::uintptr_t>(a.data() + p) + sizeof(T) - 1;
  for (std::uintptr_t line = first; line <= last; line += kLine)
    __builtin_prefetch(reinterpret_cast<const void*>(line));
}

// Particles p … p + 7 of arrays of single values: the cache lines of a run of eight
// (two when the run straddles a line). The stress update's thirteen arrays need it: without
// it, the first load of each group's F was 17 % of its gather's time (perf, 200² plate).
inline void prefetch_run(Index p, std::initializer_list<const double*> arrays) {
  for (const double* a : arrays) {
    __builtin_prefetch(a + p);
    __builtin_prefetch(a + p + 7);
  }
}

// The arrays' entries of the particle kPrefetchAhead positions after position k of `order`.
template <class... Arrays>
void prefetch_ahead(const std::vector<Index>& order, Index k, const Arrays&... arrays) {
  if (k + kPrefetchAhead < static_cast<Index>(order.size())) (prefetch(arrays, order[k + kPrefetchAhead]), ...);
}

}  // namespace

template <int D>
Simulation<D>::Simulation(Settings<D> settings, core::Particles<D>& particles, const std::string& file,
                          const std::string& prefix, std::shared_ptr<OtherProcesses> others)
    : settings_(std::move(settings)),
      particles_(particles),
      constitutive_(settings_.material, settings_.setting),
      others_(std::move(others)) {
  const double dx = particles_.lattice.spacing;
  validate(settings_, dx, file, prefix);
  auto key = [&](const std::string& k) { return prefix.empty() ? k : prefix + "." + k; };
  // Whole-body answers of a distributed run: a maximum over the processes, exact in any order.
  auto largest = [&](double local) { return others_ ? others_->max(local) : local; };
  if (largest(static_cast<double>(particles_.n_real)) == 0.0)
    throw InputError(file, key("(particles)"), "the MPM body has no particles");
  if (others_) {
    // What reads beyond a point's own grid nodes: not distributed yet (docs/models/distributed.md).
    if (settings_.nonlocal.enabled)
      throw InputError(file, key("nonlocal"), "non-local hardening is not available in a distributed run yet");
    for (const GridBc<D>& bc : settings_.boundaries)
      if (bc.kind == BcKind::symmetry)
        throw InputError(file, "symmetry", "symmetry planes are not available in a distributed MPM run yet");
  }
  K_ = nodes_per_axis(settings_.shape);

  // Grid: node lines through settings.origin, cell h, covering the domain.
  const double h = settings_.cell_size > 0.0 ? settings_.cell_size : settings_.cell_factor * dx;
  Vec<D> lo, hi;
  if (settings_.domain_min) {
    lo = *settings_.domain_min;
    hi = *settings_.domain_max;
  } else {
    lo = Vec<D>::Constant(std::numeric_limits<double>::infinity());
    hi = -lo;
    for (Index p = 0; p < particles_.n_real; ++p) {
      lo = lo.cwiseMin(particles_.position(p));
      hi = hi.cwiseMax(particles_.position(p));
    }
    for (int a = 0; a < D; ++a) lo[a] = -largest(-lo[a]), hi[a] = largest(hi[a]);
    lo -= Vec<D>::Constant(0.5 * dx + settings_.padding_cells * h);
    hi += Vec<D>::Constant(0.5 * dx + settings_.padding_cells * h);
  }
  IVec<D> klo, n;
  for (int a = 0; a < D; ++a) {
    klo[a] = static_cast<std::int32_t>(std::floor((lo[a] - settings_.origin[a]) / h + 1e-9));
    const auto khi = static_cast<std::int32_t>(std::ceil((hi[a] - settings_.origin[a]) / h - 1e-9));
    n[a] = khi - klo[a] + 1;
    if (n[a] < 2) throw InputError(file, key("grid.max"), "the grid must span at least one cell on every axis");
  }
  grid_ = Grid<D>(settings_.origin + h * klo.template cast<double>(), h, n);
  for (std::size_t b = 0; b < settings_.boundaries.size(); ++b) {
    const GridBc<D>& bc = settings_.boundaries[b];
    if (bc.kind != BcKind::symmetry) continue;
    const double k0 = (bc.position - grid_.node0[bc.axis]) / h;
    if (k0 < 0.0 || k0 > n[bc.axis] - 1)
      throw InputError(file, key(fmt::format("boundary[{}].position", b)),
                       fmt::format("symmetry plane at {} lies outside the grid [{}, {}]", bc.position,
                                   grid_.node0[bc.axis], grid_.node0[bc.axis] + (n[bc.axis] - 1) * h));
  }
  boundary_ = GridBoundary<D>(settings_.boundaries, grid_);
  reactions_.assign(settings_.boundaries.size(), Vec<D>::Zero());

  state_.resize(particles_.size());
  for (Index p = 0; p < particles_.n_real; ++p) initialise_particle(p);

  // Tractions act on the particles whose reference position lies in the region.
  const double tol = 1e-9 * dx;
  for (std::size_t t = 0; t < settings_.tractions.size(); ++t) {
    const Traction<D>& tr = settings_.tractions[t];
    std::vector<Index> sel;
    for (Index p = 0; p < particles_.n_real; ++p) {
      bool in = true;
      for (int a = 0; a < D; ++a)
        in = in && particles_.x0[p][a] >= tr.min[a] - tol && particles_.x0[p][a] <= tr.max[a] + tol;
      if (in) sel.push_back(p);
    }
    if (largest(sel.empty() ? 0.0 : 1.0) == 0.0)
      throw InputError(file, key(fmt::format("traction[{}].min", t)), "the traction region contains no particle");
    traction_particles_.push_back(std::move(sel));
  }

  // Every real particle's stencil must fit in the grid now (whatever its kind).
  active_.clear();
  for (Index p = 0; p < particles_.n_real; ++p) active_.push_back(p);
  std::string uncovered;
  try {
    compute_stencils(active_, own_);
  } catch (const RunError& e) {
    uncovered = e.what();
  }
  if (largest(uncovered.empty() ? 0.0 : 1.0) > 0.0)
    throw InputError(file, key("grid.min"),
                     "the grid does not cover the body" + (uncovered.empty() ? std::string() : ": " + uncovered));
  refresh_active();
  if (settings_.dt > 0.0) {
    const double dts = stable_dt();
    if (settings_.dt > dts)
      throw InputError(file, key("dt"),
                       fmt::format("{} s exceeds the stable step h / max(c + |v|) = {} s", settings_.dt, dts));
  }
}

template <int D>
void Simulation<D>::initialise_particle(Index p) {
  const double dx = particles_.lattice.spacing;
  state_.mass[p] = settings_.material.elastic.rho * particles_.volume[p];
  state_.half_width[p] = Vec<D>::Constant(0.5 * dx);
  state_.F.set(p, Mat<D>::Identity());
  state_.kirchhoff.set(p, Mat<3>::Zero());
  state_.J[p] = 1.0;
  state_.out_of_plane_strain[p] = 0.0;
  state_.set_history(p, PointHistory{});
  state_.eq_plastic_hardening[p] = 0.0;
  state_.energy[p] = 0.0;
  state_.dissipation[p] = 0.0;
  state_.damage[p] = 0.0;
  state_.failed[p] = 0;
  state_.initialised[p] = 1;
}

template <int D>
void Simulation<D>::sync_particles() {
  const Index old = state_.size();
  state_.resize(particles_.size());
  for (Index p = old; p < particles_.n_real; ++p) initialise_particle(p);
}

template <int D>
void Simulation<D>::refresh_active() {
  active_.clear();
  for (Index p = 0; p < particles_.n_real; ++p)
    if (is_mpm(particles_.kind[p])) active_.push_back(p);
}

// Cells of the active particles → the scatter schedule → each particle's stencil,
// stored in schedule order.
template <int D>
void Simulation<D>::compute_stencils(const std::vector<Index>& points, ScatterSet& set, bool with_stencils) {
  const Index na = static_cast<Index>(points.size());
  std::vector<IVec<D>>& cell = set.cell;
  cell.resize(points.size());
  Index bad = std::numeric_limits<Index>::max();
  const IVec<D> cells = grid_.cells();
#pragma omp parallel for schedule(static) reduction(min : bad) if (na >= kParallelMin)
  for (Index k = 0; k < na; ++k) {
    const Index p = points[k];
    const Vec<D> xr = particles_.position(p) - grid_.node0;
    if (!xr.allFinite()) {
      bad = std::min(bad, p);
      cell[k].setZero();
      continue;
    }
    // ⌊x/h⌋ clamped to the grid's cells, clamped first: on [0, cells − 1] truncation is the
    // floor (one conversion where the baseline ISA's floor is a sequence of a dozen), and far-off
    // values stay in the integer's range.
    for (int a = 0; a < D; ++a)
      cell[k][a] = static_cast<std::int32_t>(std::clamp(xr[a] / grid_.h, 0.0, static_cast<double>(cells[a] - 1)));
  }
  if (bad == std::numeric_limits<Index>::max()) {
    set.schedule.build(grid_, points, cell);
    if (!with_stencils) return;
    set.stencil.resize(set.schedule.order().size());
    if (settings_.shape == ShapeFunction::gimp)
      compute_gimp_stencils(set, bad);
    else
      compute_other_stencils(set, bad);
  }
  if (bad != std::numeric_limits<Index>::max()) {
    std::string where;
    const Vec<D> x = particles_.position(bad);
    for (int a = 0; a < D; ++a) where += fmt::format("{}{}", a ? ", " : "", x[a]);
    const Index global = !others_ ? bad
        : bad < particles_.n_real ? others_->first_global() + bad
                                  : ghost_global_[bad - particles_.n_real];
    throw RunError(
        fmt::format("MPM step {}: particle {} at ({}) has left the grid (or its stencil has)", steps_, global, where));
  }
}

// GIMP stencils eight particles at a time (gimp_lanes.hpp); a last group of fewer
// repeats its last particle in the unused lanes. Each group's positions and half-widths
// are gathered a group ahead (for_each_group_gathered_ahead).
template <int D>
void Simulation<D>::compute_gimp_stencils(ScatterSet& set, Index& bad) {
  const std::vector<Index>& order = set.schedule.order();
  const Index na = static_cast<Index>(order.size());
  const Index groups = (na + kGimpLanes - 1) / kGimpLanes;
  struct Inputs {
    double x_rel[D][kGimpLanes], lp[D][kGimpLanes];  // [axis][lane]
  };
  auto gather = [&](Index gi, Inputs& in) {
    const Index k0 = gi * kGimpLanes;
    for (Index k = k0; k < std::min(k0 + kGimpLanes, na); ++k)  // the group after it
      prefetch_ahead(order, k, particles_.x0, particles_.u, state_.half_width);
    for (int l = 0; l < kGimpLanes; ++l) {
      const Index p = order[std::min(k0 + l, na - 1)];
      const Vec<D> x = particles_.position(p) - grid_.node0;
      for (int a = 0; a < D; ++a) in.x_rel[a][l] = x[a], in.lp[a][l] = state_.half_width[p][a];
    }
  };
  auto compute = [&](Index gi, const Inputs& in) {
    const Index k0 = gi * kGimpLanes;
    for (int a = 0; a < D; ++a) {
      GimpLanes lanes;
      gimp_lanes(in.x_rel[a], in.lp[a], grid_.h, lanes);
      for (int l = 0; l < kGimpLanes && k0 + l < na; ++l) {
        Stencil<D>& st = set.stencil[k0 + l];
        st.first[a] = lanes.first[l];
        for (int n = 0; n < 3; ++n) st.w[a][n] = lanes.w[n][l], st.dw[a][n] = lanes.dw[n][l];
      }
    }
    Index group_bad = kNoParticle;
    for (Index k = k0; k < std::min(k0 + kGimpLanes, na); ++k)
      if (!inside_grid(set.stencil[k])) group_bad = std::min(group_bad, order[k]);
    return group_bad;
  };
  bad = std::min(bad, for_each_group_gathered_ahead<Inputs>(groups, na >= kParallelMin, gather, compute));
}

template <int D>
void Simulation<D>::compute_other_stencils(ScatterSet& set, Index& bad) {
  const std::vector<Index>& order = set.schedule.order();
  const Index na = static_cast<Index>(order.size());
#pragma omp parallel for schedule(static) reduction(min : bad) if (na >= kParallelMin)
  for (Index k = 0; k < na; ++k) {
    const Index p = order[k];
    prefetch_ahead(order, k, particles_.x0, particles_.u, state_.half_width);
    const Stencil<D> st =
        make_stencil<D>(settings_.shape, particles_.position(p) - grid_.node0, grid_.h, state_.half_width[p]);
    if (!inside_grid(st)) bad = std::min(bad, p);
    set.stencil[k] = st;
  }
}

template <int D>
bool Simulation<D>::inside_grid(const Stencil<D>& st) const {
  for (int a = 0; a < D; ++a)
    if (st.first[a] < 0 || st.first[a] + K_ - 1 > grid_.n[a] - 1) return false;
  return true;
}

template <int D>
Vec<D> Simulation<D>::external_force(Index p, double t) const {
  const double m = state_.mass[p];
  Vec<D> f = m * settings_.gravity + particles_.volume[p] * particles_.b[p];
  if (settings_.body_acceleration) f += m * settings_.body_acceleration(particles_.x0[p], t);
  return f;
}

// P2G: whatever `what` asks of m_I, p_I and f_I, in one pass over the particles in the
// schedule's order (each node sums its particles in the same order on any thread count).
template <int D>
void Simulation<D>::clear_grid(Scatter what) {
  const Index N = grid_.size();
#pragma omp parallel for schedule(static) if (N >= kParallelMin)
  for (Index i = 0; i < N; ++i) {
    if (what.mass) grid_.mass[i] = 0.0;
    if (what.momentum) grid_.momentum[i].setZero();
    if (what.forces) {
      grid_.force_internal[i].setZero();
      grid_.force_external[i].setZero();
    }
  }
}

template <int D>
void Simulation<D>::fold_grid(Scatter what) {
  if (what.momentum) boundary_.fold(what.mass ? &grid_.mass : nullptr, &grid_.momentum);
  if (what.forces) boundary_.fold(nullptr, &grid_.force_internal, &grid_.force_external);
}

template <int D>
void Simulation<D>::scatter(Scatter what) {
  clear_grid(what);
  const IVec<D> stride = grid_.stride;
  const bool external = any_external_force_;
  const ScatterSet& set = scatter_set();
  const std::vector<Index>& order = set.schedule.order();
  if constexpr (D == 2) {
    if (rows()) {  // a stencil row per instruction (scatter_rows.hpp)
      const ScatterSource2 source{order.data(),        set.stencil.data(),     state_.mass.data(),
                                  particles_.v.data(), stress_volume().data(), in_plane(state_.kirchhoff),
                                  ext_force_.data()};
      const ScatterTarget2 target{grid_.mass.data(), grid_.momentum.data(), grid_.force_internal.data(),
                                  grid_.force_external.data(), stride[1]};
      const ScatterFields fields{what.mass, what.momentum, what.forces, external};
      set.schedule.for_each_block(
          [&](Index k_begin, Index k_end) { scatter_rows(source, target, fields, k_begin, k_end); });
      fold_grid(what);
      return;
    }
  }
  if constexpr (D == 3) {
    if (K_ == 3) {  // a stencil row per instruction (scatter_rows.hpp)
      const ScatterSource3 source{order.data(),           set.stencil.data(), state_.mass.data(), particles_.v.data(),
                                  stress_volume().data(), &state_.kirchhoff,  ext_force_.data()};
      const ScatterTarget3 target{grid_.mass.data(), grid_.momentum.data(), grid_.force_internal.data(),
                                  grid_.force_external.data(), stride};
      const ScatterFields fields{what.mass, what.momentum, what.forces, external};
      set.schedule.for_each_block(
          [&](Index k_begin, Index k_end) { scatter_rows3(source, target, fields, k_begin, k_end); });
      fold_grid(what);
      return;
    }
  }
  set.schedule.for_each([&](Index k, Index p) {
    prefetch_ahead(order, k, state_.mass, particles_.v);
    if (what.forces) prefetch_ahead(order, k, stress_volume(), ext_force_);
    const double m = state_.mass[p];
    const Vec<D> mv = m * particles_.v[p];
    const Mat<D> Vtau = stress_volume()[p] * state_.kirchhoff.get(p).template topLeftCorner<D, D>();
    const Vec<D> fe = ext_force_[p];
    // A zero external force adds only ±0 to sums that start at +0: exact to skip (scatter_rows.cpp).
    const bool adds_external = external && !fe.isZero(0.0);
    for_each_grid_node<D>(set.stencil[k], K_, stride, [&](Index node, double w, const Vec<D>& g) {
      if (what.mass) grid_.mass[node] += w * m;
      if (what.momentum) grid_.momentum[node] += w * mv;
      if (what.forces) {
        grid_.force_internal[node] -= Vtau * g;
        if (adds_external) grid_.force_external[node] += w * fe;  // else it stays zero
      }
    });
  });
  fold_grid(what);
}

template <int D>
void Simulation<D>::grid_velocity_from_momentum(std::vector<Vec<D>>& v) const {
  const Index N = grid_.size();
#pragma omp parallel for schedule(static) if (N >= kParallelMin)
  for (Index i = 0; i < N; ++i) v[i] = grid_.mass[i] > 0.0 ? Vec<D>(grid_.momentum[i] / grid_.mass[i]) : Vec<D>::Zero();
}

template <int D>
void Simulation<D>::update_nonlocal() {
  const Index n = particles_.size();
  if (!settings_.nonlocal.enabled) return;  // ε̂_p = ε̄_p (hardening_offset is zero)
  std::vector<Vec<D>> x(n, Vec<D>::Zero());
  std::vector<double> a(n, 0.0), avg;
  std::vector<std::uint8_t> use(n, 0);
  for (Index p : active_) {
    if (state_.failed[p]) continue;
    x[p] = particles_.position(p);
    a[p] = state_.eq_plastic_strain[p];
    use[p] = 1;
  }
  nonlocal_average<D>(x, particles_.volume, a, use, settings_.nonlocal.length, avg);
  const double m = settings_.nonlocal.m;
  for (Index p : active_) state_.eq_plastic_hardening[p] = (1.0 - m) * a[p] + m * avg[p];
}

// L = Σ v_I ⊗ ∇S_I of the particle at k in the schedule from the grid velocity vg.
// Summed in scalars, L(a, b) += v_a g_b node by node — the bits of L += v_I ∇S_Iᵀ, whose
// Eigen form stored ∇S in 8-byte pieces and read it back in 16-byte ones (a store-
// forwarding stall per node: in 3D a third of the step).
template <int D>
Mat<D> Simulation<D>::velocity_gradient(Index k, const std::vector<Vec<D>>& vg) const {
  if constexpr (D == 3)
    if (K_ == 3) return velocity_gradient_rows3(own_.stencil[k], vg.data(), grid_.stride);  // the same bits by rows
  double L[D][D] = {};
  for_each_grid_node<D>(own_.stencil[k], K_, grid_.stride, [&](Index node, double, const Vec<D>& g) {
    const Vec<D>& v = vg[node];
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) L[a][b] += v[a] * g[b];
  });
  Mat<D> out;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b) out(a, b) = L[a][b];
  return out;
}

// uGIMP half-widths of particle p that follow its stretch (gimp_domain = "stretch").
template <int D>
void Simulation<D>::stretch_domain(Index p) {
  if (settings_.shape != ShapeFunction::gimp || settings_.gimp_domain != GimpDomain::stretch) return;
  const double lp0 = 0.5 * particles_.lattice.spacing;
  for (int a = 0; a < D; ++a)
    state_.half_width[p][a] = std::min(0.5 * grid_.h, lp0 * std::abs(state_.F.entry(a, a)[p]));
}

// F of the particle at k in the schedule from the grid velocity vg (and its uGIMP
// half-widths if the domains stretch).
template <int D>
void Simulation<D>::advance_deformation(Index k, const std::vector<Vec<D>>& vg, double dt) {
  const Index p = own_.schedule.order()[k];
  state_.F.set(p, cayley_increment<D>(velocity_gradient(k, vg), dt) * state_.F.get(p));
  stretch_domain(p);
}

// F, the law and the ductile criterion of every active particle. The plane-stress
// laws go eight points at a time in one pass (update_stress_in_lanes); the others in
// three passes in the stencils' order: F, the polar decompositions of the log-strain
// laws, the law. The decomposition is a long chain of dependent operations (two
// square roots, two divisions, a series, a logarithm); in a pass of its own the
// processor overlaps the chains of successive particles, which one long loop body
// does not let it do.
template <int D>
void Simulation<D>::update_stress(const std::vector<Vec<D>>& vg, double dt) {
  Index bad = std::numeric_limits<Index>::max();
  auto throw_if_bad = [&] {
    if (bad != std::numeric_limits<Index>::max())
      throw RunError(
          fmt::format("MPM step {}: particle {} inverted (det F ≤ 0); the step {} s may be too large "
                      "(stable step estimate {} s)",
                      steps_, bad, dt, stable_dt()));
  };
  if constexpr (D == 2) {
    if (const std::optional<PlaneStressLaw> law = constitutive_.plane_stress_law()) {
      update_stress_in_lanes(vg, dt, *law, bad);
      throw_if_bad();
      return;
    }
  }
  const std::vector<Index>& order = own_.schedule.order();
  const Index na = static_cast<Index>(order.size());
#pragma omp parallel for schedule(static) if (na >= kParallelMin)
  for (Index k = 0; k < na; ++k) {
    advance_deformation(k, vg, dt);
  }
  const bool log_strain = constitutive_.log_strain();
  if (log_strain) {
    polar_.resize(order.size());
    polar_decompositions(bad);
    throw_if_bad();
  }
#pragma omp parallel for schedule(static) reduction(min : bad) if (na >= kParallelMin)
  for (Index k = 0; k < na; ++k) {
    const Index p = order[k];
    prefetch_ahead(order, k, state_.J, state_.out_of_plane_strain, state_.energy, state_.dissipation);
    if (!state_.failed[p] && !apply_law(p, log_strain ? &polar_[k] : nullptr)) bad = std::min(bad, p);
  }
  throw_if_bad();
}

// The plane-stress laws in one pass of groups of up to eight particles, the schedule's
// lane groups (ScatterSchedule::lane_groups: mostly runs of consecutive particles, whose
// entries of each state array are one copy): F, the polar decompositions (polar_lanes.hpp), the law's elastic path
// (plane_stress_lanes.hpp); the lanes those flag go through polar_log<2> and the
// law point by point. Nothing is stored between the stages. Each group's inputs (L, F,
// the plastic state) are gathered a group ahead (for_each_group_gathered_ahead) and
// each stage hands its lanes to the next as vectors (lane_copy.hpp).
template <int D>
void Simulation<D>::update_stress_in_lanes(const std::vector<Vec<D>>& vg, double dt, const PlaneStressLaw& law,
                                           Index& bad) {
  if constexpr (D == 2) {
    static_assert(kPolarLanes == kLawLanes && kDeformationLanes == kLawLanes && kCopyLanes == kLawLanes);
    const std::vector<Index>& order = own_.schedule.order();
    const Index na = static_cast<Index>(order.size());
    const bool elastic_only = settings_.material.model == MaterialModel::linear_elastic;
    const auto& lane_groups = own_.schedule.lane_groups();
    const Index groups = static_cast<Index>(lane_groups.size());
    struct Inputs {
      DeformationLanes def;  // L and F
      PlaneStressLanes law;  // the plastic state (the strain and rotation come from the decomposition)
    };
    auto gather = [&](Index gi, Inputs& in) {
      const auto [k0, n, run] = lane_groups[gi];
      const MatrixArrays<3, 3>& ep = state_.plastic_strain;
      {  // the group after it: its particles' state
        const Index p = order[std::min(k0 + n, na - 1)];
        const MatrixArrays<2, 2>& F = state_.F;
        prefetch_run(
            p,
            {F.entry(0, 0), F.entry(1, 0), F.entry(0, 1), F.entry(1, 1), ep.entry(0, 0), ep.entry(1, 1), ep.entry(0, 1),
             ep.entry(2, 2), state_.eq_plastic_strain.data(), state_.J.data(), state_.out_of_plane_strain.data(),
             state_.energy.data(), state_.dissipation.data(), state_.kirchhoff.entry(0, 0),
             state_.kirchhoff.entry(1, 0), state_.kirchhoff.entry(0, 1), state_.kirchhoff.entry(1, 1)});
        for (Index k = k0; k < k0 + n; ++k) prefetch_ahead(order, k, state_.failed);
      }
      DeformationLanes& def = in.def;
      if (rows())
        velocity_gradient_lanes(def, own_.stencil.data() + k0, static_cast<int>(n), vg.data(), grid_.stride[1]);
      for (int l = 0; l < kLawLanes && !rows(); ++l) {  // 2 × 2 stencils (linear)
        const Mat<2> L = velocity_gradient(k0 + std::min<Index>(l, n - 1), vg);
        def.l00[l] = L(0, 0), def.l01[l] = L(0, 1), def.l10[l] = L(1, 0), def.l11[l] = L(1, 1);
      }
      const Index* group = order.data() + k0;
      const MatrixArrays<2, 2>& F = state_.F;
      gather_lanes(def.f00, F.entry(0, 0), group, n, run), gather_lanes(def.f01, F.entry(0, 1), group, n, run);
      gather_lanes(def.f10, F.entry(1, 0), group, n, run), gather_lanes(def.f11, F.entry(1, 1), group, n, run);
      PlaneStressLanes& law_in = in.law;
      if (elastic_only) {  // no plastic strain, whatever a history holds (set_plastic_lane)
        for (int l = 0; l < kLawLanes; ++l) set_plastic_lane(law_in, l, Mat<3>::Zero().eval(), true);
      } else {
        gather_lanes(law_in.p00, ep.entry(0, 0), group, n, run),
            gather_lanes(law_in.p11, ep.entry(1, 1), group, n, run);
        gather_lanes(law_in.p01, ep.entry(0, 1), group, n, run),
            gather_lanes(law_in.p22, ep.entry(2, 2), group, n, run);
      }
      for (int l = 0; l < kLawLanes; ++l) {
        const Index p = group[std::min<Index>(l, n - 1)];
        const double eq = state_.eq_plastic_strain[p];
        law_in.alpha[l] = eq + hardening_offset(p, eq);
      }
    };
    const core::DuctileFailure& fail = settings_.failure;
    auto compute = [&](Index gi, Inputs& in) {
      const auto [k0, n, run] = lane_groups[gi];
      const Index* group = order.data() + k0;
      Index group_bad = kNoParticle;
      DeformationLanes& def = in.def;
      advance_deformation_lanes(def, dt);
      PolarLanes polar;
      const LaneCopy to_polar[] = {
          {polar.f00, def.f00}, {polar.f10, def.f10}, {polar.f01, def.f01}, {polar.f11, def.f11}};
      copy_lanes(to_polar, 4);
      MatrixArrays<2, 2>& F = state_.F;
      scatter_lanes(F.entry(0, 0), def.f00, group, n, run), scatter_lanes(F.entry(1, 0), def.f10, group, n, run);
      scatter_lanes(F.entry(0, 1), def.f01, group, n, run), scatter_lanes(F.entry(1, 1), def.f11, group, n, run);
      for (Index l = 0; l < n; ++l) stretch_domain(group[l]);
      const unsigned polar_by_point = polar_log_lanes(polar);
      PlaneStressLanes& lanes = in.law;
      const LaneCopy to_law[] = {{lanes.l00, polar.l00},
                                 {lanes.l01, polar.l01},
                                 {lanes.l11, polar.l11},
                                 {lanes.c, polar.c},
                                 {lanes.s, polar.s}};
      copy_lanes(to_law, 5);
      const unsigned law_by_point = plane_stress_lanes(law, lanes);
      double eps_f[kLawLanes];  // the ductile fracture strain of each lane
      if (fail.enabled)
        fracture_strain_lanes(fail.d0, fail.c, lanes, lanes_needing_fracture_strain(fail, lanes, n), eps_f);
      bool none_failed = run;
      for (Index l = 0; l < n && none_failed; ++l) none_failed = !state_.failed[group[l]];
      if (none_failed && polar_by_point == 0 && law_by_point == 0) {  // the lanes' results, a run at once
        store_lanes(group[0], n, lanes, eps_f);
        return group_bad;
      }
      for (int l = 0; l < n; ++l) {
        const Index p = group[l];
        if (state_.failed[p]) continue;  // a failed particle carries no stress (its τ is zero)
        if (polar_by_point >> l & 1u || law_by_point >> l & 1u) {
          PolarLog<2> pl;
          if (polar_by_point >> l & 1u) {
            try {
              pl = polar_log<2>(state_.F.get(p));
            } catch (const RunError&) {
              group_bad = std::min(group_bad, p);
              continue;
            }
          } else {
            pl.R << polar.c[l], -polar.s[l], polar.s[l], polar.c[l];
            pl.log_U << polar.l00[l], polar.l01[l], polar.l01[l], polar.l11[l];
          }
          if (!apply_law(p, &pl)) group_bad = std::min(group_bad, p);
          continue;
        }
        // store_law_result's stores, element by element from the lanes: a vector copy of
        // a result assembled from scalar stores would wait for them (store forwarding).
        const double alpha_before = state_.eq_plastic_strain[p];
        const bool yielded = lanes.yielded >> l & 1u;
        if (yielded) add_plastic_increment(state_, p, lanes, l);
        const double offset = hardening_offset(p, alpha_before);
        store_plane_tau(state_.kirchhoff, p, lanes.k00[l], lanes.k01[l], lanes.k10[l], lanes.k11[l]);
        state_.J[p] = lanes.J[l];
        state_.out_of_plane_strain[p] = lanes.out_of_plane[l];
        state_.energy[p] = lanes.energy[l];
        state_.dissipation[p] += yielded ? lanes.dissipation[l] : 0.0;
        if (fail.enabled) apply_ductile_criterion(p, alpha_before, offset, eps_f[l]);
      }
      return group_bad;
    };
    bad = std::min(bad, for_each_group_gathered_ahead<Inputs>(groups, na >= kParallelMin, gather, compute));
  } else {
    (void)vg, (void)dt, (void)law, (void)bad;
  }
}

// The results of a run of n ≤ 8 particles from p0 the lanes computed (none of them
// failed, none left to the scalar law) into their state, as the per-lane stores of
// update_stress_in_lanes make them, the arrays of single values a run at a time.
template <int D>
void Simulation<D>::store_lanes(Index p0, Index n, const PlaneStressLanes& lanes, const double* eps_f) {
  double alpha_before[kLawLanes];
  copy_run(alpha_before, state_.eq_plastic_strain.data() + p0, n);
  const unsigned y = lanes.yielded & ((1u << n) - 1u);  // the run's lanes (the others repeat its last)
  if (y != 0) {                                         // add_plastic_increment of the yielded lanes, entry by entry
    MatrixArrays<3, 3>& e = state_.plastic_strain;
    auto add = [&](double* to, const double* d) {
      for (Index l = 0; l < n; ++l) to[p0 + l] = y >> l & 1u ? to[p0 + l] + d[l] : to[p0 + l];
    };
    add(e.entry(0, 0), lanes.d00), add(e.entry(1, 1), lanes.d11), add(e.entry(2, 2), lanes.d22);
    add(e.entry(0, 1), lanes.d01), add(e.entry(1, 0), lanes.d01);
    add(state_.eq_plastic_strain.data(), lanes.d_alpha);
  }
  MatrixArrays<3, 3>& tau = state_.kirchhoff;
  copy_run(tau.entry(0, 0) + p0, lanes.k00, n), copy_run(tau.entry(1, 0) + p0, lanes.k10, n);
  copy_run(tau.entry(0, 1) + p0, lanes.k01, n), copy_run(tau.entry(1, 1) + p0, lanes.k11, n);
  copy_run(state_.J.data() + p0, lanes.J, n);
  copy_run(state_.out_of_plane_strain.data() + p0, lanes.out_of_plane, n);
  copy_run(state_.energy.data() + p0, lanes.energy, n);
  for (Index l = 0; l < n; ++l) state_.dissipation[p0 + l] += y >> l & 1u ? lanes.dissipation[l] : 0.0;
  const core::DuctileFailure& fail = settings_.failure;
  if (fail.enabled)
    for (Index l = 0; l < n; ++l)
      apply_ductile_criterion(p0 + l, alpha_before[l], hardening_offset(p0 + l, alpha_before[l]), eps_f[l]);
}

// The law of particle p (from polar, its polar decomposition, for the log-strain laws;
// else from F), stored with store_law_result; false if the return map failed.
template <int D>
bool Simulation<D>::apply_law(Index p, const PolarLog<D>* polar) {
  PointHistory hist = state_.history(p);
  const double alpha_before = hist.eq_plastic_strain;
  const double offset = hardening_offset(p, alpha_before);
  StressResult r;
  try {
    r = polar ? constitutive_.update(*polar, hist, offset) : constitutive_.update(state_.F.get(p), hist, offset);
  } catch (const RunError&) {
    return false;
  }
  state_.set_history(p, hist);
  store_law_result(p, r, alpha_before, offset);
  return true;
}

// The law's result r into particle p's state, then the ductile criterion (ε̄_p was
// alpha_before before the update; offset = ε̂_p − ε̄_p of the non-local hardening).
template <int D>
void Simulation<D>::store_law_result(Index p, const StressResult& r, double alpha_before, double offset) {
  state_.kirchhoff.set(p, r.kirchhoff);
  state_.J[p] = r.J;
  state_.out_of_plane_strain[p] = r.out_of_plane_strain;
  state_.energy[p] = r.energy;
  state_.dissipation[p] += r.dissipation;
  const core::DuctileFailure& fail = settings_.failure;
  if (fail.enabled)
    apply_ductile_criterion(p, alpha_before, offset,
                            fracture_strain(fail.d0, fail.c, mpm::triaxiality(state_.cauchy(p))));
}

// The ductile criterion of particle p, whose stress and ε̄_p the law just updated
// (ε̄_p was alpha_before; offset as for store_law_result): fails it when its plastic
// strain (rule "strain") or accumulated damage (rule "accumulated") reaches the
// fracture strain eps_f of its triaxiality.
template <int D>
void Simulation<D>::apply_ductile_criterion(Index p, double alpha_before, double offset, double eps_f) {
  const core::DuctileFailure& fail = settings_.failure;
  const double eps_p = state_.eq_plastic_strain[p];
  bool broke = false;
  if (fail.rule == core::FailureRule::strain) {
    broke = eps_p + offset >= eps_f;
  } else {
    state_.damage[p] += (eps_p - alpha_before) / eps_f;
    broke = state_.damage[p] >= 1.0;
  }
  if (broke) {
    state_.failed[p] = 1;
    failed_this_step_[p] = 1;
    state_.kirchhoff.set(p, Mat<3>::Zero());
    state_.energy[p] = 0.0;
  }
}

// polar_ of the active particles in schedule order; bad = the lowest inverted
// particle (unchanged if none). In 2D eight particles at a time (polar_lanes.hpp);
// the lanes it flags, and failed particles' F (which may be anything), go through
// polar_log<2> itself.
template <int D>
void Simulation<D>::polar_decompositions(Index& bad) {
  const std::vector<Index>& order = own_.schedule.order();
  const Index na = static_cast<Index>(order.size());
  // false if particle order[k] has inverted (bad is reduced in the loops, not here).
  auto decompose = [&](Index k) {
    const Index p = order[k];
    if (state_.failed[p]) return true;
    try {
      polar_[k] = polar_log<D>(state_.F.get(p));
    } catch (const RunError&) {
      return false;
    }
    return true;
  };
  if constexpr (D != 2) {
#pragma omp parallel for schedule(static) reduction(min : bad) if (na >= kParallelMin)
    for (Index k = 0; k < na; ++k) {
      prefetch_ahead(order, k, state_.failed);
      if (!decompose(k)) bad = std::min(bad, order[k]);
    }
  } else {
    const Index groups = (na + kPolarLanes - 1) / kPolarLanes;
    auto gather = [&](Index gi, PolarLanes& lanes) {  // a group ahead (for_each_group_gathered_ahead)
      const Index k0 = gi * kPolarLanes, n = std::min<Index>(kPolarLanes, na - k0);
      for (Index k = k0; k < k0 + n; ++k) prefetch_ahead(order, k, state_.failed);  // the group after it
      const MatrixArrays<D, D>& F = state_.F;
      for (int l = 0; l < kPolarLanes; ++l) {
        const Index p = order[k0 + std::min<Index>(l, n - 1)];
        lanes.f00[l] = F.entry(0, 0)[p], lanes.f10[l] = F.entry(1, 0)[p], lanes.f01[l] = F.entry(0, 1)[p],
        lanes.f11[l] = F.entry(1, 1)[p];
      }
    };
    auto compute = [&](Index gi, PolarLanes& lanes) {
      const Index k0 = gi * kPolarLanes, n = std::min<Index>(kPolarLanes, na - k0);
      Index group_bad = kNoParticle;
      const unsigned scalar = polar_log_lanes(lanes);
      for (int l = 0; l < n; ++l) {
        const Index k = k0 + l;
        if (scalar >> l & 1u) {
          if (!decompose(k)) group_bad = std::min(group_bad, order[k]);
        } else if (!state_.failed[order[k]]) {
          polar_[k].R << lanes.c[l], -lanes.s[l], lanes.s[l], lanes.c[l];
          polar_[k].log_U << lanes.l00[l], lanes.l01[l], lanes.l01[l], lanes.l11[l];
        }
      }
      return group_bad;
    };
    bad = std::min(bad, for_each_group_gathered_ahead<PolarLanes>(groups, na >= kParallelMin, gather, compute));
  }
}

template <int D>
double Simulation<D>::stable_dt() const {
  const core::Elastic& m = settings_.material.elastic;
  const double M = m.wave_modulus(settings_.setting);
  double vmax = 0.0;
  const Index na = static_cast<Index>(active_.size());
#pragma omp parallel for schedule(static) reduction(max : vmax) if (na >= kParallelMin)
  for (Index k = 0; k < na; ++k) {
    const Index p = active_[k];
    double modulus = M;
    if (settings_.material.model == MaterialModel::neo_hookean) {
      // The neo-Hookean tangent stiffens with stretch: λ + 2μ λ_max(B), λ_max ≤ ‖B‖_∞.
      const Mat<3> F3 = embed_deformation<D>(state_.F.get(p));
      const Mat<3> B = F3 * F3.transpose();
      modulus = m.lame() + 2.0 * m.shear() * std::max(1.0, B.cwiseAbs().rowwise().sum().maxCoeff());
    }
    const double c = std::sqrt(modulus / m.rho) + particles_.v[p].norm();
    vmax = std::max(vmax, c);
  }
  if (others_) vmax = others_->max(vmax);
  return vmax > 0.0 ? grid_.h / vmax : std::numeric_limits<double>::infinity();
}

template <int D>
double Simulation<D>::step() {
  refresh_active();
  const double dt = settings_.dt > 0.0 ? settings_.dt : settings_.cfl * stable_dt();
  step(dt);
  return dt;
}

template <int D>
void Simulation<D>::step(double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw RunError(fmt::format("MPM step {}: invalid time step {}", steps_, dt));
  refresh_active();
  newly_failed_.clear();
  if (active_.empty() && !others_) {  // (a distributed process without points still joins the others)
    boundary_.advance(time_, dt);
    time_ += dt;
    ++steps_;
    return;
  }
  const double t = time_;
  PhaseClock clock;
  prepare_step(t);
  phase_seconds_.prepare += clock.lap();

  // P2G and vⁿ. USL and MUSL scatter the forces of the stress the last step left in the
  // same pass; USF updates the stress from vⁿ first.
  const bool usf = settings_.scheme == UpdateScheme::usf;
  scatter({.mass = true, .momentum = true, .forces = !usf});
  grid_velocity_from_momentum(grid_.velocity);
  boundary_.constrain(grid_.velocity, t);
  boundary_.mirror(grid_.velocity);
  phase_seconds_.p2g += clock.lap();
  if (usf) {
    update_stress(grid_.velocity, dt);
    phase_seconds_.stress += clock.lap();
    if (others_) refresh_ghosts(GhostField::stress);
    scatter({.forces = true});
    phase_seconds_.p2g += clock.lap();
  }

  update_grid(t, dt);
  phase_seconds_.grid += clock.lap();
  // MUSL remaps: the new particle momenta back to the grid, the stress from that velocity.
  const bool musl = settings_.scheme == UpdateScheme::musl;
  grid_to_particles(t, dt, musl);
  phase_seconds_.g2p += clock.lap();

  if (musl) {
    grid_velocity_from_momentum(grid_.velocity_new);
    boundary_.constrain(grid_.velocity_new, t + dt);
    boundary_.mirror(grid_.velocity_new);
    phase_seconds_.p2g += clock.lap();
  }
  if (!usf) {
    update_stress(grid_.velocity_new, dt);
    phase_seconds_.stress += clock.lap();
  }
  remap_current_ = musl;

  for (Index p : active_)
    if (failed_this_step_[p]) newly_failed_.push_back(p);
  if (others_) drop_ghosts();
  boundary_.advance(t, dt);  // moving grips carry their node boxes to tⁿ⁺¹
  time_ += dt;
  ++steps_;
}

// The particles' per-step data: stencils and schedule, external forces at tⁿ, the
// nonlocal hardening variable.
template <int D>
void Simulation<D>::prepare_step(double t) {
  sync_particles();
  failed_this_step_.assign(particles_.size(), 0);
  compute_stencils(active_, own_, !others_);  // distributed: the own points' stencils come with the ghosts'
  // External forces (time tⁿ); only the active particles' entries are read.
  ext_force_.resize(particles_.size());
  const Index na = static_cast<Index>(active_.size());
  bool any = false;
  // (serial with a scene-expression body force: its evaluator is not known to be re-entrant)
  const bool parallel = na >= kParallelMin && !settings_.body_acceleration;
#pragma omp parallel for schedule(static) reduction(|| : any) if (parallel)
  for (Index k = 0; k < na; ++k) {
    const Vec<D> f = external_force(active_[k], t);
    ext_force_[active_[k]] = f;
    any = any || !f.isZero(0.0);
  }
  for (std::size_t i = 0; i < settings_.tractions.size(); ++i) {
    const Traction<D>& tr = settings_.tractions[i];
    const double r = ramp(t, tr.ramp_time);
    for (Index p : traction_particles_[i])
      if (is_mpm(particles_.kind[p])) {
        const Vec<D> value = tr.traction_field ? tr.traction_field(particles_.x0[p], t) : tr.traction;
        ext_force_[p] += r * value * particles_.volume[p] / particles_.lattice.spacing;
        any = any || !ext_force_[p].isZero(0.0);
      }
  }
  any_external_force_ = any;
  update_nonlocal();
  if (others_) {
    receive_ghosts();
    build_shared_scatter();
  }
}

template <int D>
void Simulation<D>::update_grid(double t, double dt) {
  // Grid momentum update with damping, then boundary conditions at tⁿ⁺¹.
  const Index N = grid_.size();
  damping_.resize(static_cast<std::size_t>(N));
  auto& damping = damping_;
  const double cv = settings_.damping_viscous, cl = settings_.damping_local;
#pragma omp parallel for schedule(static) if (N >= kParallelMin)
  for (Index i = 0; i < N; ++i) {
    const double m = grid_.mass[i];
    if (!(m > 0.0)) {
      grid_.velocity_new[i].setZero();
      damping[i].setZero();
      continue;
    }
    const Vec<D> v = grid_.velocity[i];
    const Vec<D> f = grid_.force_internal[i] + grid_.force_external[i];
    Vec<D> fd = -cv * m * v;
    if (cl > 0.0)
      for (int a = 0; a < D; ++a) fd[a] -= cl * std::abs(f[a]) * (v[a] > 0.0 ? 1.0 : v[a] < 0.0 ? -1.0 : 0.0);
    damping[i] = fd;
    grid_.velocity_new[i] = v + dt * (f + fd) / m;
  }
  velocity_free_ = grid_.velocity_new;
  const auto& v_free = velocity_free_;
  if (others_) {  // the reactions of the nodes this process books, summed with the others' in one process's order
    std::vector<typename GridBoundary<D>::NodeTerm> terms;
    boundary_.constrain(grid_.velocity_new, t + dt, &grid_.mass, dt, &reactions_, &terms);
    sum_node_terms(terms, &reactions_, nullptr);
  } else {
    boundary_.constrain(grid_.velocity_new, t + dt, &grid_.mass, dt, &reactions_);
  }
  boundary_.mirror(grid_.velocity_new);

  // Work of external and boundary forces over the step (midpoint velocity). The
  // damping force is a function of the velocity at the start of the step and its
  // power is f_d·vⁿ ≤ 0; the midpoint would include the step's own update, which
  // near equilibrium (|Δv| ≫ |v|, the velocity flipping sign every step) books
  // dissipation the damping never did (measured: the booked work kept growing at
  // rest: 8.7× the true half of the external work after 2e-4 s in the unit test's
  // plate; with vⁿ the balance closes to 1e-3 of the work).
  {
    const Vec<3> w = sum_over_nodes<3>([&](Index i) {
      const double share = boundary_.real_share(i);
      const Vec<D> vm = 0.5 * share * (grid_.velocity[i] + grid_.velocity_new[i]);
      Vec<3> r;
      r[0] = grid_.force_external[i].dot(vm);
      r[1] = grid_.mass[i] > 0.0 ? (grid_.mass[i] / dt) * (grid_.velocity_new[i] - v_free[i]).dot(vm) : 0.0;
      r[2] = share * damping[i].dot(grid_.velocity[i]);
      return r;
    });
    external_work_ += dt * w[0];
    boundary_work_ += dt * w[1];
    damping_work_ += dt * w[2];
  }
}

// G2P: particle velocity (FLIP/PIC blend) and position, in the stencils' order. With
// `remap` (MUSL) each particle's new momentum goes back to the grid in the same pass,
// run by the scatter schedule: the remap writes only p_I, which G2P does not read, and
// each node still sums its particles in the schedule's order.
template <int D>
void Simulation<D>::grid_to_particles(double t, double dt, bool remap) {
  const std::vector<Index>& order = own_.schedule.order();
  const Index na = static_cast<Index>(order.size());
  const IVec<D> stride = grid_.stride;
  const double flip = settings_.flip;
  std::atomic<bool> finite{true};
  // One process scatters the remap in the G2P pass; a distributed one needs the ghosts'
  // new velocities first, so its remap is a scatter of its own after them.
  const bool fused_remap = remap && !others_;
  auto move_particle = [&](Index k, Index p) {
    prefetch_ahead(order, k, particles_.v, particles_.u);
    if (fused_remap) prefetch_ahead(order, k, state_.mass);
    Vec<D> v_pic = Vec<D>::Zero(), dv = Vec<D>::Zero();
    for_each_grid_node<D>(own_.stencil[k], K_, stride, [&](Index node, double w, const Vec<D>&) {
      v_pic += w * grid_.velocity_new[node];
      dv += w * (grid_.velocity_new[node] - grid_.velocity[node]);
    });
    particles_.v[p] = flip * (particles_.v[p] + dv) + (1.0 - flip) * v_pic;
    particles_.u[p] += dt * v_pic;
    if (!particles_.v[p].allFinite() || !particles_.u[p].allFinite()) finite.store(false, std::memory_order_relaxed);
    if (fused_remap) {
      const Vec<D> mv = state_.mass[p] * particles_.v[p];
      for_each_grid_node<D>(own_.stencil[k], K_, stride,
                            [&](Index node, double w, const Vec<D>&) { grid_.momentum[node] += w * mv; });
    }
  };
  // The particles at schedule positions [k_begin, k_end); with 3 × 3 (× 3) stencils a
  // stencil row per instruction (g2p_rows.hpp).
  auto move_run = [&](Index k_begin, Index k_end) {
    if constexpr (D == 2) {
      if (rows()) {
        const G2PArrays2 arrays{order.data(),          own_.stencil.data(),       state_.mass.data(),
                                grid_.velocity.data(), grid_.velocity_new.data(), particles_.v.data(),
                                particles_.u.data(),   grid_.momentum.data(),     stride[1]};
        if (!g2p_rows(arrays, {flip, dt, fused_remap}, k_begin, k_end)) finite.store(false, std::memory_order_relaxed);
        return;
      }
    }
    if constexpr (D == 3) {
      if (K_ == 3) {
        const G2PArrays3 arrays{order.data(),          own_.stencil.data(),       state_.mass.data(),
                                grid_.velocity.data(), grid_.velocity_new.data(), particles_.v.data(),
                                particles_.u.data(),   grid_.momentum.data(),     stride};
        if (!g2p_rows3(arrays, {flip, dt, fused_remap}, k_begin, k_end)) finite.store(false, std::memory_order_relaxed);
        return;
      }
    }
    for (Index k = k_begin; k < k_end; ++k) move_particle(k, order[k]);
  };
  if (fused_remap) {
    clear_grid({.momentum = true});
    own_.schedule.for_each_block(move_run);
    fold_grid({.momentum = true});
  } else {
    constexpr Index kChunk = 256;
#pragma omp parallel for schedule(static) if (na >= kParallelMin)
    for (Index k0 = 0; k0 < na; k0 += kChunk) move_run(k0, std::min(na, k0 + kChunk));
  }
  if (!finite.load() && others_)  // the energies would wait for the other processes
    throw RunError(fmt::format("MPM step {} (t = {} s): non-finite particle velocity", steps_, t));
  if (!finite.load()) {
    const Energies e = energies();
    throw RunError(
        fmt::format("MPM step {} (t = {} s): non-finite particle velocity; kinetic energy {} J, strain "
                    "energy {} J; step {} s vs stable estimate {} s",
                    steps_, t, e.kinetic, e.strain, dt, stable_dt()));
  }
  if (remap && others_) {
    refresh_ghosts(GhostField::velocity);
    scatter({.momentum = true});
  }
}

template <int D>
void Simulation<D>::set_deformation_gradient(Index p, const Mat<D>& F) {
  state_.F.set(p, F);
  PointHistory h = state_.history(p);
  const StressResult r = constitutive_.update(F, h, hardening_offset(p, h.eq_plastic_strain));
  state_.set_history(p, h);
  state_.kirchhoff.set(p, r.kirchhoff);
  state_.J[p] = r.J;
  state_.energy[p] = r.energy;
  state_.out_of_plane_strain[p] = r.out_of_plane_strain;
}

template <int D>
void Simulation<D>::set_state(Index p, const Mat<D>& F, const PointHistory& history) {
  state_.set_history(p, history);
  state_.eq_plastic_hardening[p] = history.eq_plastic_strain;
  set_deformation_gradient(p, F);
}

template <int D>
void Simulation<D>::set_stress_weight(const std::vector<double>& weight) {
  if (weight.empty()) {
    stress_volume_.clear();
    return;
  }
  if (weight.size() < particles_.volume.size()) throw RunError("MPM: one stress weight per particle expected");
  if (others_) throw RunError("MPM: stress weights (the hybrid's blend) are not distributed yet");
  stress_volume_.resize(particles_.volume.size());
  for (std::size_t p = 0; p < stress_volume_.size(); ++p) stress_volume_[p] = weight[p] * particles_.volume[p];
}

template <int D>
Energies Simulation<D>::energies() const {
  const Vec<3> s = sum_over_points<3>([&](Index k) {
    const Index p = active_[k];
    const double V = stress_volume()[p];
    return Vec<3>(0.5 * state_.mass[p] * particles_.v[p].squaredNorm(), V * state_.energy[p],
                  V * state_.dissipation[p]);
  });
  Energies e;
  e.kinetic = s[0];
  e.strain = s[1];
  e.dissipated = s[2];
  e.external_work = external_work_;
  e.boundary_work = boundary_work_;
  e.damping_work = damping_work_;
  return e;
}

template <int D>
double Simulation<D>::pending_boundary_work(double dt) {
  std::vector<Vec<D>> f(static_cast<std::size_t>(grid_.size()), Vec<D>::Zero());
  const IVec<D> stride = grid_.stride;
  if (others_) receive_ghosts();  // the others' points as they are now
  // Distributed, every node sums its points in the global order, as one process does.
  const std::vector<Index> points = others_ ? own_and_ghosts() : active_;
  for (Index p : points) {
    const Stencil<D> st =
        make_stencil<D>(settings_.shape, particles_.position(p) - grid_.node0, grid_.h, state_.half_width[p]);
    if (!inside_grid(st)) continue;  // the next step reports it
    if (state_.failed[p]) continue;
    const Mat<D> Vtau = stress_volume()[p] * state_.kirchhoff.get(p).template topLeftCorner<D, D>();
    for_each_grid_node<D>(st, K_, stride, [&](Index node, double, const Vec<D>& g) { f[node] -= Vtau * g; });
  }
  boundary_.fold(nullptr, &f);
  if (!others_) return 0.5 * dt * boundary_.constraint_power(f, time_);
  std::vector<typename GridBoundary<D>::NodeTerm> terms;
  boundary_.constraint_power(f, time_, &terms);
  double power = 0.0;
  sum_node_terms(terms, nullptr, &power);
  drop_ghosts();
  return 0.5 * dt * power;
}

template <int D>
template <int N, class Fn>
Eigen::Matrix<double, N, 1> Simulation<D>::sum_over_points(Fn&& term) const {
  using V = Eigen::Matrix<double, N, 1>;
  const Index na = static_cast<Index>(active_.size());
  if (!others_) return deterministic_sum<V>(na, V::Zero(), term);
  // deterministic_sum continued from process to process: the closed chunks' total, the
  // open chunk's partial sum and the count of terms so far travel along the chain.
  std::array<double, 2 * N + 1> chain{};
  others_->ordered_sum(chain.data(), 2 * N + 1, [&](double* c) {
    Eigen::Map<V> total(c), partial(c + N);
    auto count = static_cast<std::int64_t>(c[2 * N]);
    for (Index k = 0; k < na; ++k, ++count) {
      if (count > 0 && count % kSumChunk == 0) {
        total += partial;
        partial.setZero();
      }
      partial += term(k);
    }
    c[2 * N] = static_cast<double>(count);
  });
  const Eigen::Map<const V> total(chain.data()), partial(chain.data() + N);
  return chain[2 * N] > 0.0 ? V(total + partial) : V(total);
}

template <int D>
template <int N, class Fn>
Eigen::Matrix<double, N, 1> Simulation<D>::sum_over_nodes(Fn&& term) const {
  using V = Eigen::Matrix<double, N, 1>;
  const Index nodes = grid_.size();
  if (!others_) return deterministic_sum<V>(nodes, V::Zero(), term);
  // The terms of the nodes this process books, gathered with the others', summed as one
  // process sums them. A zero term is not sent (the node's term stays +0): the sums start at
  // +0 and round to nearest, so they never hold −0, and adding ±0 leaves them as they are.
  std::vector<double> mine;
  for (Index i = 0; i < nodes; ++i) {
    if (!owned_node_[i]) continue;
    const V t = term(i);
    if ((t.array() == 0.0).all()) continue;
    mine.push_back(static_cast<double>(i));
    mine.insert(mine.end(), t.data(), t.data() + N);
  }
  const std::vector<double> all = others_->all_gather(mine);
  std::vector<V> terms(static_cast<std::size_t>(nodes), V::Zero());
  for (std::size_t r = 0; r < all.size(); r += N + 1)
    terms[static_cast<std::size_t>(all[r])] = Eigen::Map<const V>(&all[r + 1]);
  return deterministic_sum<V>(nodes, V::Zero(), [&](Index i) { return terms[i]; });
}

template <int D>
Vec<D> Simulation<D>::momentum() const {
  return sum_over_points<D>([&](Index k) {
    const Index p = active_[k];
    return Vec<D>(state_.mass[p] * particles_.v[p]);
  });
}

template <int D>
std::optional<double> Simulation<D>::grid_kinetic_energy() const {
  if (!remap_current_) return std::nullopt;
  return sum_over_nodes<1>([&](Index i) {
    const double m = grid_.mass[i];
    return Eigen::Matrix<double, 1, 1>(m > 0.0 ? boundary_.real_share(i) * 0.5 * grid_.momentum[i].squaredNorm() / m
                                               : 0.0);
  })[0];
}

template <int D>
double Simulation<D>::total_mass() const {
  return sum_over_points<1>([&](Index k) { return Eigen::Matrix<double, 1, 1>(state_.mass[active_[k]]); })[0];
}

template <int D>
double Simulation<D>::von_mises(Index p) const {
  return mpm::von_mises(state_.cauchy(p));
}

template <int D>
double Simulation<D>::triaxiality(Index p) const {
  return mpm::triaxiality(state_.cauchy(p));
}

template <int D>
void Simulation<D>::checkpoint(core::StateArchive& a) {
  a.expect("mpm/grid_nodes", grid_.size());
  auto& st = state_;
  a.sync("mpm/mass", st.mass);
  a.sync("mpm/half_width", st.half_width);
  std::vector<Mat<D>> F = st.F.packed();  // the checkpoint keeps whole matrices
  a.sync("mpm/F", F);
  st.F.unpack(F);
  std::vector<Mat<3>> tau = st.kirchhoff.packed();
  a.sync("mpm/kirchhoff", tau);
  st.kirchhoff.unpack(tau);
  a.sync("mpm/J", st.J);
  a.sync("mpm/out_of_plane_strain", st.out_of_plane_strain);
  std::vector<PointHistory> history(static_cast<std::size_t>(st.size()));
  for (Index p = 0; p < st.size(); ++p) history[p] = st.history(p);
  a.sync("mpm/history", history);
  st.plastic_strain.resize(static_cast<Index>(history.size()), Mat<3>::Zero());
  st.eq_plastic_strain.resize(history.size());
  for (Index p = 0; p < st.size(); ++p) st.set_history(p, history[p]);
  a.sync("mpm/eq_plastic_hardening", st.eq_plastic_hardening);
  a.sync("mpm/energy", st.energy);
  a.sync("mpm/dissipation", st.dissipation);
  a.sync("mpm/damage", st.damage);
  a.sync("mpm/failed", st.failed);
  a.sync("mpm/initialised", st.initialised);
  a.sync("mpm/active", active_);
  a.sync("mpm/reactions", reactions_);
  a.sync("mpm/newly_failed", newly_failed_);
  a.sync("mpm/failed_this_step", failed_this_step_);
  a.sync("mpm/phase_seconds", phase_seconds_);
  a.sync("mpm/time", time_);
  a.sync("mpm/steps", steps_);
  a.sync("mpm/external_work", external_work_);
  a.sync("mpm/boundary_work", boundary_work_);
  a.sync("mpm/damping_work", damping_work_);
  a.sync("mpm/grip_box_offsets", boundary_.box_offsets());
  boundary_.refresh();
}

template class Simulation<1>;
template class Simulation<2>;
template class Simulation<3>;

}  // namespace pdmpm::mpm
