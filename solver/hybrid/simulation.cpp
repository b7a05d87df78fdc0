#include "solver/hybrid/simulation.hpp"

#include <omp.h>

#include <algorithm>

#include "solver/core/error.hpp"
#include "solver/hybrid/conversion.hpp"
#include "solver/hybrid/plastic_state_transfer.hpp"
#include "solver/pd/damage.hpp"

namespace pdmpm::hybrid {

using core::ParticleKind;

namespace {

template <int D>
double horizon_ratio(const pd::System<D>& sys) {
  return sys.delta / sys.spacing();
}

template <int D>
double bond_reach(const pd::System<D>& sys) {
  return pd::family_ratio(sys.partial_volume, sys.delta, sys.spacing());
}

}  // namespace

template <int D>
Simulation<D>::Simulation(pd::Simulation<D>& pd, mpm::Simulation<D>& mpm, const Settings& settings)
    : pd_(pd),
      mpm_(mpm),
      settings_(settings),
      map_(pd.particles(), horizon_ratio(pd.system()), bond_reach(pd.system()), settings.radii),
      removed_(static_cast<std::size_t>(pd.particles().n_real), 0) {
  settings_.validate();
  if (&mpm.particles() != &pd.particles())
    throw RunError("hybrid: the PD body and the MPM simulation must share one particle store");
  if (pd.particles().n_ghost() > 0)
    throw RunError("hybrid: symmetry planes are not supported (PD regions are not mirrored)");
  const bool blended = settings_.coupling == Coupling::blended;
  if (blended && pd.model().name() != "lps_plastic")
    throw RunError("hybrid: coupling \"blended\" weights lps_plastic's force states; the PD model is " +
                   pd.model().name());
  pd.system().transition_full_state = settings_.coupling == Coupling::full_state || blended;
  pd.system().transition_pairs_active = blended;
  if (blended) band_ = {.reach = bond_reach(pd.system()), .ramp = settings_.blend_width * horizon_ratio(pd.system())};
  transition_ball_ = blended ? core::Stencil<D>::build(band_.zone()) : map_.bonds();
}

template <int D>
void Simulation<D>::classify_band() {
  if (settings_.coupling != Coupling::blended) return;
  auto& p = pd_.particles();
  classify_blended<D>(map_, band_, p.kind, removed_, blend_beta_);
  pd_.system().blend_weight = blend_beta_;
  std::vector<double> grid_weight(blend_beta_.size());
  for (std::size_t i = 0; i < grid_weight.size(); ++i) grid_weight[i] = 1.0 - blend_beta_[i];
  mpm_.set_stress_weight(grid_weight);
}

template <int D>
void Simulation<D>::start(std::span<const Index> initial_pd) {
  auto& p = pd_.particles();
  auto& sys = pd_.system();
  const Index n = p.n_real;
  if (settings_.mode == Mode::pd) {
    std::fill(p.kind.begin(), p.kind.end(), ParticleKind::pd);
  } else {
    std::fill(p.kind.begin(), p.kind.end(), ParticleKind::mpm);
    std::vector<Index> cut;
    if (settings_.precrack_starts_pd)
      for (Index i = 0; i < n; ++i)
        for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b)
          if (sys.bonds.flags.committed[b] & pd::kBondCut) {
            cut.push_back(i);
            break;
          }
    for (const Index i : initial_pd) {
      if (i < 0 || i >= n) throw RunError("hybrid: an initial PD particle is not a real particle");
      p.kind[i] = ParticleKind::pd;
    }
    seed<D>(map_, cut, p.kind, removed_);
    classify_band();
  }
  pd_.refresh_kinds();
  mpm_.refresh_active();
  pd_.boundaries().apply_displacement(p, 0.0, 0.0);
  p.update_ghosts();
  evaluate_forces(0.0, true);
  pd_.accept();
}

template <int D>
void Simulation<D>::step(double dt, bool energy) {
  if (!(dt > 0.0)) throw RunError("hybrid: the time step must be positive");
  if (dt != dt_) base_time_ = time_, base_steps_ = steps_, dt_ = dt;
  auto& p = pd_.particles();
  const auto& bcs = pd_.boundaries();
  const double t = time_;
  double clock = omp_get_wtime();
  auto lap = [&clock](double& phase) {
    const double now = omp_get_wtime();
    phase += now - clock;
    clock = now;
  };

  pd_.kick(0.5 * dt);
  bcs.apply_velocity(p, t + 0.5 * dt);
  pd_.drift(dt);
  lap(seconds_.pd);
  pd_particle_steps_ += static_cast<std::int64_t>(pd_.movers().size());
  mpm_particle_steps_ += static_cast<std::int64_t>(mpm_.active().size());
  mpm_.step(dt);
  lap(seconds_.mpm);
  ++steps_;
  // The time as time::VelocityVerlet has it (Δt × steps for a fixed Δt), so mode pd is bitwise the PD run.
  time_ = base_time_ + dt * static_cast<double>(steps_ - base_steps_);
  const double t1 = time_;
  bcs.apply_displacement(p, t1, dt);
  p.update_ghosts();
  lap(seconds_.pd);  // the boundary conditions and ghosts are the PD body's, not region management

  const std::int64_t converted = events_.to_pd + events_.to_mpm;
  last_conversion_jump_ = 0.0;
  manage_regions();
  lap(seconds_.regions);
  const bool audit = settings_.audit_conversions && events_.to_pd + events_.to_mpm != converted;
  evaluate_forces(t1, energy || audit);
  if (audit) {
    const double after = internal_energy();
    if (after > 0.0)
      largest_jump_with_breaks_ =
          std::max(largest_jump_with_breaks_, std::abs(after - energy_before_conversion_) / after);
  }
  clock = omp_get_wtime();
  pd_.kick(0.5 * dt);
  bcs.apply_velocity(p, t1);
  pd_.accept();
  lap(seconds_.pd);
}

// PD forces on PD and transition particles at time t; each transition particle's
// PD force density becomes its external force density for the next grid step. With
// no PD particle nothing is evaluated and no particle carries a coupling force.
template <int D>
void Simulation<D>::evaluate_forces(double t, bool energy) {
  auto& p = pd_.particles();
  const double t0 = omp_get_wtime();
  if (pd_.movers().empty()) {
    for (const Index i : coupled_) p.b[i].setZero();
    coupled_.clear();
    last_breaks_.clear();
    return;
  }
  pd_.forces(t, energy);
  const double t1 = omp_get_wtime();
  seconds_.pd += t1 - t0;
  last_breaks_ = bonds_broken_by_last_evaluation();
  // pd::Simulation wrote body forces and tractions into b of every particle: the
  // grid applies its own to MPM particles, so they keep only the coupling force.
  coupled_.clear();
  for (Index i = 0; i < p.n_real; ++i) {
    if (p.kind[i] == ParticleKind::pd) continue;
    if (p.kind[i] == ParticleKind::transition) {
      p.b[i] = p.f[i];
      coupled_.push_back(i);
    } else {
      p.b[i].setZero();
    }
  }
  seconds_.coupling += omp_get_wtime() - t1;
}

template <int D>
std::vector<Index> Simulation<D>::bonds_broken_by_last_evaluation() const {
  const auto& sys = pd_.system();
  std::vector<Index> owners;
  if (sys.bonds.pending_breaks == 0) return owners;
  auto visit = [&](Index i) {
    for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b)
      if (sys.bonds.broken(b) && !(sys.bonds.flags.committed[b] & pd::kBondBroken)) {
        owners.push_back(i);
        return;
      }
  };
  if (sys.owners.empty())
    for (Index i = 0; i < sys.n_real(); ++i) visit(i);
  else
    for (const Index i : sys.owners) visit(i);
  return owners;
}

template <int D>
void Simulation<D>::manage_regions() {
  if (settings_.mode == Mode::pd) return;
  auto& kind = pd_.particles().kind;
  std::vector<Index> failed;
  for (const Index i : mpm_.newly_failed())
    if (!removed_[i]) failed.push_back(i);
  const bool may_shrink = settings_.mode == Mode::expand_shrink;
  if (failed.empty() && last_breaks_.empty()) return;
  const std::vector<ParticleKind> before = kind;
  const std::int64_t converted = events_.to_pd + events_.to_mpm;
  double before_alone = 0.0;
  if (settings_.audit_conversions) {
    energy_before_conversion_ = probed_strain_energy(true);
    before_alone = probed_strain_energy(false);
  }

  if (!failed.empty()) {
    onset<D>(map_, failed, kind, removed_);
    events_.onsets += static_cast<std::int64_t>(failed.size());
  }
  if (!last_breaks_.empty() && !expand<D>(map_, last_breaks_, kind, removed_).empty()) {
    ++events_.expansions;
    ++expansions_since_shrink_;
  }
  if (may_shrink && expansions_since_shrink_ >= settings_.shrink_every) {
    expansions_since_shrink_ = 0;
    // Tips are searched on the grown region (damage is the bonds' alone, whatever the
    // kinds), and only then is anything converted: a particle the expansion took in and
    // the shrink gives back keeps its grid state instead of a round trip through PD.
    track_tips();
    // Without a tip (the tracker found none) nothing is reverted: the paper's rule would
    // revert the whole region, crack included.
    if (!tips_.empty()) {
      std::vector<Vec<D>> at;
      for (const auto& tip : tips_) at.push_back(tip.position);
      if (!shrink<D>(map_, at, particles_that_stay_pd(before), kind, removed_).empty()) ++events_.shrinks;
    }
  }
  classify_band();
  convert(before);
  if (settings_.audit_conversions && events_.to_pd + events_.to_mpm != converted) {
    const double after = probed_strain_energy(false), jump = after - before_alone;
    conversion_energy_ += jump;
    last_conversion_jump_ = after > 0.0 ? std::abs(jump) / after : 0.0;
    largest_conversion_jump_ = std::max(largest_conversion_jump_, last_conversion_jump_);
  }
}

template <int D>
double Simulation<D>::probed_strain_energy(bool allow_breaks) {
  return (pd_.movers().empty() ? 0.0 : pd_.probe_internal_energy(allow_breaks)) + mpm_.energies().strain;
}

// Converts every particle whose kind differs from `before` (conversion.hpp), then
// refreshes the bonds, the PD movers and the grid's particle list.
template <int D>
void Simulation<D>::convert(const std::vector<ParticleKind>& before) {
  auto& p = pd_.particles();
  auto& sys = pd_.system();
  std::vector<Index> changed, into_pd;
  for (Index i = 0; i < p.n_real; ++i) {
    const ParticleKind was = before[i], now = p.kind[i];
    if (was == now) continue;
    changed.push_back(i);
    if (now == ParticleKind::removed) continue;
    if (now == ParticleKind::pd) {
      to_pd<D>(mpm_, sys, pd_.model(), i);
      into_pd.push_back(i);
      ++events_.to_pd;
    } else if (was == ParticleKind::pd) {
      to_mpm<D>(sys, pd_.model(), mpm_, i, settings_.plastic_transfer);
      ++events_.to_mpm;
    } else if (now == ParticleKind::transition && sys.transition_full_state) {
      to_pd<D>(mpm_, sys, pd_.model(), i);  // its whole-family PD state starts from the grid's plastic state
      into_pd.push_back(i);
    }
  }
  if (changed.empty()) return;
  pd_.refresh_kinds(changed);
  // The elastic-state transfer reads the particle's state bonds, so after the refresh.
  if (settings_.plastic_transfer == PlasticTransfer::elastic_state)
    for (const Index i : into_pd) to_pd_elastic_state<D>(mpm_, sys, pd_.model(), i);
  mpm_.refresh_active();
}

// The PD particles a shrink must not revert. Every damaged one — no healing: both faces
// of a crack keep their broken bonds and never meet on one grid. Every one a boundary
// condition holds: PD holds particles, the grid nodes, so a held particle that reverted
// would move its grip's edge (docs/models/hybrid.md, the edge crack's grips). With revert_residual < 1
// also every one that was PD when the step began whose elastic state one F would carry too
// poorly (a conversion would lose its non-affine part). The expansion's new PD particles
// are not converted yet: reverting them costs nothing.
template <int D>
std::vector<std::uint8_t> Simulation<D>::particles_that_stay_pd(const std::vector<ParticleKind>& before) const {
  const auto& sys = pd_.system();
  const auto* plastic = dynamic_cast<const pd::LpsPlastic<D>*>(&pd_.model());
  const bool bound = settings_.revert_residual < 1.0 && plastic;
  std::vector<std::uint8_t> keep(static_cast<std::size_t>(sys.n_real()), 0);
  for (Index i = 0; i < sys.n_real(); ++i) {
    if (sys.particles.kind[i] != ParticleKind::pd) continue;
    for (BondIndex b = sys.families.begin(i); b < sys.families.end(i); ++b)
      if (sys.bonds.broken(b)) {
        keep[i] = 1;
        break;
      }
    for (int a = 0; a < D && !keep[i]; ++a) keep[i] = pd_.boundaries().constrained(i, a);
    if (!keep[i] && bound && before[i] == ParticleKind::pd)
      keep[i] = non_affine_share<D>(sys, *plastic, i) > settings_.revert_residual;
  }
  return keep;
}

template <int D>
const std::vector<CrackTip<D>>& Simulation<D>::track_tips() {
  const auto& sys = pd_.system();
  const auto& p = sys.particles;
  std::vector<IVec<D>> sites;
  std::vector<double> phi;
  for (Index i = 0; i < p.n_real; ++i) {  // the PD particles by kind: those of a grown region not yet converted too
    if (p.kind[i] != ParticleKind::pd) continue;
    sites.push_back(p.site[i]);
    phi.push_back(pd::particle_damage(sys, i));
  }
  tips_ = match_crack_tips<D>(tips_, find_crack_tips<D>(p.lattice, sites, phi, settings_.tips), settings_.tips,
                              next_tip_id_);
  return tips_;
}

template <int D>
Index Simulation<D>::region_violations() const {
  const auto& p = pd_.particles();
  Index bad = 0;
  for (Index i = 0; i < p.n_real; ++i) {
    const ParticleKind k = p.kind[i];
    bad += (k == ParticleKind::removed) != (removed_[i] != 0);
    if (k == ParticleKind::pd || k == ParticleKind::removed) continue;
    bool near_pd = false;
    for (const auto& off : transition_ball_.offset) {
      const Index j = map_.find(p.site[i] + off);
      near_pd = near_pd || (j >= 0 && j < p.n_real && p.kind[j] == ParticleKind::pd);
    }
    bad += near_pd != (k == ParticleKind::transition);
  }
  return bad;
}

template <int D>
KindCounts Simulation<D>::counts() const {
  KindCounts c;
  const auto& p = pd_.particles();
  for (Index i = 0; i < p.n_real; ++i) switch (p.kind[i]) {
      case ParticleKind::pd:
        ++c.pd;
        break;
      case ParticleKind::transition:
        ++c.transition;
        break;
      case ParticleKind::mpm:
        ++c.mpm;
        break;
      case ParticleKind::removed:
        ++c.removed;
        break;
    }
  return c;
}

template <int D>
Vec<D> Simulation<D>::momentum() const {
  const auto& p = pd_.particles();
  Vec<D> owed = Vec<D>::Zero();
  for (const Index i : coupled_) owed += p.volume[i] * p.b[i];
  return pd_.momentum() + mpm_.momentum() + 0.5 * dt_ * owed;
}

template <int D>
double Simulation<D>::kinetic_energy() const {
  return pd_.kinetic_energy() + mpm_.energies().kinetic;
}

template <int D>
double Simulation<D>::transition_pd_energy() const {
  const auto& p = pd_.particles();
  if (pd_.movers().empty()) return 0.0;  // no evaluation has run
  double u = 0.0;
  for (Index i = 0; i < p.n_real; ++i)
    if (p.kind[i] == ParticleKind::transition) u += pd_.energy_density(i) * p.volume[i];
  return u;
}

template <int D>
double Simulation<D>::internal_energy() const {
  return pd_.internal_energy() + mpm_.energies().strain;
}

template <int D>
void Simulation<D>::checkpoint(core::StateArchive& a) {
  pd_.checkpoint(a);
  mpm_.checkpoint(a);
  a.sync("hybrid/removed", removed_);
  a.sync("hybrid/tips", tips_);
  a.sync("hybrid/next_tip_id", next_tip_id_);
  a.sync("hybrid/last_breaks", last_breaks_);
  a.sync("hybrid/coupled", coupled_);
  a.sync("hybrid/expansions_since_shrink", expansions_since_shrink_);
  a.sync("hybrid/dt", dt_);
  a.sync("hybrid/time", time_);
  a.sync("hybrid/base_time", base_time_);
  a.sync("hybrid/base_steps", base_steps_);
  a.sync("hybrid/steps", steps_);
  a.sync("hybrid/pd_particle_steps", pd_particle_steps_);
  a.sync("hybrid/mpm_particle_steps", mpm_particle_steps_);
  a.sync("hybrid/events", events_);
  a.sync("hybrid/phase_seconds", seconds_);
  a.sync("hybrid/energy_before_conversion", energy_before_conversion_);
  a.sync("hybrid/conversion_energy", conversion_energy_);
  a.sync("hybrid/largest_conversion_jump", largest_conversion_jump_);
  a.sync("hybrid/largest_jump_with_breaks", largest_jump_with_breaks_);
  a.sync("hybrid/last_conversion_jump", last_conversion_jump_);
  classify_band();  // the blended coupling's weights follow from the kinds restored (same kinds when saving)
}

template class Simulation<2>;
template class Simulation<3>;

}  // namespace pdmpm::hybrid
