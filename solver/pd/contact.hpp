#pragma once
// Short-range repulsion between particles that are not joined by an intact
// bond (Deryugin et al. 2023 eqs 6.2–6.4; with `bonded_pairs`, between all pairs, as in
// LAMMPS' peri/pmb): for |y| < d_ij,
//   f = (c_s/δ)(|y| − d_ij) y/|y| V_j,  c_s = 15 c,  d_ij = min(0.9|ξ|, 1.35Δx).
// A separate loop, run only when a scene enables contact, over a Verlet list:
// the pairs closer than reach + skin, rebuilt from a cell list of the deformed
// positions once any particle has moved more than skin/2 since the last build
// (until then no pair outside the list can come within reach). In a distributed run
// the list also holds other processes' particles near this one's (ContactGhosts), and
// every process lists, orders and sums a particle's partners as one process does: cells
// over the whole body's box, a cell's particles in the global order.
#include "solver/core/cell_list.hpp"
#include "solver/pd/contact_ghosts.hpp"
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
  // Adds contact force densities to sys.particles.f; returns the number of active pairs
  // (of every process).
  std::int64_t add_forces(System<D>& sys);
  // Upper bound of the contact stiffness row sum Σ_j V_j C_ij (for the stable step; the
  // largest volume of every process).
  double stiffness_row_sum(const System<D>& sys) const;
  // Distributed: the most active pairs at one evaluation that joined particles of two
  // processes (every process's; what shows the run tests contact across them).
  std::int64_t most_pairs_across_processes() const { return most_across_; }
  // The Verlet list and the positions it was built at: the pairs and their order.
  void checkpoint(core::StateArchive& a);

 private:
  ContactParameters prm_;
  double c_;
  bool list_is_stale(Index local, double skin) const;
  void build_list(const core::Particles<D>& p, Index local, double radius);
  Index global_of_entry(const core::Particles<D>& p, Index k) const;

  core::CellList<D> cells_;
  // The list's particles: real and symmetry ghosts (one process) or own (distributed),
  // then other processes' (ghosts_): positions now and at the last build, reference
  // positions and volumes (as at the last build).
  std::vector<Vec<D>> y_, y_at_build_, x0_;
  std::vector<double> volume_;
  ContactGhosts<D> ghosts_;
  Index real_ = 0;
  std::int64_t most_across_ = 0;
  std::vector<std::int64_t> start_;  // CSR of candidate partners per real particle
  std::vector<Index> partner_;
};

}  // namespace pdmpm::pd
