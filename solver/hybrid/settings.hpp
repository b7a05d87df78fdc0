#pragma once
// The options of an adaptive SBPD–MPM run (scene table [hybrid]; Noorian et al.,
// adaptive SBPD–MPM, §2). Radii in units of the horizon δ, paper values as defaults.
#include <array>
#include <string>

#include "solver/core/named_enum.hpp"
#include "solver/hybrid/crack_tips.hpp"
#include "solver/hybrid/regions.hpp"

namespace pdmpm::hybrid {

// The paper's three runs of one scene: pure SBPD over the whole body, PD regions
// that only grow, and regions that grow with the tips and shrink behind them.
enum class Mode { pd, expand, expand_shrink };
constexpr std::array<EnumName<Mode>, 3> names(Mode) {
  return {{{Mode::pd, "pd"}, {Mode::expand, "expand"}, {Mode::expand_shrink, "expand_shrink"}}};
}

// How the transition particles (grid particles inside a PD particle's horizon, virtual
// PD particles) take part in PD. paper: their PD state (m, θ, the plastic return) comes
// from their bonds to PD particles alone, as a surface particle's would (Noorian et al.
// eq 10). full_state: from their whole family — the bonds to grid particles count in the
// state and exchange no force — so under an affine motion their force states, and with
// them the PD particles' forces, are the interior ones (docs/models/hybrid.md, ghost forces).
// blended: the two energies blended over a band around each region (hybrid/blend_zone.hpp):
// the grid's stress weighted by 1 − β, each PD force state by its owner's β, whole-family
// states, so the grid sees no hole (Badia et al. 2008; docs/models/hybrid.md).
enum class Coupling { paper, full_state, blended };
constexpr std::array<EnumName<Coupling>, 3> names(Coupling) {
  return {{{Coupling::paper, "paper"}, {Coupling::full_state, "full_state"}, {Coupling::blended, "blended"}}};
}

// What an MPM particle turned PD carries of its plastic state (plastic_state_transfer.hpp).
// strain: its plastic strain, as each bond's plastic extension p = |ξ| n·ε_p·n — right at
// small strain only (the grid's is a log strain, the bonds' extensions are not: at 5 %
// strain a round trip moves the stress by its own size). elastic_state: the plastic state
// that gives the particle, at its current bond geometry, the grid's elastic strain — no
// spurious stress at any strain (plane strain and 3D: the deviatoric part; docs/models/hybrid.md).
enum class PlasticTransfer { strain, elastic_state };
constexpr std::array<EnumName<PlasticTransfer>, 2> names(PlasticTransfer) {
  return {{{PlasticTransfer::strain, "strain"}, {PlasticTransfer::elastic_state, "elastic_state"}}};
}

struct Settings {
  Mode mode = Mode::expand_shrink;
  Coupling coupling = Coupling::paper;
  PlasticTransfer plastic_transfer = PlasticTransfer::strain;
  RegionRadii radii;  // R_pd, l_crit, l_ext, l_con (δ)
  // coupling = blended: the band over which β falls from 1 to 0, beyond the grid-moved layer
  // of one bond reach where β = 1 (δ; project decision, the paper has no blend).
  double blend_width = 2.0;
  int shrink_every = 1;  // i_crit: look for tips and shrink after every i_crit expansions (paper: 1)
  // A shrink reverts a PD particle only if at most this share of its deviatoric PD elastic
  // energy is non-affine (hybrid::non_affine_share): the part one deformation gradient cannot
  // carry, which its return to the grid would lose. 1: the paper's rule, every particle
  // beyond l_con reverts (project decision; the paper is silent on the energy of a conversion).
  double revert_residual = 1.0;
  CrackTipSettings tips;
  // Particles with a bond cut before the run (a pre-crack) start PD with a region of
  // R_pd around them: an MPM grid cannot carry a cut (project decision, the paper is silent).
  bool precrack_starts_pd = true;
  // Measure the energy each conversion adds (conversion_energy()): up to three extra PD
  // evaluations in every step in which bonds break or particles fail. Diagnostics and tests.
  bool audit_conversions = false;

  // Throws InputError naming the key (hybrid.…) in `file`.
  void validate(const std::string& file = "") const;
};

}  // namespace pdmpm::hybrid
