// The bond loops, compiled once per instruction set: included by
// bond_kernels_{sse2,avx2,avx512}.cpp with PDMPM_SIMD_NS and PDMPM_SIMD_SET set.
// See bond_kernels.hpp for the canonical lane order that makes every build
// give the same bits.
//
// Each block of eight bonds is done in two phases: a gather of the neighbours'
// data into lanes (lane_gather.hpp: whole-row loads and a transpose with
// AVX-512, scalar loads otherwise), then arithmetic on whole lane vectors
// (lane_vector.hpp), with selects instead of branches.
#include <algorithm>
#include <cmath>
#include <vector>

#include "solver/pd/kernels/kernel_set.hpp"
#include "solver/pd/kernels/lane_gather.hpp"
#include "solver/pd/kernels/lane_vector.hpp"

namespace pdmpm::pd::kernels::PDMPM_SIMD_NS {
namespace {

inline double lane_sum(d8 v) { return ((v[0] + v[1]) + (v[2] + v[3])) + ((v[4] + v[5]) + (v[6] + v[7])); }

inline d8 load8(const double* p) {
  d8 v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}

// How a block is gathered, fixed per family so the bond loop has no branch on it:
// `wide` when no neighbour's u_j is the last row of u (a wide gather reads four
// doubles per row, see lane_gather.hpp), `uniform_volume` when V_j is one number.
template <bool Wide, bool UniformVolume>
struct GatherMode {
  static constexpr bool wide = Wide, uniform_volume = UniformVolume;
};

// Lanes of a block whose bond is intact and active (padding lanes excluded).
inline m8 live_lanes(const FamilyView& fam, BondIndex b0, int count) {
  return lanes_zero(fam.broken + b0) & first_lanes(count);
}

// Lanes of a block whose bond counts in its owner's state: live, or intact and kept
// for the state only (kStateOnlyFlag: a full-state transition particle's bonds to
// grid particles). Without such bonds in the body, the live lanes.
inline m8 state_lanes(const FamilyView& fam, BondIndex b0, int count) {
  if (!fam.state_only_bonds) return live_lanes(fam, b0, count);
  return lanes_zero_ignoring(fam.broken + b0, kStateOnlyFlag) & first_lanes(count);
}

// The live lanes among a state pass's visited ones: only they may break (a state-only
// bond belongs to the grid).
inline m8 breakable_lanes(const FamilyView& fam, m8 visited, BondIndex b0, int count) {
  return fam.state_only_bonds ? live_lanes(fam, b0, count) : visited;
}

// Which lanes a bond loop visits: the live ones (forces) or those of the state.
enum class Lanes { live, state };
template <Lanes Set>
inline m8 visited_lanes(const FamilyView& fam, BondIndex b0, int count) {
  return Set == Lanes::live ? live_lanes(fam, b0, count) : state_lanes(fam, b0, count);
}

// Whether a block has a lane of the set, from the flag bytes alone (no lane masks built).
template <Lanes Set>
inline bool any_visited(const FamilyView& fam, BondIndex b0, int count) {
  if (Set == Lanes::live || !fam.state_only_bonds) return any_zero_byte(fam.broken + b0, count);
  return any_zero_byte(fam.broken + b0, count, kStateOnlyFlag);
}

// Whether a block has a live bond. A block without one adds nothing to any sum (every
// kernel masks its lanes with `live`) and is skipped before its gather: in a hybrid a
// transition particle's family is mostly bonds to other transition particles, which
// belong to the grid (pd::bond_active), and a crack face's blocks are mostly broken.
inline bool any_live(const FamilyView& fam, BondIndex b0, int count) {
  return any_visited<Lanes::live>(fam, b0, count);
}

// One block of up to eight bonds of particle i, gathered into lanes.
template <int D>
struct Block {
  d8 eta[D];  // η = u_j − u_i
  d8 xi[D];   // ξ
  d8 L;       // |ξ|
  d8 wv;      // ω β V_j
  m8 live;    // all ones for a visited bond (live, or in the state), 0 for a broken bond or a padding lane
  alignas(32) Index j[lanes];

  // Families are subsequences of the stencil, in stencil order. Where a block's
  // offsets are consecutive (always in a whole-stencil family, mostly elsewhere)
  // ξ, |ξ| and ω β are contiguous rows of the table, loaded whole (the table is
  // padded to a multiple of 8 lanes); otherwise they are gathered by offset.
  // Lanes past the family's end read the padded tail of the bond arrays and are
  // masked out by `live`.
  // (Forced inline: as a call, the gathered lanes go through memory, ~1.5× slower.)
  template <Lanes Set, class Mode>
  __attribute__((always_inline)) void gather(Mode, const FamilyView& fam, const BondShapeTable& T, const double* u,
                                             const double* ui, const double* volume, BondIndex b0, int count) {
    __builtin_memcpy(j, fam.neighbor + b0, sizeof j);
    const std::uint16_t* k = fam.shape + b0;
    if (k[count - 1] - k[0] == count - 1) {
      for (int d = 0; d < D; ++d) xi[d] = load8(T.xi[d] + k[0]);
      L = load8(T.length + k[0]);
      wv = load8(T.weight + k[0]);
    } else {
      d8 r[D + 1];
      gather_rows_wide<D + 1, 4>(T.rows, k, r);
      for (int d = 0; d < D; ++d) xi[d] = r[d];
      L = r[D];
      wv = d8{T.weight[k[0]], T.weight[k[1]], T.weight[k[2]], T.weight[k[3]],
              T.weight[k[4]], T.weight[k[5]], T.weight[k[6]], T.weight[k[7]]};
    }
    if constexpr (Mode::wide)
      gather_rows_wide<D, D>(u, j, eta);
    else
      gather_rows_narrow<D, D>(u, j, eta);
    for (int d = 0; d < D; ++d) eta[d] -= ui[d];
    if constexpr (Mode::uniform_volume)
      wv *= volume[0];
    else
      wv *= d8{volume[j[0]], volume[j[1]], volume[j[2]], volume[j[3]],
               volume[j[4]], volume[j[5]], volume[j[6]], volume[j[7]]};
    live = visited_lanes<Set>(fam, b0, count);
  }
};

// The bond loop of particle i: gathers each block of its family into B and
// calls block(mode, b0, count), with the gather mode chosen once per family.
template <int D, Lanes Set = Lanes::live, class Args, class Fn>
__attribute__((always_inline)) inline void for_each_block(const Args& a, Index i, Block<D>& B, Fn&& block) {
  const FamilyView& fam = a.fam;
  const BondIndex begin = fam.offsets[i], end = fam.offsets[i + 1];
  // D j + 4 ≤ D n_sites: j < n_sites − 1 in 2D/3D, j < n_sites − 3 in 1D.
  const Index limit = fam.n_sites - (4 - 1) / D;
  Index j_max = 0;
  for (BondIndex b = begin; b < end; ++b) j_max = std::max(j_max, fam.neighbor[b]);
  auto loop = [&](auto mode) {
    const double* ui = a.u + D * i;
    for (BondIndex b0 = begin; b0 < end; b0 += lanes) {
      const int count = static_cast<int>(std::min<BondIndex>(lanes, end - b0));
      if (!any_visited<Set>(fam, b0, count)) continue;
      B.template gather<Set>(mode, fam, a.table, a.u, ui, a.volume, b0, count);
      block(mode, b0, count);
    }
  };
  const bool wide = j_max < limit;
  if (wide && a.uniform_volume)
    loop(GatherMode<true, true>{});
  else if (wide)
    loop(GatherMode<true, false>{});
  else if (a.uniform_volume)
    loop(GatherMode<false, true>{});
  else
    loop(GatherMode<false, false>{});
}

// Deformed bonds of a block: y = ξ + η, |y|, and num = 2 ξ·η + η·η = (|y| + |ξ|) e,
// the extension numerator without cancellation.
template <int D>
struct Deformed {
  d8 y[D];
  d8 len, num;
};

template <int D>
inline Deformed<D> deform(const Block<D>& B) {
  Deformed<D> g;
  d8 xe = splat(0.0), ee = splat(0.0), l2 = splat(0.0);
  for (int d = 0; d < D; ++d) {
    g.y[d] = B.xi[d] + B.eta[d];
    xe += B.xi[d] * B.eta[d];
    ee += B.eta[d] * B.eta[d];
    l2 += g.y[d] * g.y[d];
  }
  g.len = sqrt8(l2);
  g.num = 2.0 * xe + ee;
  return g;
}

// Lanes where s = num / ((|y| + L) L) reaches s₀ (compared without the division):
// s ≥ s₀, or s > s₀ for the break-after-force rule.
inline m8 reaches_critical_stretch(const d8& num, const d8& len, const d8& L, double s0, bool strict) {
  const d8 limit = s0 * L * (len + L);
  return strict ? greater(num, limit) : greater_equal(num, limit);
}

// Bonds of this block that just broke are marked; returns how many.
inline std::int64_t mark_broken(const FamilyView& fam, BondIndex b0, int count, m8 breaks) {
  if (!any(breaks)) return 0;
  std::int64_t n = 0;
  for (int l = 0; l < count; ++l)
    if (breaks[l]) {
      fam.broken[b0 + l] = 1;
      ++n;
    }
  return n;
}

template <int D, bool Energy>
std::int64_t pmb(const PmbArgs& a) {
  const FamilyView& fam = a.fam;
  const m8 breaking = a.breaking ? m8{} - 1 : m8{};
  const double s0 = a.s0, c = a.c;
  std::int64_t newly = 0;
#pragma omp parallel for schedule(static) reduction(+ : newly)
  for (Index k = 0; k < fam.n_owners; ++k) {
    const Index i = fam.particle(k);
    d8 acc[D], w = splat(0.0);
    for (auto& x : acc) x = splat(0.0);
    Block<D> B;
    for_each_block<D>(a, i, B, [&](auto, BondIndex b0, int count) {
      const Deformed<D> g = deform<D>(B);
      const m8 breaks = breaking & B.live & reaches_critical_stretch(g.num, g.len, B.L, s0, a.after_force);
      const m8 acts = a.after_force ? B.live : B.live & ~breaks;
      const d8 cw = c * B.wv;
      const d8 coef = cw * g.num / ((g.len + B.L) * g.len * B.L);  // c ω β V s / |y|
      for (int d = 0; d < D; ++d) add_to(acc[d], keep(acts, coef * g.y[d]));
      if constexpr (Energy) {
        const d8 s = g.num / ((g.len + B.L) * B.L);
        add_to(w, keep(acts, 0.25 * cw * s * s * B.L));  // ½ Σ_j ½ c ω β s² |ξ| V_j
      }
      newly += mark_broken(fam, b0, count, breaks);
    });
    for (int d = 0; d < D; ++d) a.f[D * i + d] = lane_sum(acc[d]);
    if constexpr (Energy) a.energy[i] = lane_sum(w);
  }
  return newly;
}

template <int D>
std::int64_t lps_dilatation(const LpsArgs& a) {
  const FamilyView& fam = a.fam;
  const m8 breaking = a.breaking && !a.after_force ? m8{} - 1 : m8{};
  const double s0 = a.s0;
  std::int64_t newly = 0;
#pragma omp parallel for schedule(static) reduction(+ : newly)
  for (Index k = 0; k < fam.n_owners; ++k) {
    const Index i = fam.particle(k);
    d8 acc = splat(0.0);
    Block<D> B;
    for_each_block<D, Lanes::state>(a, i, B, [&](auto, BondIndex b0, int count) {
      const Deformed<D> g = deform<D>(B);
      const m8 breaks =
          breaking & breakable_lanes(fam, B.live, b0, count) & reaches_critical_stretch(g.num, g.len, B.L, s0, false);
      const m8 acts = B.live & ~breaks;
      add_to(acc, keep(acts, B.wv * B.L * g.num / (g.len + B.L)));  // ω β |ξ| e V_j
      newly += mark_broken(fam, b0, count, breaks);
    });
    a.theta[i] = a.m[i] > 0.0 ? a.d * lane_sum(acc) / a.m[i] : 0.0;
  }
  return newly;
}

// Pair force (t_ij + t_ji) β V_j y/|y| with t = (A θ ω|ξ| + B ω e)/m, written as
// ω β V_j [ |ξ| (α_i + α_j)(|y| + |ξ|) + (b_i + b_j) num ] / ((|y| + |ξ|) |y|),
// α = Aθ/m and b = B/m per particle: one division per bond.
template <int D, bool Energy>
std::int64_t lps_forces(const LpsArgs& a) {
  const FamilyView& fam = a.fam;
  const m8 breaking = a.breaking && a.after_force ? m8{} - 1 : m8{};
  std::int64_t newly = 0;
#pragma omp parallel for schedule(static) reduction(+ : newly)
  for (Index k = 0; k < fam.n_owners; ++k) {
    const Index i = fam.particle(k);
    d8 acc[D], dev = splat(0.0);
    for (auto& x : acc) x = splat(0.0);
    Block<D> B;
    d8 ab_j[2];  // α_j, b_j
    const double alpha_i = a.alpha_beta[2 * i], beta_i = a.alpha_beta[2 * i + 1], theta_i = a.theta[i];
    for_each_block<D>(a, i, B, [&](auto mode, BondIndex b0, int count) {
      if constexpr (decltype(mode)::wide)  // rows of two doubles: readable wherever u_j is
        gather_rows_wide<2, 2>(a.alpha_beta, B.j, ab_j);
      else
        gather_rows_narrow<2, 2>(a.alpha_beta, B.j, ab_j);
      const Deformed<D> g = deform<D>(B);
      const d8 coef =
          B.wv * (B.L * (alpha_i + ab_j[0]) * (g.len + B.L) + (beta_i + ab_j[1]) * g.num) / ((g.len + B.L) * g.len);
      for (int d = 0; d < D; ++d) add_to(acc[d], keep(B.live, coef * g.y[d]));
      if constexpr (Energy) {
        const d8 ed = g.num / (g.len + B.L) - a.gamma * theta_i * B.L;  // deviatoric extension
        add_to(dev, keep(B.live, B.wv * ed * ed));
      }
      // Break-after-force rule: i's side only, which no other particle reads in this pass.
      newly += mark_broken(fam, b0, count, breaking & B.live & reaches_critical_stretch(g.num, g.len, B.L, a.s0, true));
    });
    for (int d = 0; d < D; ++d) a.f[D * i + d] = lane_sum(acc[d]);
    if constexpr (Energy) a.energy[i] = 0.5 * a.kappa * theta_i * theta_i + 0.5 * beta_i * lane_sum(dev);
  }
  return newly;
}

// A per-offset value of each lane's bond (lps_plastic's c): one load where the
// block's offsets are consecutive (the array is padded), else one read per lane.
inline d8 per_offset(const double* v, const std::uint16_t* k, int count) {
  if (k[count - 1] - k[0] == count - 1) return load8(v + k[0]);
  return d8{v[k[0]], v[k[1]], v[k[2]], v[k[3]], v[k[4]], v[k[5]], v[k[6]], v[k[7]]};
}

// lps_plastic's first pass: LPS's dilatation (same breaks, same θ) and the
// deviatoric dilatation θ_c = (d/m_d) Σ c ωβ|ξ| e V, keeping e per bond in a scratch
// row of the thread; then a second sweep over the family: ε = e − γθ_c|ξ| − p_n and
// Σ c ωβ V ε² over the live bonds, ε in place; then the model's return mapping of the
// particle, which reads ε from the row (it stays in cache: no ε goes to memory).
template <int D>
std::int64_t lps_plastic_extension(const LpsPlasticArgs& p) {
  const LpsArgs& a = p.lps;
  const FamilyView& fam = a.fam;
  const m8 breaking = a.breaking && !a.after_force ? m8{} - 1 : m8{};
  const double s0 = a.s0;
  std::int64_t newly = 0;
#pragma omp parallel reduction(+ : newly)
  {
    std::vector<double> strain;  // e, then ε, of the family being swept (padded to whole blocks)
#pragma omp for schedule(static)
    for (Index k = 0; k < fam.n_owners; ++k) {
      const Index i = fam.particle(k);
      const BondIndex begin = fam.offsets[i], end = fam.offsets[i + 1];
      if (strain.size() < static_cast<std::size_t>(end - begin) + lanes) strain.resize(end - begin + lanes);
      double* row = strain.data();  // row[b − begin] for b in [begin, end + lanes)
      d8 acc = splat(0.0), acc_c = splat(0.0);
      Block<D> B;
      for_each_block<D, Lanes::state>(a, i, B, [&](auto, BondIndex b0, int count) {
        const Deformed<D> g = deform<D>(B);
        const m8 breaks =
            breaking & breakable_lanes(fam, B.live, b0, count) & reaches_critical_stretch(g.num, g.len, B.L, s0, false);
        const m8 acts = B.live & ~breaks;
        const d8 e = g.num / (g.len + B.L);
        const d8 moment = keep(acts, B.wv * B.L * e);  // ω β |ξ| e V_j
        add_to(acc, moment);
        add_to(acc_c, per_offset(p.shell, fam.shape + b0, count) * moment);
        __builtin_memcpy(row + (b0 - begin), &e, sizeof e);
        // p_n of the block, read by the second sweep: the load missed the cache there (a
        // stream the hardware prefetcher does not follow among the gathers).
        __builtin_prefetch(p.plastic_extension + b0);
        __builtin_prefetch(p.plastic_extension + b0 + lanes - 1);
        newly += mark_broken(fam, b0, count, breaks);
      });
      a.theta[i] = a.m[i] > 0.0 ? a.d * lane_sum(acc) / a.m[i] : 0.0;
      const double theta_c = a.d * lane_sum(acc_c) * p.inv_md[i];
      p.theta_c[i] = theta_c;
      const double gt = a.gamma * theta_c;
      d8 n2 = splat(0.0);
      for (BondIndex b0 = begin; b0 < end; b0 += lanes) {
        const int count = static_cast<int>(std::min<BondIndex>(lanes, end - b0));
        const m8 live = state_lanes(fam, b0, count);
        if (!any(live)) continue;  // its row was not written (skipped above); no ε is read from it
        const std::uint16_t* shape = fam.shape + b0;
        const Index* j = fam.neighbor + b0;
        const d8 L = per_offset(a.table.length, shape, count);
        d8 wvc = per_offset(a.table.weight, shape, count) * per_offset(p.shell, shape, count);
        if (a.uniform_volume)
          wvc *= a.volume[0];
        else
          wvc *= d8{a.volume[j[0]], a.volume[j[1]], a.volume[j[2]], a.volume[j[3]],
                    a.volume[j[4]], a.volume[j[5]], a.volume[j[6]], a.volume[j[7]]};
        const d8 eps = load8(row + (b0 - begin)) - gt * L - load8(p.plastic_extension + b0);
        add_to(n2, keep(live, wvc * eps * eps));
        __builtin_memcpy(row + (b0 - begin), &eps, sizeof eps);
      }
      p.norm2[i] = lane_sum(n2);
      p.return_map(p.model, i, row);
    }
  }
  return newly;
}

// How far ahead (bond sides) the force pass prefetches the plastic extensions: eight
// blocks (measured: 4 blocks 1.94×, 8 1.90×, 16 1.92× elastic LPS on the 40³ cube).
constexpr BondIndex kPrefetchBonds = 8 * lanes;

// lps_plastic's force pass: (t_ij + t_ji) β V_j y/|y| with
// t_ij + t_ji = ω [ |ξ| (μ_i + μ_j) + c (s_i ε_ij + s_j ε_ji) ], ε_ij = e − γθ_c,i|ξ| − p_ij and
// ε_ji = e − γθ_c,j|ξ| − p_ji (the same expression, on the same bits, as each side's first
// pass: e is symmetric).
// W_i = volumetric part + ½ (B/m_d) Σ c ωβ V (r ε)².
template <int D, bool Energy>
std::int64_t lps_plastic_forces(const LpsPlasticArgs& p) {
  const LpsArgs& a = p.lps;
  const FamilyView& fam = a.fam;
  const m8 breaking = a.breaking && a.after_force ? m8{} - 1 : m8{};
  std::int64_t newly = 0;
#pragma omp parallel for schedule(static) reduction(+ : newly)
  for (Index k = 0; k < fam.n_owners; ++k) {
    const Index i = fam.particle(k);
    d8 acc[D], dev = splat(0.0);
    for (auto& x : acc) x = splat(0.0);
    Block<D> B;
    d8 row_j[3];  // μ_j, s_j, γθ_c,j
    const double mu_i = p.particle_rows[4 * i], s_i = p.particle_rows[4 * i + 1], gt_i = p.particle_rows[4 * i + 2];
    for_each_block<D>(a, i, B, [&](auto, BondIndex b0, int count) {
      gather_rows_wide<3, 4>(p.particle_rows, B.j, row_j);  // rows of four: always readable
      const Deformed<D> g = deform<D>(B);
      const d8 c = per_offset(p.shell, fam.shape + b0, count);
      // p_ij and p_ji of the blocks ahead (streams the hardware prefetcher loses among the gathers).
      __builtin_prefetch(p.plastic_extension + b0 + kPrefetchBonds);
      __builtin_prefetch(p.reverse_plastic + b0 + kPrefetchBonds);
      const d8 e = g.num / (g.len + B.L);
      const d8 eps_i = e - gt_i * B.L - load8(p.plastic_extension + b0);
      const d8 eps_j = e - row_j[2] * B.L - load8(p.reverse_plastic + b0);
      const d8 t = B.L * (mu_i + row_j[0]) + c * (s_i * eps_i + row_j[1] * eps_j);
      const d8 coef = B.wv * t / g.len;
      for (int d = 0; d < D; ++d) add_to(acc[d], keep(B.live, coef * g.y[d]));
      if constexpr (Energy) add_to(dev, keep(B.live, B.wv * c * eps_i * eps_i));
      // Break-after-force rule: i's side only, which no other particle reads in this pass.
      newly += mark_broken(fam, b0, count, breaking & B.live & reaches_critical_stretch(g.num, g.len, B.L, a.s0, true));
    });
    for (int d = 0; d < D; ++d) a.f[D * i + d] = lane_sum(acc[d]);
    if constexpr (Energy) a.energy[i] = p.volumetric_energy[i] + 0.5 * s_i * p.scale[i] * lane_sum(dev);
  }
  return newly;
}

}  // namespace
}  // namespace pdmpm::pd::kernels::PDMPM_SIMD_NS

namespace pdmpm::pd::kernels {

const KernelSet PDMPM_SIMD_SET = {
    PDMPM_SIMD_NAME,
    {{PDMPM_SIMD_NS::pmb<1, false>, PDMPM_SIMD_NS::pmb<1, true>},
     {PDMPM_SIMD_NS::pmb<2, false>, PDMPM_SIMD_NS::pmb<2, true>},
     {PDMPM_SIMD_NS::pmb<3, false>, PDMPM_SIMD_NS::pmb<3, true>}},
    {PDMPM_SIMD_NS::lps_dilatation<1>, PDMPM_SIMD_NS::lps_dilatation<2>, PDMPM_SIMD_NS::lps_dilatation<3>},
    {{PDMPM_SIMD_NS::lps_forces<1, false>, PDMPM_SIMD_NS::lps_forces<1, true>},
     {PDMPM_SIMD_NS::lps_forces<2, false>, PDMPM_SIMD_NS::lps_forces<2, true>},
     {PDMPM_SIMD_NS::lps_forces<3, false>, PDMPM_SIMD_NS::lps_forces<3, true>}},
    {PDMPM_SIMD_NS::lps_plastic_extension<1>, PDMPM_SIMD_NS::lps_plastic_extension<2>,
     PDMPM_SIMD_NS::lps_plastic_extension<3>},
    {{PDMPM_SIMD_NS::lps_plastic_forces<1, false>, PDMPM_SIMD_NS::lps_plastic_forces<1, true>},
     {PDMPM_SIMD_NS::lps_plastic_forces<2, false>, PDMPM_SIMD_NS::lps_plastic_forces<2, true>},
     {PDMPM_SIMD_NS::lps_plastic_forces<3, false>, PDMPM_SIMD_NS::lps_plastic_forces<3, true>}},
};

}  // namespace pdmpm::pd::kernels
