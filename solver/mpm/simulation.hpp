#pragma once
// Explicit material point method on a fixed background grid (Sulsky, Chen &
// Schreyer 1994; Sulsky, Zhou & Schreyer 1995), with USF / USL / MUSL orderings,
// linear / uGIMP / quadratic B-spline interpolation, and the constitutive models
// of constitutive.hpp.
//
// The simulation works on a core::Particles store it does not own: it integrates
// the particles whose kind is mpm or transition (real particles only), reads their
// external force density `b` (N/m³ of reference volume: the hybrid puts PD forces
// there) and writes their displacement u and velocity v. Everything else MPM needs
// lives in ParticleState, indexed like the store.
//
// One step (dt), with S_Ip and ∇S_Ip evaluated at the particle positions xⁿ:
//   P2G   m_I = Σ S m_p,  p_I = Σ S m_p v_p,  f_I = −Σ V₀ τ_p ∇S + Σ S f_ext,p
//   USF   vⁿ_I = p/m → BC → stress update from Lₚ = Σ vⁿ_I ⊗ ∇S → forces with the new stress
//   grid  vⁿ⁺¹_I = vⁿ_I + dt f_I/m_I → BC
//   G2P   v_p ← flip·(v_p + dt Σ S aᵢ) + (1 − flip)·Σ S vⁿ⁺¹_I,  x_p ← x_p + dt Σ S vⁿ⁺¹_I
//   USL   stress update from Σ vⁿ⁺¹_I ⊗ ∇S
//   MUSL  p_I = Σ S m_p v_p (new) → v_I = p/m → BC → stress update from Σ v_I ⊗ ∇S
// F is updated by the Cayley increment (kinematics.hpp), so a rigid rotation of
// the grid velocity field rotates each particle exactly.
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "solver/core/particles.hpp"
#include "solver/mpm/constitutive.hpp"
#include "solver/mpm/grid.hpp"
#include "solver/mpm/grid_boundary.hpp"
#include "solver/mpm/other_processes.hpp"
#include "solver/mpm/particle_state.hpp"
#include "solver/mpm/scatter_schedule.hpp"
#include "solver/mpm/settings.hpp"

namespace pdmpm::mpm {

struct Energies {
  double kinetic = 0.0;        // Σ ½ m |v|²
  double strain = 0.0;         // Σ V₀ W (stored elastic energy)
  double dissipated = 0.0;     // Σ V₀ ∫ τ : dε_p (plastic work)
  double external_work = 0.0;  // work of body forces, tractions and particle external forces
  double boundary_work = 0.0;  // work of the grid boundary reactions
  double damping_work = 0.0;   // work of the grid damping forces (≤ 0)
  // Conserved in the continuum: kinetic + strain + dissipated − external − boundary − damping.
  double balance() const { return kinetic + strain + dissipated - external_work - boundary_work - damping_work; }
};

// Wall time of the phases of an MPM step (seconds), accumulated over steps.
struct StepPhaseSeconds {
  double prepare = 0.0;  // stencils and scatter schedule, external forces, nonlocal hardening
  double p2g = 0.0;      // scatter to the grid, vⁿ and its constraints (MUSL: the remapped v's too)
  double grid = 0.0;     // grid momentum update, constraints at tⁿ⁺¹, work booking
  double g2p = 0.0;      // particle velocities and positions (MUSL: with the remap's scatter)
  double stress = 0.0;   // velocity gradient, F, constitutive update, failure
  double total() const { return prepare + p2g + grid + g2p + stress; }
};

template <int D>
class Simulation {
 public:
  // Validates the settings (InputError with `file` and `prefix` in the key path),
  // builds the grid around the particles and initialises the MPM state of every
  // real particle (whatever its kind, so a later switch to MPM finds it ready).
  // Distributed (`others`): `particles` holds this process's own points, the real ones,
  // in global order; the grid is the whole body's, and every sum, maximum and output
  // is the whole body's, as one process computes it (solver/mpm/other_processes.hpp).
  Simulation(Settings<D> settings, core::Particles<D>& particles, const std::string& file = "",
             const std::string& prefix = "mpm", std::shared_ptr<OtherProcesses> others = nullptr);

  // h / max_p (c_p + |v_p|): the CFL = 1 step of the grid wave speed.
  double stable_dt() const;
  // One step of settings.dt if set, else cfl × stable_dt(). Returns the step used.
  double step();
  // One step of the given size.
  void step(double dt);

  double time() const { return time_; }
  std::int64_t step_count() const { return steps_; }
  const Settings<D>& settings() const { return settings_; }
  const Grid<D>& grid() const { return grid_; }
  const GridBoundary<D>& boundary() const { return boundary_; }
  double cell_size() const { return grid_.h; }
  const ParticleState<D>& state() const { return state_; }
  const core::Particles<D>& particles() const { return particles_; }

  // Indices of the particles the MPM step integrates (kind mpm/transition, real).
  const std::vector<Index>& active() const { return active_; }
  Energies energies() const;
  // Work the velocity constraints have done but the balance has not booked yet. The
  // balance books a step's boundary work with the reaction of the stress at its start
  // (explicit), while the stored energy already holds the step's deformation; the
  // trapezoid rule would add ½ Δt R(tⁿ⁺¹)·V(tⁿ⁺¹). This returns that half step, from
  // the internal forces of the current stress on the constrained nodes. Costs a
  // particle pass: for the stability check when the booked work looks too small
  // (a grip at full speed from t = 0 has done no booked work after its first step).
  double pending_boundary_work(double dt);
  Vec<D> momentum() const;
  double total_mass() const;
  // The particles' kinetic energy as the grid sees it after the last step: Σ ½|p_I|²/m_I
  // of MUSL's remapped nodal momenta (≤ energies().kinetic by Cauchy–Schwarz). The rest is
  // kinetic energy in velocity modes the particle-to-grid map cannot see (its null space):
  // FLIP keeps such modes and the grid does not restrain them. For the particles the last
  // step integrated (a hybrid's conversions change them: not for hybrid runs); nullopt
  // before the first step (and after a restart) and for USF/USL, whose nodal momenta after a
  // step are not the current velocities'.
  std::optional<double> grid_kinetic_energy() const;
  // Force each boundary exerted on the body during the last step (N; volumes carry
  // thickness / cross-section), in the order of settings.boundaries.
  const std::vector<Vec<D>>& reactions() const { return reactions_; }

  // Distributed: other processes' points this process held as ghosts in the last step.
  Index ghost_points() const { return ghosts_seen_; }
  // Wall time spent in each phase of step() since construction (seconds, this process).
  const StepPhaseSeconds& phase_seconds() const { return phase_seconds_; }

  // Per-particle outputs.
  double von_mises(Index p) const;
  double triaxiality(Index p) const;
  double eq_plastic_strain(Index p) const { return state_.eq_plastic_strain[p]; }
  bool failed(Index p) const { return state_.failed[p] != 0; }
  // Particles that failed during the last step, ascending.
  const std::vector<Index>& newly_failed() const { return newly_failed_; }

  // Set a particle's deformation gradient and recompute its stress (initial
  // states, tests). Plastic history is left as it is.
  void set_deformation_gradient(Index p, const Mat<D>& F);
  // Set a particle's plastic history, then its deformation gradient (a particle the
  // hybrid hands back from PD; solver/hybrid/conversion.hpp).
  void set_state(Index p, const Mat<D>& F, const PointHistory& history);
  // Call after particles were added or changed kind outside the simulation:
  // sizes the MPM state and initialises new slots.
  void sync_particles();
  // Re-reads which particles the step integrates (kinds mpm/transition); step() does
  // it itself, so only needed for momentum()/energies() right after kinds changed.
  void refresh_active();
  // Weights of the particles' stress in the grid's internal force and strain energy, one
  // per particle (a hybrid's blended coupling: 1 − β, hybrid/blend_zone.hpp); empty: 1.
  void set_stress_weight(const std::vector<double>& weight);

  // Its state for a checkpoint (core/state_archive.hpp): the material points' state,
  // time, step count, work books, this step's failures and reactions; not the
  // particle store, which it borrows.
  void checkpoint(core::StateArchive& a);

 private:
  void prepare_step(double t);
  void update_grid(double t, double dt);
  void grid_to_particles(double t, double dt, bool remap);
  void initialise_particle(Index p);
  // Cells of `points` → `schedule` → their stencils in its order (see ScatterSet); without
  // `with_stencils` the cells and schedule only.
  struct ScatterSet;
  void compute_stencils(const std::vector<Index>& points, ScatterSet& set, bool with_stencils = true);
  struct Scatter {
    bool mass = false, momentum = false, forces = false;
  };
  void scatter(Scatter what);
  // Distributed: the other processes' points that reach this process's nodes, as ghosts
  // after the real particles (store and state), with the scatter over own points and
  // ghosts; refresh_ghosts sends their velocity (MUSL's remap) or stress (USF) again;
  // drop_ghosts ends the step with the real particles alone.
  void receive_ghosts();
  void build_shared_scatter();
  enum class GhostField { velocity, stress };
  void refresh_ghosts(GhostField field);
  void drop_ghosts();
  void set_ghost_count(Index n);
  // Σ term(k) over the active points k, in deterministic_sum's chunks; distributed, over
  // every process's points in their global order (the one-process sum, to the bit).
  template <int N, class Fn>
  Eigen::Matrix<double, N, 1> sum_over_points(Fn&& term) const;
  // Σ term(i) over the grid nodes in deterministic_sum's chunks; distributed, each node's
  // term from the process that books it (owned_node_), gathered in node order.
  template <int N, class Fn>
  Eigen::Matrix<double, N, 1> sum_over_nodes(Fn&& term) const;
  // Distributed: own points and ghosts, merged in global order.
  std::vector<Index> own_and_ghosts() const;

  // Distributed: the boundaries' node terms of every process's owned nodes, in one
  // process's order, summed per boundary into `out` (reactions) or, with `power`, as
  // −Σ over their components.
  void sum_node_terms(const std::vector<typename GridBoundary<D>::NodeTerm>& terms, std::vector<Vec<D>>* out,
                      double* power) const;
  void clear_grid(Scatter what);  // zero what a scatter sums
  void fold_grid(Scatter what);   // fold it across symmetry planes afterwards
  void grid_velocity_from_momentum(std::vector<Vec<D>>& v) const;
  void update_stress(const std::vector<Vec<D>>& grid_velocity, double dt);
  void update_stress_in_lanes(const std::vector<Vec<D>>& grid_velocity, double dt, const PlaneStressLaw& law,
                              Index& bad);
  void store_lanes(Index p0, Index n, const PlaneStressLanes& lanes, const double* eps_f);
  void advance_deformation(Index k, const std::vector<Vec<D>>& grid_velocity, double dt);
  Mat<D> velocity_gradient(Index k, const std::vector<Vec<D>>& grid_velocity) const;
  void stretch_domain(Index p);
  bool apply_law(Index p, const PolarLog<D>* polar);
  void store_law_result(Index p, const StressResult& r, double alpha_before, double offset);
  void apply_ductile_criterion(Index p, double alpha_before, double offset, double eps_f);
  void update_nonlocal();
  // ε̂_p − ε̄_p of particle p with ε̄_p = eq_plastic: the non-local correction of the
  // hardening variable, zero for a local model (its ε̂_p is not kept up to date).
  double hardening_offset(Index p, double eq_plastic) const {
    return settings_.nonlocal.enabled ? state_.eq_plastic_hardening[p] - eq_plastic : 0.0;
  }
  Vec<D> external_force(Index p, double t) const;
  // The stencils of `set.schedule`'s points in its order; bad = the lowest particle
  // whose stencil leaves the grid (whose F has inverted), left as it is if none.
  void compute_gimp_stencils(ScatterSet& set, Index& bad);
  void compute_other_stencils(ScatterSet& set, Index& bad);
  void polar_decompositions(Index& bad);
  bool inside_grid(const Stencil<D>& st) const;  // every node of the stencil is a grid node

  Settings<D> settings_;
  core::Particles<D>& particles_;
  Constitutive<D> constitutive_;
  Grid<D> grid_;
  GridBoundary<D> boundary_;
  ParticleState<D> state_;
  std::vector<Index> active_;
  bool remap_current_ = false;  // the grid's momenta are MUSL's remap of the last step
  // Points, their scatter schedule and their stencils (in schedule order) for a step.
  struct ScatterSet {
    ScatterSchedule<D> schedule;
    std::vector<Stencil<D>> stencil;  // per point this step, in schedule.order()
    std::vector<IVec<D>> cell;        // per point this step: its cell (scratch of compute_stencils)
  };
  ScatterSet own_;  // the active particles: G2P and the stress update go through it
  // Distributed: own points and ghosts in global order (the scatter goes through them, so
  // every node sums its points in one process's order), each ghost's global index, and
  // per node whether this process books it in the grid's sums (receive_ghosts).
  std::shared_ptr<OtherProcesses> others_;
  ScatterSet shared_;
  std::vector<Index> ghost_global_;
  std::vector<std::uint8_t> owned_node_;
  Index ghosts_seen_ = 0;
  const ScatterSet& scatter_set() const { return others_ ? shared_ : own_; }
  std::vector<PolarLog<D>> polar_;                 // per active particle this step (log-strain laws), same order
  bool rows() const { return D == 2 && K_ == 3; }  // the 2D stencil-row passes (scatter_rows, g2p_rows)
  std::vector<Vec<D>> ext_force_;                  // per particle external force this step (N)
  std::vector<double> stress_volume_;              // V weighted by set_stress_weight (empty: none set)
  const std::vector<double>& stress_volume() const {
    return stress_volume_.empty() ? particles_.volume : stress_volume_;
  }
  bool any_external_force_ = false;  // some active particle has one this step
  std::vector<std::vector<Index>> traction_particles_;
  std::vector<Vec<D>> reactions_;
  std::vector<Index> newly_failed_;
  std::vector<Vec<D>> damping_, velocity_free_;  // per node this step: damping force, v before constraints
  StepPhaseSeconds phase_seconds_;
  std::vector<std::uint8_t> failed_this_step_;
  int K_ = 3;  // nodes per axis of the shape function
  double time_ = 0.0;
  std::int64_t steps_ = 0;
  double external_work_ = 0.0, boundary_work_ = 0.0, damping_work_ = 0.0;
};

}  // namespace pdmpm::mpm
