#pragma once
// Crack observables: when and where a PD body cracks, computed from the broken
// flags and the local damage φ at the run's history samples. Definitions (the
// README's "Crack observables" section restates them for users):
//
//  cracked particle   φ_i ≥ threshold (default ½), i not excluded.
//  crack face         φ_i ≥ path_threshold (default 0.35), i not excluded. A clean
//                     straight cut leaves its face particles at φ ≈ 0.39 (δ = 3Δx:
//                     the share of a disk beyond Δx/2 from its centre), below ½, so
//                     crack paths follow the faces: with ½ a crack's tip would stand
//                     still while the cut advances and then jump.
//  excluded           the initial notch — particles with φ > 0 before the first step
//                     (the neighbourhood of the pre-cracks) — plus the particles of the
//                     scene's crack.exclude regions (supports, loaded layers: a boundary
//                     layer tearing off along its length is not a propagating crack).
//  initiation time    first sample at which some particle is cracked; the
//                     initiation particles are the ones cracked at that sample.
//  first bond failure at a named location: first sample at which a bond of a
//                     particle within the location's radius is broken (bonds cut by
//                     pre-cracks do not count).
//  components         connected components of the graph whose vertices are the
//                     real particles and whose edges are the intact bonds (union–find;
//                     a bond to a symmetry ghost joins its owner): fragments included.
//  pieces             the same graph without the particles at φ ≥ threshold (the crack
//                     itself), counting components that hold at least min_piece_fraction
//                     of the particles. Removing the crack's particles matters: a particle
//                     pulled into an opening crack keeps compressed bonds to both faces,
//                     which would otherwise join two pieces that carry no load between them.
//  separation time    first sample with more pieces than before the first step.
//  cracks             connected sets of crack-face particles, two being linked when
//                     they are family members (|ξ| ≤ δ). A crack's identity is its
//                     earliest member; when two cracks join, the younger one ends. Its
//                     origin is the centroid of its members at its first sample; its tip
//                     is the member farthest from the origin (reference positions).
//  path               the tip positions at every sample (a polyline in time).
//  extent             |tip − origin|; angle: direction of the chord origin → tip.
//  speed              growth rate of the extent's running maximum r̂: least-squares
//                     slope of r̂ against t over the samples in a sliding window
//                     [t − W, t]; undefined until the crack is W old. The tip moves in
//                     lattice steps: the default W = 10 Δx / c_R (crack.speed_window)
//                     makes a one-site error worth at most 10 % of c_R.
//  overall angle      direction of the principal axis of all crack-face particles.
#include <limits>
#include <optional>
#include <unordered_map>
#include <string>
#include <vector>

#include "solver/pd/system.hpp"

namespace pdmpm::pd {

struct CrackSettings {
  double threshold = 0.5;            // φ at which a particle counts as cracked
  double path_threshold = 0.35;      // φ of the particles that make up crack paths (crack faces)
  double min_piece_fraction = 0.01;  // smallest component counted as a piece, as a fraction of N
  double speed_window = 0.0;         // W in seconds; 0 → 10 Δx / c_R
};

template <int D>
struct NamedLocation {
  std::string name;
  Vec<D> point = Vec<D>::Zero();
  double radius = 0.0;
  std::vector<Index> particles;  // real particles within radius of point
};

template <int D>
struct CrackPath {
  Index key = -1;                 // earliest-cracked member (the crack's identity)
  Vec<D> origin = Vec<D>::Zero();
  bool ended = false;             // joined an older crack
  std::vector<double> time;
  std::vector<Vec<D>> tip;
  std::vector<double> extent;     // |tip − origin|
  std::vector<double> reach;      // running maximum of the extent
  std::vector<double> speed;      // windowed growth rate of the running maximum extent
  std::size_t members = 0;        // cracked particles at the last sample

  double max_speed() const;
  double angle_deg() const;       // chord origin → last tip, from the x axis
};

// Rayleigh wave speed of an isotropic solid in the given setting: root of
// (2 − ξ²)² = 4 √(1 − ξ²) √(1 − ξ² c_s²/c_p²), c_R = ξ c_s, with c_p of the setting.
double rayleigh_speed(const core::Elastic& m, core::Setting s);

template <int D>
class CrackObservables {
 public:
  // `exclude` marks particles where no crack is detected, in addition to those
  // damaged at the first sample. Call sample() at t = 0 before the first step.
  CrackObservables(const System<D>& sys, const CrackSettings& settings, std::vector<NamedLocation<D>> locations,
                   std::vector<std::uint8_t> exclude);

  void sample(const System<D>& sys, const std::vector<double>& phi, double t);

  const CrackSettings& settings() const { return settings_; }
  double speed_window() const { return settings_.speed_window > 0.0 ? settings_.speed_window : default_window_; }
  const std::vector<NamedLocation<D>>& locations() const { return locations_; }
  // Times are empty until the event has been seen.
  std::optional<double> initiation_time() const { return initiation_; }
  const std::vector<Index>& initiation_particles() const { return initiation_particles_; }
  std::optional<double> separation_time() const { return separation_; }
  std::optional<double> first_failure(std::size_t location) const { return first_failure_[location]; }
  std::int64_t broken_at(std::size_t location) const { return broken_at_[location]; }
  Index components() const { return components_; }
  Index pieces() const { return pieces_; }
  Index initial_pieces() const { return initial_pieces_; }
  Index cracked() const { return cracked_; }
  const std::vector<CrackPath<D>>& paths() const { return paths_; }
  // The crack with the largest extent at the last sample (nullptr if none).
  const CrackPath<D>* leading() const;
  double overall_angle_deg() const { return overall_angle_; }
  // The overall angle when the body first separated (NaN before).
  double separation_angle_deg() const { return separation_angle_; }
  double max_speed() const;
  // First sample time at which each particle became a crack face (negative: never).
  const std::vector<double>& crack_time() const { return crack_time_; }
  const std::vector<std::uint8_t>& excluded() const { return excluded_; }

 private:
  void count_components(const System<D>& sys, const std::vector<double>& phi);
  void track_cracks(const System<D>& sys, double t);
  void update_speed(CrackPath<D>& c) const;

  CrackSettings settings_;
  std::vector<NamedLocation<D>> locations_;
  std::vector<std::uint8_t> excluded_;
  bool started_ = false;
  double default_window_ = 0.0;

  std::vector<double> crack_time_;
  std::vector<std::optional<double>> first_failure_;
  std::vector<std::int64_t> baseline_broken_, broken_at_;
  std::optional<double> initiation_, separation_;
  std::vector<Index> initiation_particles_;
  Index components_ = 0, pieces_ = 0, initial_pieces_ = 0, cracked_ = 0;
  double overall_angle_ = 0.0, separation_angle_ = std::numeric_limits<double>::quiet_NaN();
  std::vector<CrackPath<D>> paths_;
  std::unordered_map<Index, std::size_t> path_of_key_;
};

}  // namespace pdmpm::pd
