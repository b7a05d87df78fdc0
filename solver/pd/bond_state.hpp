#pragma once
// Per-bond state of a PD body, kept for the whole body (families are built once)
// so that it survives any change of which particles are PD.
//
// One flag byte per bond, read by the bond kernels as "live when zero":
//   broken   (bit 0) μ = 0 for ever: set by the critical-stretch rule, a pre-crack
//            or a test; nothing clears it (a region change only touches bit 1);
//   inactive (bit 1) an end of the bond is not PD-like at the moment
//            (pd::bond_active decides, from the particle kinds);
//   cut      (bit 2) broken before the run (pre-crack, test set-up): the bond
//            is not part of the reference family (LPS weighted volume), while a
//            bond broken by the run still is, so m does not depend on the history
//            of particle kinds.
//   state    (bit 3) the bond counts in its owner's state (m, θ, the plastic return)
//            but exchanges no force: a hybrid's transition particle, with the
//            full-state coupling, measures its state over its whole family
//            (hybrid/settings.hpp, Coupling::full_state). Never set with bit 1.
// The flags the kernels write are a trial state; accept() commits it at the end
// of a step, reject() returns to the last committed state (the Lanczos estimate
// and dynamic relaxation's trial evaluations need no hand-made save/restore).
// A later per-bond quantity (plastic extension) joins as another Committed<T>.
#include <cstdint>
#include <string>
#include <vector>

#include "solver/core/index.hpp"
#include "solver/core/particles.hpp"
#include "solver/core/state_archive.hpp"
#include "solver/pd/kernels/bond_kernels.hpp"

namespace pdmpm::pd {

inline constexpr std::uint8_t kBondBroken = 1;
inline constexpr std::uint8_t kBondInactive = 2;
inline constexpr std::uint8_t kBondCut = 4;
inline constexpr std::uint8_t kBondStateOnly = kernels::kStateOnlyFlag;

// Which bonds of a family a sum runs over: the live ones (what acts now), those of
// the particle's state (live, or state-only and intact), or the reference family
// (what LPS's weighted volume is built on).
enum class BondSet { live, state, reference };

// A particle takes part in PD bonds when it is PD, or a transition particle (an
// MPM particle inside a PD particle's horizon, a virtual PD particle).
inline bool pd_like(core::ParticleKind k) { return k == core::ParticleKind::pd || k == core::ParticleKind::transition; }
// A bond acts when both ends are PD-like and at least one is PD: bonds between
// two transition particles belong to the grid, not to PD.
inline bool bond_active(core::ParticleKind a, core::ParticleKind b) {
  return pd_like(a) && pd_like(b) && (a == core::ParticleKind::pd || b == core::ParticleKind::pd);
}
// What a bond from a particle of kind a to one of kind b is: active (forces and state),
// state only (a transition particle's bond to a grid particle, when transition
// particles keep whole families), or inactive.
enum class BondRole : std::uint8_t { active, state_only, inactive };
// With `transition_pairs` (the hybrid's blended coupling) bonds between two transition
// particles act too: the band's PD energy is weighted, not cut (hybrid/blend_zone.hpp).
inline BondRole bond_role(core::ParticleKind a, core::ParticleKind b, bool transition_full_state,
                          bool transition_pairs = false) {
  if (bond_active(a, b)) return BondRole::active;
  if (transition_pairs && a == core::ParticleKind::transition && b == core::ParticleKind::transition)
    return BondRole::active;
  const bool grid_particle = b == core::ParticleKind::mpm || b == core::ParticleKind::transition;
  if (transition_full_state && a == core::ParticleKind::transition && grid_particle) return BondRole::state_only;
  return BondRole::inactive;
}
inline std::uint8_t role_bits(BondRole r) {
  return r == BondRole::active ? 0 : r == BondRole::state_only ? kBondStateOnly : kBondInactive;
}

// Values per item as a trial (what the current evaluation writes) and as
// committed at the last accepted step.
template <class T>
struct Committed {
  std::vector<T> trial, committed;

  void assign(std::size_t n, T value) {
    trial.assign(n, value);
    committed.assign(n, value);
  }
  void accept() { committed = trial; }
  void reject() { trial = committed; }
  void checkpoint(core::StateArchive& a, const std::string& name) {
    a.sync(name + "/trial", trial);
    a.sync(name + "/committed", committed);
  }
};

struct BondState {
  Committed<std::uint8_t> flags;
  std::int64_t pending_breaks = 0;  // bonds broken since the last accept/reject

  void reset(BondIndex n_bonds, BondIndex padding) {
    flags.assign(n_bonds + padding, 0);
    pending_breaks = 0;
  }
  bool broken(BondIndex b) const { return flags.trial[b] & kBondBroken; }
  bool live(BondIndex b) const { return flags.trial[b] == 0; }
  // Counts in its owner's state now: live, or a state-only bond that is intact.
  bool in_state(BondIndex b) const { return (flags.trial[b] & ~kBondStateOnly) == 0; }
  // Active, and not cut before the run (broken during it or not).
  bool in_reference_family(BondIndex b) const { return !(flags.trial[b] & (kBondInactive | kBondCut)); }
  std::uint8_t* kernel_flags() { return flags.trial.data(); }

  // Breaks bond b before the run, in the trial and the committed state (pre-cracks, tests).
  void cut(BondIndex b) {
    flags.trial[b] |= kBondBroken | kBondCut;
    flags.committed[b] |= kBondBroken | kBondCut;
  }
  // Region changes: sets bits 1 and 3 in both states, never touches bit 0.
  void set_role(BondIndex b, BondRole role) {
    const std::uint8_t keep = static_cast<std::uint8_t>(~(kBondInactive | kBondStateOnly));
    const std::uint8_t bits = role_bits(role);
    flags.trial[b] = static_cast<std::uint8_t>((flags.trial[b] & keep) | bits);
    flags.committed[b] = static_cast<std::uint8_t>((flags.committed[b] & keep) | bits);
  }
  BondRole role(BondIndex b) const {
    const std::uint8_t f = flags.trial[b];
    return f & kBondInactive ? BondRole::inactive : f & kBondStateOnly ? BondRole::state_only : BondRole::active;
  }
  // Copies only when the step changed something (most steps break no bond).
  void accept() {
    if (pending_breaks) flags.accept();
    pending_breaks = 0;
  }
  void reject() {
    if (pending_breaks) flags.reject();
    pending_breaks = 0;
  }
  void checkpoint(core::StateArchive& a) {
    flags.checkpoint(a, "pd/bond_flags");
    a.sync("pd/pending_breaks", pending_breaks);
  }
};

}  // namespace pdmpm::pd
