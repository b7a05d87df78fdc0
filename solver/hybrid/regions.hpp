#pragma once
// Which particles of the adaptive SBPD–MPM hybrid are PD, transition or MPM, and
// how the PD regions are formed, grown and shrunk around crack tips (Noorian et
// al., adaptive SBPD–MPM, §2, eqs 11–12):
//   onset   an MPM particle that fails is removed, and every particle within
//           R_pd of it becomes PD;
//   expand  (eq 11) a PD particle with a bond broken this step that lies within
//           l_crit of a transition particle turns every MPM or transition
//           particle within l_ext of it into PD;
//   shrink  (eq 12) PD particles farther than l_con from every crack tip revert
//           to MPM, except those the caller keeps;
//   classify after each of them: a non-PD particle within bond reach of a PD
//           particle is transition, any other non-PD particle is MPM.
// The functions only rewrite kind bytes and return who changed, so the caller
// converts the particles' state (stress, deformation gradient, bond flags).
//
// Distances are measured in the reference configuration, on the lattice: bonds
// (and so the transition set) are defined there, and a distance between two
// sites is an exact integer comparison, so membership does not depend on the
// deformation or on round-off. Every neighbourhood query goes through one
// visitor over lattice offsets (regions.cpp, for_each_within); measuring in the
// current configuration means replacing it with a core::CellList query on x0 + u.
//
// Removed particles: onset sets a particle's kind to core::ParticleKind::removed
// and its byte in the `removed` mask (indexed like the particle store), and
// nothing here changes either again: no bond reaches a removed particle
// (pd::bond_active) and the MPM step does not map it to the grid. The mask is
// what the functions below read, so a caller's kind array cannot revive one.
//
// No healing: shrink reverts a damaged PD particle only if the caller lets it;
// the `keep` mask (e.g. damage > 0) names the particles that must stay PD.
//
// Symmetry ghosts (indices ≥ n_real) copy their owner's kind. Regions are not
// mirrored: onset, expand and shrink act on real particles only (a region that
// reaches a symmetry plane is cut by it, not reflected).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "solver/core/particles.hpp"
#include "solver/core/site_map.hpp"
#include "solver/core/stencil.hpp"

namespace pdmpm::hybrid {

// The radii of the region rules, in units of the horizon δ (paper defaults).
struct RegionRadii {
  double pd_radius = 7.0;       // R_pd, region formed at onset
  double expand_trigger = 3.0;  // l_crit, eq 11
  double expand_radius = 7.0;   // l_ext, eq 11
  double keep_radius = 7.0;     // l_con, eq 12

  // Throws InputError naming the key (hybrid.pd_radius, …) in `file`.
  void validate(const std::string& file = "") const;
};

// Lattice look-ups built once per body: the site map and the offsets that reach
// every site within each radius.
template <int D>
class RegionMap {
 public:
  // horizon_ratio = δ/Δx scales the radii; family_ratio is the bond reach in
  // lattice spacings (pd::family_ratio), so transition means bond membership.
  RegionMap(const core::Particles<D>& p, double horizon_ratio, double family_ratio, const RegionRadii& radii);

  Index size() const { return static_cast<Index>(site_.size()); }  // real particles and ghosts
  Index n_real() const { return n_real_; }
  const IVec<D>& site(Index i) const { return site_[i]; }
  Index owner(Index i) const { return i < n_real_ ? i : ghost_owner_[i - n_real_]; }
  Index find(const IVec<D>& s) const { return map_.find(s); }

  const core::Lattice<D>& lattice() const { return lattice_; }
  const core::Stencil<D>& bonds() const { return bonds_; }
  const core::Stencil<D>& pd_ball() const { return pd_ball_; }
  const core::Stencil<D>& trigger_ball() const { return trigger_ball_; }
  const core::Stencil<D>& expand_ball() const { return expand_ball_; }
  double keep_ratio() const { return keep_ratio_; }  // l_con/Δx

 private:
  core::Lattice<D> lattice_;
  std::vector<IVec<D>> site_;
  std::vector<Index> ghost_owner_;
  Index n_real_;
  core::SiteMap<D> map_;
  core::Stencil<D> bonds_, pd_ball_, trigger_ball_, expand_ball_;
  double keep_ratio_;
};

// Shapes shared by the functions below: `kind` covers every particle of the
// store (map.size()); `removed` and `keep` are byte masks (non-zero = set) with
// at least n_real entries, read for real particles only. Returned index lists
// are ascending and hold real particles only.

// Transition and MPM kinds from the PD set (PD and removed particles unchanged);
// ghosts copy their owner's kind.
template <int D>
void classify(const RegionMap<D>& map, std::span<core::ParticleKind> kind, std::span<const std::uint8_t> removed);

// Onset: removes each failed particle (it must not be removed already), then
// makes every particle within R_pd of one of them PD. Returns those made PD.
template <int D>
std::vector<Index> onset(const RegionMap<D>& map, std::span<const Index> failed, std::span<core::ParticleKind> kind,
                         std::span<std::uint8_t> removed);

// Initial regions: every particle within R_pd of one of `centres` becomes PD, none
// is removed (e.g. around a pre-crack, whose faces an MPM grid cannot carry).
// Returns those made PD.
template <int D>
std::vector<Index> seed(const RegionMap<D>& map, std::span<const Index> centres, std::span<core::ParticleKind> kind,
                        std::span<const std::uint8_t> removed);

// Expansion (eq 11). `triggers`: particles with a bond broken this step; those
// that are not PD are ignored, so the caller may pass every bond owner. Which
// triggers fire is decided on the kinds before any conversion, so the result
// does not depend on their order. Returns the particles made PD.
template <int D>
std::vector<Index> expand(const RegionMap<D>& map, std::span<const Index> triggers, std::span<core::ParticleKind> kind,
                          std::span<const std::uint8_t> removed);

// Shrink (eq 12): PD particles neither within l_con of a tip nor kept revert.
// `tips` are reference positions (with no tip, every PD particle not kept
// reverts). Returns the particles that left PD (now transition or MPM).
template <int D>
std::vector<Index> shrink(const RegionMap<D>& map, const std::vector<Vec<D>>& tips, std::span<const std::uint8_t> keep,
                          std::span<core::ParticleKind> kind, std::span<const std::uint8_t> removed);

}  // namespace pdmpm::hybrid
