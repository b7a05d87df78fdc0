#pragma once
// Everything a peridynamic force model acts on: particles, families (built once
// for the whole body), the bond table and the per-bond state; which particles
// the PD force loops visit (owners) follows the particles' kinds.
#include <algorithm>
#include <cstdint>
#include <optional>
#include <vector>

#include "solver/core/families.hpp"
#include "solver/core/particles.hpp"
#include "solver/pd/bond_state.hpp"
#include "solver/pd/bond_table.hpp"
#include "solver/pd/hpd_options.hpp"
#include "solver/core/material.hpp"

namespace pdmpm::pd {

static_assert(core::kBondPadding >= kernels::lanes, "bond arrays must be padded for whole-block kernel loads");

template <int D>
struct System {
  core::Particles<D> particles;
  core::Families<D> families;
  BondTable<D> table;
  BondState bonds;
  // Real particles whose bond loops run (PD-like kinds), in increasing order;
  // empty when every real particle is PD (the kernels then visit all of them).
  std::vector<Index> owners;

  core::Setting setting = core::Setting::solid3d;
  core::Elastic material;
  std::optional<core::J2Hardening> hardening;  // plastic models; none: elastic
  core::DuctileFailure ductile_failure;        // plastic models: ε_f = d₀ exp(cη) on ε̄_p (off by default)
  double delta = 0.0;                          // horizon δ
  double measure = 1.0;                        // thickness (2D), area (1D), 1 (3D)
  Influence influence = Influence::constant;
  PartialVolume partial_volume = PartialVolume::seed001;
  // LPS weighted volume: false → the discrete sum over each family (docs/models/lps.md; exact
  // patch tests), true → the continuum integral for every particle (Gu & Zhou 2017 eq 15).
  bool continuum_weighted_volume = false;
  // Plastic LPS: weight each bond's deviatoric term by c(n) = 1 + κ(n_x⁴ + n_y⁴ + n_z⁴ − 3/5),
  // κ chosen so the full stencil's fourth bond moment is isotropic (docs/models/lps_plastic.md);
  // false: the plain lattice sums, whose deviatoric response is cubic.
  bool isotropic_deviatoric = false;
  // Plastic LPS: a particle with broken bonds reads its equivalent stress over the live
  // bonds' weighted volume (docs/models/lps_plastic.md, "Damaged particles"); false: over
  // the reference family's, as LPS.
  bool yield_on_live_bonds = false;
  // A hybrid's transition particles measure their state over their whole family (bonds
  // to grid particles state-only, pd/bond_state.hpp); false: over their active bonds.
  bool transition_full_state = false;
  // A hybrid's blended coupling (hybrid/blend_zone.hpp): bonds between transition particles
  // act, and each particle's force state is scaled by its weight β (empty: 1 for all).
  // lps_plastic only (it scales the particle's force-state rows).
  bool transition_pairs_active = false;
  std::vector<double> blend_weight;
  HpdOptions hpd;  // the hybrid model's law and sub-horizon size (solver/pd/hpd.hpp)

  double spacing() const { return particles.lattice.spacing; }
  Index n_real() const { return particles.n_real; }

  kernels::FamilyView family_view() {
    const bool all = owners.empty();
    return {all ? families.n_owners() : static_cast<Index>(owners.size()),
            all ? nullptr : owners.data(),
            particles.size(),
            families.offsets.data(),
            families.neighbor.data(),
            families.shape.data(),
            bonds.kernel_flags(),
            transition_full_state};
  }

  // Whether every particle (ghosts too) has the same volume, as on a lattice body.
  bool uniform_volume() const {
    const auto& v = particles.volume;
    return std::all_of(v.begin(), v.end(), [&](double x) { return x == v.front(); });
  }

  // Build families and the bond table for the whole body, once: later changes of
  // particle kind change which bonds are live, never the families.
  void connect() {
    families = core::Families<D>::build(particles, family_ratio(partial_volume, delta, spacing()));
    table = BondTable<D>::build(families.stencil, spacing(), delta, influence, partial_volume);
    bonds.reset(families.n_bonds(), core::kBondPadding);
    refresh_activity();
  }

  // Kind of any particle, mirror ghosts taking their owner's.
  core::ParticleKind kind(Index j) const { return particles.kind[particles.source(j)]; }

  // Re-derives every bond's role (pd::bond_role) and the owner list from the kinds;
  // returns the real particles whose set of active or state bonds changed.
  std::vector<Index> refresh_activity() { return refresh_activity_of(nullptr); }

  // The same when only the real particles in `kind_changed` changed kind: a bond's
  // activity depends on its two ends' kinds, so only their bonds and their neighbours'
  // are re-derived (families are symmetric), with the same result as the full pass
  // — which a hybrid paid over the whole body at every conversion. A body with ghosts
  // (periodic images) takes the full pass.
  std::vector<Index> refresh_activity(const std::vector<Index>& kind_changed) {
    if (particles.n_ghost() > 0) return refresh_activity();
    std::vector<std::uint8_t> near(static_cast<std::size_t>(particles.n_real), 0);
    for (const Index i : kind_changed) {
      near[i] = 1;
      for (BondIndex b = families.begin(i); b < families.end(i); ++b) near[families.neighbor[b]] = 1;
    }
    return refresh_activity_of(&near);
  }

  // Calls fn(b, j, k) — bond index, neighbour, stencil offset — for every bond
  // of particle i in the set (pd/bond_state.hpp): live (intact, both ends
  // PD-like), the state (live or state-only) or the reference family (active or
  // state-only, not cut before the run).
  template <class Fn>
  void for_each_bond(Index i, BondSet set, Fn&& fn) const {
    for (BondIndex b = families.begin(i); b < families.end(i); ++b)
      if (set == BondSet::live        ? bonds.live(b)
              : set == BondSet::state ? bonds.in_state(b)
                                      : bonds.in_reference_family(b))
        fn(b, families.neighbor[b], static_cast<int>(families.shape[b]));
  }
  template <class Fn>
  void for_each_live_bond(Index i, Fn&& fn) const {
    for_each_bond(i, BondSet::live, fn);
  }

 private:
  // The full pass over every real particle's bonds, or only over those flagged in `only`.
  std::vector<Index> refresh_activity_of(const std::vector<std::uint8_t>* only) {
    const Index n = particles.n_real;
    std::vector<Index> changed;
    owners.clear();
    bool all_pd = true;
    for (Index i = 0; i < n; ++i) {
      const auto ki = particles.kind[i];
      if (!only || (*only)[i]) {
        bool moved = false;
        for (BondIndex b = families.begin(i); b < families.end(i); ++b) {
          const BondRole role =
              bond_role(ki, kind(families.neighbor[b]), transition_full_state, transition_pairs_active);
          moved = moved || role != bonds.role(b);
          bonds.set_role(b, role);
        }
        if (moved) changed.push_back(i);
      }
      if (pd_like(ki)) owners.push_back(i);
      all_pd = all_pd && ki == core::ParticleKind::pd;
    }
    if (all_pd) owners.clear();
    return changed;
  }
};

}  // namespace pdmpm::pd
