#pragma once
// The adaptive SBPD–MPM hybrid (Noorian et al., adaptive SBPD–MPM, §2): one body,
// one particle store, one Δt. MPM carries the body; state-based PD carries it where
// it cracks. Each particle is
//   pd          integrated by PD (velocity Verlet, pd::Simulation's movers);
//   transition  a non-PD particle within bond reach of a PD one: integrated by the
//               grid, and a virtual PD particle whose bonds to PD particles act —
//               their pair forces enter the grid as particle external forces (the
//               paper's eq 10) and their reactions act on the PD particles (with
//               coupling = blended: every non-PD particle of the band around a region,
//               blend_zone.hpp, its bonds to other transition particles acting too);
//   mpm         integrated by the grid only;
//   removed     failed in MPM (ductile criterion) and taken out of the body.
//
// One step, tⁿ → tⁿ⁺¹ (reads like velocity Verlet with the grid inside it):
//   PD     half kick with fⁿ, velocity BCs, drift
//   MPM    one grid step; transition particles carry the PD force of tⁿ as external force
//   PD     displacement BCs at tⁿ⁺¹
//   regions  onset at the particles MPM found failed this step (eq 8–9 → R_pd),
//            expansion (eq 11) at PD particles with a bond broken by the last
//            evaluation, shrink (eq 12) after every i_crit expansions around the
//            crack tips (eqs 13–15); states converted both ways (conversion.hpp)
//   PD     forces at tⁿ⁺¹ on PD and transition particles, coupling into the grid's
//          external force, half kick, velocity BCs, commit the bond state.
// Every pair force of an evaluation gives both its ends the impulse Δt (half kicks
// on the PD side, the next grid step on the transition side), so with no external
// load  P + ½Δt Σ_transition V f  is conserved to round-off (momentum()).
// Particles converted during a step take part in the evaluation that ends it, so
// they start the next step with the forces of their new method (the paper: converted
// at step m, PD from step m + 1). Conversions need no acceleration (the paper carries
// it): the evaluation gives the new PD particles theirs.
//
// Limits, by construction: with no PD particle the PD side does nothing and the MPM
// step is the pure MPM step; with mode pd and no MPM particle the sequence is exactly
// time::VelocityVerlet's.
#include <cstdint>
#include <span>
#include <vector>

#include "solver/hybrid/crack_tips.hpp"
#include "solver/hybrid/blend_zone.hpp"
#include "solver/hybrid/regions.hpp"
#include "solver/hybrid/settings.hpp"
#include "solver/mpm/simulation.hpp"
#include "solver/pd/simulation.hpp"

namespace pdmpm::hybrid {

struct KindCounts {
  Index pd = 0, transition = 0, mpm = 0, removed = 0;
};

// Region events since the start.
struct Events {
  std::int64_t onsets = 0;      // particles removed at ductile failure (each forms a region)
  std::int64_t expansions = 0;  // steps in which eq 11 converted particles
  std::int64_t shrinks = 0;     // steps in which eq 12 converted particles back
  std::int64_t to_pd = 0;       // particles converted MPM → PD
  std::int64_t to_mpm = 0;      // particles converted PD → MPM
};

// Wall time of the parts of a step (seconds, accumulated).
struct PhaseSeconds {
  double pd = 0.0;        // PD bond forces, kicks and drifts
  double mpm = 0.0;       // the grid step (its own phases: mpm::Simulation::phase_seconds)
  double coupling = 0.0;  // PD forces of transition particles into the grid's external force
  double regions = 0.0;   // onset, expansion, tips, shrink, conversions, bond refresh
  double total() const { return pd + mpm + coupling + regions; }
};

template <int D>
class Simulation {
 public:
  // Borrows a PD body and an MPM simulation built on the same particle store
  // (pd.particles() is mpm's store). Throws InputError for invalid settings and
  // RunError for a PD body with symmetry ghosts (regions are not mirrored).
  Simulation(pd::Simulation<D>& pd, mpm::Simulation<D>& mpm, const Settings& settings);

  // Kinds at t = 0 (mode pd: every particle PD; otherwise MPM, with a PD region
  // around pre-cracks, and the particles `initial_pd` PD), boundary conditions at
  // t = 0 and the first PD forces.
  void start(std::span<const Index> initial_pd = {});
  // Its state for a checkpoint (core/state_archive.hpp): the borrowed PD and MPM
  // simulations', removed particles, tips, step bookkeeping, counters; not the
  // particle store. A resumed run calls start() and then restores over it.
  void checkpoint(core::StateArchive& a);
  // One step of size dt (the caller's: the smaller of the PD and MPM stable steps).
  void step(double dt, bool energy = false);

  double time() const { return time_; }
  std::int64_t steps() const { return steps_; }
  const Settings& settings() const { return settings_; }
  pd::Simulation<D>& pd() { return pd_; }
  const pd::Simulation<D>& pd() const { return pd_; }
  mpm::Simulation<D>& mpm() { return mpm_; }
  const mpm::Simulation<D>& mpm() const { return mpm_; }
  const core::Particles<D>& particles() const { return pd_.particles(); }

  KindCounts counts() const;
  const Events& events() const { return events_; }
  const PhaseSeconds& phase_seconds() const { return seconds_; }
  // Crack tips of the last tip search (at each shrink, or track_tips()).
  const std::vector<CrackTip<D>>& tips() const { return tips_; }
  // Finds the crack tips of the current PD region now (outputs; shrink calls it).
  const std::vector<CrackTip<D>>& track_tips();
  std::int64_t pd_particle_steps() const { return pd_particle_steps_; }
  std::int64_t mpm_particle_steps() const { return mpm_particle_steps_; }
  // Particles whose kind breaks the region rules: a non-PD particle within bond reach
  // of a PD one that is not transition, a transition particle with no PD particle in
  // reach, a kind `removed` without the removed mark or the other way round. Zero
  // after every step (tests; costs a pass over the bonds of the body).
  Index region_violations() const;
  // Per real particle: 1 once removed at ductile failure.
  const std::vector<std::uint8_t>& removed() const { return removed_; }

  // Momentum of the body: PD movers, grid particles, and the impulse the pending
  // coupling forces still owe the transition particles (½Δt of the last evaluation).
  Vec<D> momentum() const;
  double kinetic_energy() const;   // PD movers + MPM particles
  double internal_energy() const;  // PD strain energy of the movers (last evaluation with energy) + MPM stored energy
  // PD strain energy of the transition particles (last evaluation with energy). The pair
  // forces derive from the PD energy of PD and transition particles together (paper
  // coupling), so kinetic + internal + this is the energy the coupled step would conserve;
  // the body's strain energy counts the transition particles once, in internal_energy().
  double transition_pd_energy() const;
  // Energy added by conversions since the start (J; with settings.audit_conversions,
  // else 0): at each converting step the strain energy of the body at tⁿ⁺¹ after the
  // conversions minus before them, with the bonds as they are (both evaluations break
  // none; kinetic energy does not change: v is carried).
  double conversion_energy() const { return conversion_energy_; }
  // The jump of the last step's conversions relative to the body's strain energy after
  // them (0 if it converted nothing), and the largest so far.
  double last_conversion_jump() const { return last_conversion_jump_; }
  double largest_conversion_jump() const { return largest_conversion_jump_; }
  // The same with the bonds the step's evaluation breaks: a particle turned PD can bring
  // bonds stretched past the critical stretch, which break at once.
  double largest_jump_with_breaks() const { return largest_jump_with_breaks_; }

 private:
  void manage_regions();
  void convert(const std::vector<core::ParticleKind>& before);
  void evaluate_forces(double t, bool energy);
  std::vector<Index> bonds_broken_by_last_evaluation() const;
  // The body's strain energy now, probing PD without committing (conversion audit).
  double probed_strain_energy(bool allow_breaks);
  std::vector<std::uint8_t> particles_that_stay_pd(const std::vector<core::ParticleKind>& before) const;
  // coupling = blended: widen the transition set to the band's zone and pass the
  // weights to both methods (blend_zone.hpp); nothing otherwise.
  void classify_band();

  pd::Simulation<D>& pd_;
  mpm::Simulation<D>& mpm_;
  Settings settings_;
  RegionMap<D> map_;
  std::vector<std::uint8_t> removed_;
  BlendBand band_;                    // coupling = blended
  core::Stencil<D> transition_ball_;  // offsets within which a non-PD particle is transition
  std::vector<double> blend_beta_;    // β per particle (blended)
  std::vector<CrackTip<D>> tips_;
  int next_tip_id_ = 0;
  std::vector<Index> last_breaks_;  // particles with a bond broken by the last evaluation
  std::vector<Index> coupled_;      // transition particles carrying a coupling force in b
  int expansions_since_shrink_ = 0;
  double dt_ = 0.0, time_ = 0.0, base_time_ = 0.0;
  std::int64_t base_steps_ = 0, steps_ = 0, pd_particle_steps_ = 0, mpm_particle_steps_ = 0;
  Events events_;
  PhaseSeconds seconds_;
  double energy_before_conversion_ = 0.0;  // audit: strain energy before this step's conversions, breaks allowed
  double conversion_energy_ = 0.0, last_conversion_jump_ = 0.0, largest_conversion_jump_ = 0.0,
         largest_jump_with_breaks_ = 0.0;
};

}  // namespace pdmpm::hybrid
