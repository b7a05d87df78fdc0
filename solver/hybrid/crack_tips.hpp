#pragma once
// Crack tips in the PD region of the adaptive SBPD–MPM hybrid (Noorian et al.,
// adaptive SBPD–MPM, eqs 13–15): a tip is a local minimum of the lattice
// Laplacian of the damage φ. The paper gives no thresholds and calls its tracker
// error-prone; the filters below make it robust on the damage a PD crack leaves.
//
// Detection, per lattice site s of the region:
//  ∇²φ       central differences Σ_a [φ(s+e_a) − 2φ(s) + φ(s−e_a)]/Δx². A missing
//            neighbour (body edge, or a site outside the PD region) takes the value
//            mirrored through s, i.e. a zero normal derivative: a crack that runs
//            out of the region then looks continued, not ended, and undamaged
//            edges stay undamaged. Treating missing sites as undamaged (φ = 0)
//            would put a false tip at the mouth of every edge crack.
//  crack end the 3^D neighbourhood holds φ ≥ damage_threshold, ∇²φ Δx² <
//            laplacian_threshold, and the damage around s within end_radius lies
//            on one side of s along the crack. Moment m = Σ φ(s+o) P o over the
//            window (missing sites mirrored as above, so a region edge does not
//            look like the end of a crack), A = |m| / Σ φ(s+o) |P o|, where P
//            projects onto the crack's line (plane in 3D), whose normal is the axis
//            of least spread of that damage: the part across the crack only tells
//            on which face s sits. A = 1 for damage on one ray, 0 for a line through
//            s, so sites along the faces of a crack and branch points (three arms
//            nearly balance) are dropped.
//  ridge     and s lies on the ridge of its crack's damage band: along the band's
//            normal (the axis of least covariance of the window's damage about its
//            centroid) no site within end_radius has more than φ(s) / ridge_fraction.
//            A site on the band's flank, a row or two off the crack, sees the band to
//            one side; the least second moment about s then lies along the crack, and
//            the flank's damage, which varies from particle to particle along the
//            crack (a bond more or less broken), passes the one-sidedness test. A
//            running PD crack in the central-crack plate put up to 18 false tips on
//            its flanks without this test, and each held a region of keep_radius.
//  candidate a crack-end site with ∇²φ(s) ≤ ∇²φ at every present 3^D − 1
//            neighbour. Non-strict on purpose: on a lattice-aligned crack front
//            equal values are exact, and merging removes the duplicates. Behind a
//            running crack the damage keeps growing, so the deepest ∇²φ can lie on
//            the ridge behind the end and no end site is a minimum: a connected
//            group of crack-end sites without a candidate gives its deepest site.
//  position  the site, moved to the vertex of the parabola through ∇²φ along each
//            axis (at most ½Δx), then tip_offset along −m (towards the intact side): the
//            minimum of ∇²φ sits behind the end of the cut.
//  merging   candidates sorted by ∇²φ (deepest first, ties by site) are kept
//            unless a kept one lies within merge_radius: one tip per crack end.
// In 3D the same rules give points along the crack front, about merge_radius
// apart: the front is a curve of minima, not isolated points.
//
// Matching: previous and new tips closer than match_radius are paired
// closest-first; a paired tip keeps its id, an unpaired new one (a branch, a new
// crack) gets a fresh id, an unpaired previous one has vanished and is dropped.
#include <vector>

#include "solver/core/lattice.hpp"
#include "solver/core/state_archive.hpp"
#include "solver/core/types.hpp"

namespace pdmpm::hybrid {

// Lengths in units of the lattice spacing Δx; ∇²φ thresholds in units of 1/Δx².
struct CrackTipSettings {
  // Below the φ ≈ 0.39 a clean PD cut leaves on its faces (δ = 3Δx), above stray broken bonds.
  double damage_threshold = 0.2;
  // Ends measured at ∇²φ Δx² = −0.3 … −1.1; −0.05 only skips shallow dips of diffuse damage (faces: the end test).
  double laplacian_threshold = -0.05;
  // About a horizon: the damage band of a cut is ±δ wide, the window must see past it along the crack.
  double end_radius = 4.0;
  // Measured: crack faces ≤ 0.2 and a ±30° fork 0.24, ends ≥ 0.66 in 2D; a 3D front 0.39 (a half-disc, not a ray).
  double end_asymmetry = 0.3;
  // A crack end lies on the ridge of the damage band: φ(s) at least this share of the largest φ
  // across the band (within end_radius). Measured: a running tip's site 1.0 (≈ 0.6 even if the
  // band's axis were taken wrongly), the band's flanks 0.31–0.37. 0 turns the test off.
  double ridge_fraction = 0.5;
  // The minimum of ∇²φ lies 0.75 Δx behind the end of a PD cut on average (δ = 3Δx, 40 ends and angles swept).
  double tip_offset = 0.75;
  // A horizon: damage cannot resolve two tips closer than δ, a crack end spreads its minima over ~δ.
  double merge_radius = 3.0;
  // Tips move < 1 Δx a step (CFL, crack speed < c_R) and detection jitters by ~1 Δx.
  double match_radius = 3.0;
};

template <int D>
struct CrackTip {
  int id = -1;                       // from match_crack_tips; -1 straight from detection
  IVec<D> site = IVec<D>::Zero();    // lattice site of the tip
  Vec<D> position = Vec<D>::Zero();  // estimate of the crack's end, near lattice.position(site)
  double laplacian = 0.0;            // ∇²φ at the site (1/length²)
};

}  // namespace pdmpm::hybrid

// An int, a site, a position and a double: its bytes are its value (checkpoints copy them).
template <int D>
inline constexpr bool pdmpm::core::kBytesAreValue<pdmpm::hybrid::CrackTip<D>> = true;

namespace pdmpm::hybrid {

// Tips of the damage field phi[i] at sites[i] (the PD region; distinct sites),
// sorted by site (lexicographic in the coordinates). Ids are -1.
template <int D>
std::vector<CrackTip<D>> find_crack_tips(const core::Lattice<D>& lattice, const std::vector<IVec<D>>& sites,
                                         const std::vector<double>& phi, const CrackTipSettings& s);

// Ids for `found` from the previous step's tips; allocates new ids from next_id
// (in the order of `found`). Returns the tips sorted by id.
template <int D>
std::vector<CrackTip<D>> match_crack_tips(const std::vector<CrackTip<D>>& previous, std::vector<CrackTip<D>> found,
                                          const CrackTipSettings& s, int& next_id);

}  // namespace pdmpm::hybrid
