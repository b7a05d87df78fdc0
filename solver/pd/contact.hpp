#pragma once
// Short-range repulsion between particles that are not joined by an intact
// bond (seed 001 eqs 6.2–6.4; with `bonded_pairs`, between all pairs, as in
// LAMMPS' peri/pmb): for |y| < d_ij,
//   f = (c_s/δ)(|y| − d_ij) y/|y| V_j,  c_s = 15 c,  d_ij = min(0.9|ξ|, 1.35Δx).
// A separate loop over a cell list of the deformed positions, run only when a
// scene enables contact.
#include "solver/core/cell_list.hpp"
#include "solver/pd/system.hpp"

namespace pdmpm::pd {

struct ContactParameters {
  double stiffness_factor = 15.0;
  double distance_factor = 0.9;
  double max_distance = 1.35;  // in Δx
  bool bonded_pairs = false;   // repel bonded pairs too (LAMMPS peri/pmb does)
};

template <int D>
class ShortRangeContact {
 public:
  ShortRangeContact(const ContactParameters& prm, double micromodulus) : prm_(prm), c_(micromodulus) {}
  // Adds contact force densities to sys.particles.f; returns the number of active pairs.
  std::int64_t add_forces(System<D>& sys);
  // Upper bound of the contact stiffness row sum Σ_j V_j C_ij (for the stable step).
  double stiffness_row_sum(const System<D>& sys) const;

 private:
  ContactParameters prm_;
  double c_;
  core::CellList<D> cells_;
  std::vector<Vec<D>> y_;
};

}  // namespace pdmpm::pd
