#pragma once
// Short-range repulsion between particles that are not joined by an intact
// bond (Deryugin et al. 2023 eqs 6.2–6.4; with `bonded_pairs`, between all pairs, as in
// LAMMPS' peri/pmb): for |y| < d_ij,
//   f = (c_s/δ)(|y| − d_ij) y/|y| V_j,  c_s = 15 c,  d_ij = min(0.9|ξ|, 1.35Δx).
// A separate loop, run only when a scene enables contact, over a Verlet list:
// the pairs closer than reach + skin, rebuilt from a cell list of the deformed
// positions once any particle has moved more than skin/2 since the last build
// (until then no pair outside the list can come within reach).
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
  // The Verlet list and the positions it was built at: the pairs and their order.
  void checkpoint(core::StateArchive& a);

 private:
  ContactParameters prm_;
  double c_;
  bool list_is_stale(double skin) const;
  void build_list(double radius);

  core::CellList<D> cells_;
  std::vector<Vec<D>> y_, y_at_build_;  // positions of real and ghost particles: now, at the last build
  Index real_ = 0;
  std::vector<std::int64_t> start_;  // CSR of candidate partners per real particle
  std::vector<Index> partner_;
};

}  // namespace pdmpm::pd
