#include "solver/sim/hybrid_run.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "solver/core/error.hpp"
#include "solver/hybrid/j_samples.hpp"
#include "solver/pd/damage.hpp"
#include "solver/sim/frame_fields.hpp"
#include "solver/sim/output_schedule.hpp"
#include "solver/sim/run_metrics.hpp"
#include "solver/sim/run_recorder.hpp"
#include "solver/time/stable_step.hpp"

namespace pdmpm::sim {
namespace {

template <int D>
class HybridRun {
 public:
  HybridRun(const io::Scene& scene, HybridSetup<D>& setup, const RunOptions& options)
      : scene_(scene), s_(setup), h_(*setup.hybrid_simulation), p_(setup.pd.system.particles), rec_(scene, options) {}

  RunResult run();

 private:
  void pd_stable_step();
  void choose_time_step();
  void start_outputs();
  void step(bool energy);
  void history_row(std::int64_t step, double t);
  void frame(std::int64_t step, double t);
  bool stable(std::int64_t step, double t);
  const std::vector<hybrid::CrackTip<D>>& tips();
  std::vector<Vec<D>> reactions() const;
  double max_speed() const;
  nlohmann::json summary() const;
  void state(core::StateArchive& a);  // what a checkpoint holds of this run

  const io::Scene& scene_;
  HybridSetup<D>& s_;
  hybrid::Simulation<D>& h_;
  core::Particles<D>& p_;
  RunRecorder rec_;

  double dt_ = 0.0, dt_pd_ = 0.0, dt_cfl0_ = 0.0, end_time_ = 0.0;
  std::int64_t total_steps_ = 0, steps_done_ = 0, energy_every_ = 1;
  // Energies of the last step with energy; E₀; the work the loads did (an upper
  // bound: |grid external + boundary work| + Σ |work on held PD components and of
  // PD external forces|), for the instability test.
  double kinetic_ = 0.0, internal_ = 0.0, initial_energy_ = 0.0, pd_work_ = 0.0;
  // The particles PD integrates in the step being taken (its movers at the start) and
  // their u and v then.
  std::vector<Index> moved_;
  std::vector<Vec<D>> u_before_, v_before_;
};

// Before start(): every bond of the body counts (any particle may become PD).
template <int D>
void HybridRun<D>::pd_stable_step() {
  auto& sys = s_.pd.system;
  dt_pd_ = scene_.time.estimate == io::StableStepEstimate::lanczos ? time::lanczos_step<D>(sys, *s_.pd.model).dt
                                                                   : time::silling_askari_step<D>(sys, *s_.pd.model);
  if (!std::isfinite(dt_pd_))
    throw InputError(scene_.file, "shape",
                     "no particle has a bond: the body falls apart at once (horizon too small or body too thin)");
}

template <int D>
void HybridRun<D>::choose_time_step() {
  // After start(): the grid's step for the particles it carries at t = 0. Mode pd
  // has none and steps as the PD run does; otherwise a grid with no particle yet
  // still gets the elastic CFL step, since particles can convert to it.
  dt_cfl0_ = h_.mpm().stable_dt();
  if (!std::isfinite(dt_cfl0_) && h_.settings().mode != hybrid::Mode::pd)
    dt_cfl0_ = h_.mpm().cell_size() / std::sqrt(scene_.material.wave_modulus(scene_.setting) / scene_.material.rho);
  const double dt = scene_.time.dt ? *scene_.time.dt : scene_.time.safety_factor * std::min(dt_pd_, dt_cfl0_);
  const StepPlan plan = plan_steps(scene_.time, dt);
  dt_ = plan.dt;
  total_steps_ = plan.steps;
  end_time_ = plan.end_time;
}

template <int D>
const std::vector<hybrid::CrackTip<D>>& HybridRun<D>::tips() {
  // expand_shrink searches tips at each shrink (and matches them to the last search):
  // report that search, so outputs do not change the run. The other modes never
  // search, so search now.
  if (h_.settings().mode == hybrid::Mode::expand_shrink) return h_.tips();
  return h_.track_tips();
}

template <int D>
void HybridRun<D>::start_outputs() {
  rec_.plan(total_steps_, dt_);
  energy_every_ = std::min<std::int64_t>(rec_.history_every(), 10);
  std::vector<std::string> cols{"step",          "time",
                                "pd_particles",  "transition_particles",
                                "mpm_particles", "removed_particles",
                                "to_pd",         "to_mpm",
                                "expansions",    "shrinks",
                                "onsets",        "tips"};
  for (int k = 0; k < kHybridTipColumns; ++k)
    for (int a = 0; a < D; ++a) cols.push_back("tip" + std::to_string(k) + "_" + axis_name(a));
  cols.insert(cols.end(), {"kinetic_energy", "internal_energy", "load_work_bound"});
  if (h_.settings().audit_conversions) cols.push_back("conversion_energy");
  for (int a = 0; a < D; ++a) cols.push_back(std::string("momentum_") + axis_name(a));
  cols.push_back("max_damage");
  cols.push_back("max_speed");
  for (const auto& b : scene_.boundaries)
    if (b.kind != io::BoundaryKind::traction)
      for (int a = 0; a < D; ++a) cols.push_back("reaction_" + b.name + "_" + axis_name(a));
  add_probe_columns<D>(s_.pd.probes, cols);
  add_j_integral_columns(s_.pd.j_integrals, cols);
  rec_.checkpoints([this](core::StateArchive& a) { state(a); });
  rec_.start(cols, D, end_time_, "pd");
}

template <int D>
void HybridRun<D>::state(core::StateArchive& a) {
  a.sync("hybrid_run/dt", dt_);
  a.sync("hybrid_run/total_steps", total_steps_);
  a.sync("hybrid_run/steps_done", steps_done_);
  a.sync("hybrid_run/kinetic_energy", kinetic_);
  a.sync("hybrid_run/internal_energy", internal_);
  a.sync("hybrid_run/initial_energy", initial_energy_);
  a.sync("hybrid_run/pd_work", pd_work_);
  p_.checkpoint(a);
  h_.checkpoint(a);
}

template <int D>
void HybridRun<D>::step(bool energy) {
  // Work bound on the PD side (as time::VelocityVerlet books it, in absolute
  // values): held components take the reaction's work and the kinetic energy the
  // support gives them, free ones the work of the external force density. Booked
  // over the particles PD moves in this step: one converted during the step moved
  // on the grid before (the grid's work book has it) or on PD (booked here).
  moved_ = h_.pd().movers();
  const auto n = static_cast<Index>(moved_.size());
  u_before_.resize(moved_.size());
  v_before_.resize(moved_.size());
  for (Index k = 0; k < n; ++k) u_before_[k] = p_.u[moved_[k]], v_before_[k] = p_.v[moved_[k]];
  h_.step(dt_, energy);
  const auto& bcs = h_.pd().boundaries();
  const double rho = scene_.material.rho;
  double dw = 0.0;
  for (Index k = 0; k < n; ++k) {
    const Index i = moved_[k];
    for (int a = 0; a < D; ++a) {
      const double du = p_.u[i][a] - u_before_[k][a];
      if (bcs.constrained(i, a)) {
        const double dv2 = p_.v[i][a] * p_.v[i][a] - v_before_[k][a] * v_before_[k][a];
        dw += p_.volume[i] * (std::abs((p_.f[i][a] + p_.b[i][a]) * du) + 0.5 * rho * std::abs(dv2));
      } else {
        dw += p_.volume[i] * std::abs(p_.b[i][a] * du);
      }
    }
  }
  pd_work_ += dw;
  if (energy) {
    kinetic_ = h_.kinetic_energy();
    internal_ = h_.internal_energy();
  }
}

template <int D>
void HybridRun<D>::history_row(std::int64_t step, double t) {
  const auto c = h_.counts();
  const auto& e = h_.events();
  const auto& found = tips();
  std::vector<double> row{static_cast<double>(step),         t,
                          static_cast<double>(c.pd),         static_cast<double>(c.transition),
                          static_cast<double>(c.mpm),        static_cast<double>(c.removed),
                          static_cast<double>(e.to_pd),      static_cast<double>(e.to_mpm),
                          static_cast<double>(e.expansions), static_cast<double>(e.shrinks),
                          static_cast<double>(e.onsets),     static_cast<double>(found.size())};
  for (int k = 0; k < kHybridTipColumns; ++k)
    for (int a = 0; a < D; ++a)
      row.push_back(k < static_cast<int>(found.size()) ? found[k].position[a]
                                                       : std::numeric_limits<double>::quiet_NaN());
  const auto g = h_.mpm().energies();
  row.insert(row.end(), {kinetic_, internal_, pd_work_ + std::abs(g.external_work) + std::abs(g.boundary_work)});
  if (h_.settings().audit_conversions) row.push_back(h_.conversion_energy());
  const Vec<D> mom = h_.momentum();
  for (int a = 0; a < D; ++a) row.push_back(mom[a]);
  const auto phi = pd::local_damage(s_.pd.system);
  row.push_back(phi.empty() ? 0.0 : *std::max_element(phi.begin(), phi.end()));
  row.push_back(max_speed());
  for (const Vec<D>& r : reactions())
    for (int a = 0; a < D; ++a) row.push_back(r[a]);
  add_probe_values<D>(s_.pd.probes, p_.u, p_.v, row);
  if constexpr (D == 2)
    add_j_integral_values(
        s_.pd.j_integrals, [&](const Vec<2>& tip, double r) { return hybrid::j_samples(h_, tip, r); }, row);
  rec_.write_history(row);
}

// The fastest particle that is not removed: a crack-face particle torn loose shows here
// first (docs/models/hybrid.md, "Ejected crack-face particles").
template <int D>
double HybridRun<D>::max_speed() const {
  double v2 = 0.0;
  for (Index i = 0; i < p_.n_real; ++i)
    if (p_.kind[i] != core::ParticleKind::removed) v2 = std::max(v2, p_.v[i].squaredNorm());
  return std::sqrt(v2);
}

// Force the supports exert on the body, per scene boundary (as the MPM and PD runs
// report it): the grid's reaction on its held nodes plus, quasi-static, −Σ V (f + b)
// over the held particles that are PD.
template <int D>
std::vector<Vec<D>> HybridRun<D>::reactions() const {
  std::vector<Vec<D>> out;
  for (std::size_t k = 0; k < scene_.boundaries.size(); ++k) {
    const auto& b = scene_.boundaries[k];
    if (b.kind == io::BoundaryKind::traction) continue;
    Vec<D> r = Vec<D>::Zero();
    for (std::size_t g = 0; g < s_.grid_bc_source.size(); ++g)
      if (s_.grid_bc_source[g] == static_cast<int>(k)) r += h_.mpm().reactions()[g];
    for (const auto& c : h_.pd().boundaries().constraints)
      if (c.name == b.name)
        for (Index i : c.particles)
          if (p_.kind[i] == core::ParticleKind::pd) r -= p_.volume[i] * (p_.f[i] + p_.b[i]);
    out.push_back(r);
  }
  return out;
}

template <int D>
void HybridRun<D>::frame(std::int64_t step, double t) {
  if (!rec_.writes_fields()) return;
  const Index n = p_.n_real;
  auto wants = [&](const char* name) { return wants_field(scene_, name); };
  std::vector<io::Field> fields;
  // 0 pd, 1 mpm, 2 transition, 3 removed (core::ParticleKind).
  if (wants("method"))
    fields.push_back({"method", io::FieldKind::scalar,
                      scalar_field(n, [&](Index i) { return static_cast<double>(static_cast<int>(p_.kind[i])); })});
  if (wants("displacement"))
    fields.push_back({"displacement", io::FieldKind::vector, vector_field<D>(n, [&](Index i) { return p_.u[i]; })});
  if (wants("velocity"))
    fields.push_back({"velocity", io::FieldKind::vector, vector_field<D>(n, [&](Index i) { return p_.v[i]; })});
  if (wants("damage")) fields.push_back({"damage", io::FieldKind::scalar, pd::local_damage(s_.pd.system)});
  // PD particles: the PD model's stress and ε̄_p; the grid's particles (and removed ones): MPM's.
  auto is_pd = [&](Index i) { return p_.kind[i] == core::ParticleKind::pd; };
  if (wants("stress") || wants("von_mises") || wants("triaxiality")) {
    const auto sigma = pd_stresses<D>(s_.pd.system, *s_.pd.model);
    if (wants("stress"))
      fields.push_back({"stress", io::FieldKind::tensor6, tensor6_field(n, [&](Index i) {
                          return is_pd(i) ? sigma[i] : tensor6_of(h_.mpm().state().cauchy(i));
                        })});
    if (wants("von_mises"))
      fields.push_back({"von_mises", io::FieldKind::scalar, scalar_field(n, [&](Index i) {
                          return is_pd(i) ? pd::von_mises(sigma[i]) : h_.mpm().von_mises(i);
                        })});
    if (wants("triaxiality"))
      fields.push_back({"triaxiality", io::FieldKind::scalar, scalar_field(n, [&](Index i) {
                          return is_pd(i) ? pd::triaxiality(sigma[i]) : h_.mpm().triaxiality(i);
                        })});
  }
  if (wants("eq_plastic_strain")) {
    const std::vector<double>& pd_eps = *s_.pd.model->eq_plastic_strain();  // a plastic model (the parser)
    fields.push_back({"eq_plastic_strain", io::FieldKind::scalar,
                      scalar_field(n, [&](Index i) { return is_pd(i) ? pd_eps[i] : h_.mpm().eq_plastic_strain(i); })});
  }
  rec_.write_frame(step, t, vector_field<D>(n, [&](Index i) { return p_.position(i); }), fields);
}

// Unstable: non-finite energies, kinetic + internal energy far above what the
// loads can have put in, or particles so fast that the step exceeds the grid's CFL limit.
template <int D>
bool HybridRun<D>::stable(std::int64_t step, double t) {
  const auto g = h_.mpm().energies();
  const double e = kinetic_ + internal_;
  const double input = initial_energy_ + pd_work_ + std::abs(g.external_work) + std::abs(g.boundary_work);
  double allowed = scene_.time.energy_growth_limit * input + 1e-200;
  // As the MPM run: the grid books a step's boundary work at the next step (all of
  // it after step 1 of a grip that starts at full speed).
  if (std::isfinite(e) && e > allowed)
    allowed += scene_.time.energy_growth_limit * std::abs(h_.mpm().pending_boundary_work(dt_));
  std::ostringstream m;
  if (!std::isfinite(e) || e > allowed) {
    m << "unstable at step " << step << " (t = " << t << " s): kinetic + internal energy " << e << " J exceeds "
      << scene_.time.energy_growth_limit << " × (initial energy + bound on the work of the loads) = " << allowed
      << " J; time step " << dt_ << " s (PD stable step " << dt_pd_ << " s, grid CFL step at t = 0 " << dt_cfl0_
      << " s)";
  } else if (const double cfl = h_.mpm().stable_dt(); !h_.mpm().active().empty() && dt_ > cfl) {
    m << "unstable at step " << step << " (t = " << t << " s): particles moved so fast that the step " << dt_
      << " s exceeds the grid's CFL limit h / max(c + |v|) = " << cfl << " s; lower time.safety_factor or time.dt";
  } else {
    return true;
  }
  rec_.stop("unstable", m.str());
  return false;
}

template <int D>
nlohmann::json HybridRun<D>::summary() const {
  const auto c = h_.counts();
  const auto& e = h_.events();
  const auto& ph = h_.phase_seconds();
  const auto& mph = h_.mpm().phase_seconds();
  double umax = 0.0;
  for (Index i = 0; i < p_.n_real; ++i) umax = std::max(umax, p_.u[i].norm());
  const auto phi = pd::local_damage(s_.pd.system);
  const double max_damage = phi.empty() ? 0.0 : *std::max_element(phi.begin(), phi.end());
  const auto& hs = h_.settings();
  return {
      {"solver", "hybrid"},
      {"model", scene_.model},
      {"constitutive", std::string(name(scene_.mpm->constitutive))},
      {"mode", std::string(name(hs.mode))},
      {"dimension", D},
      {"setting", std::string(name(scene_.setting))},
      {"spacing", scene_.spacing},
      {"horizon", scene_.delta},
      {"cell_size", h_.mpm().cell_size()},
      {"particles", p_.n_real},
      {"dt", dt_},
      {"dt_estimate", {{"pd_stable_step", dt_pd_}, {"grid_cfl_step_at_start", dt_cfl0_}}},
      {"end_time", dt_ * static_cast<double>(steps_done_)},
      {"particle_steps", {{"pd", h_.pd_particle_steps()}, {"mpm", h_.mpm_particle_steps()}}},
      {"wall_time_phases",
       {{"pd", ph.pd},
        {"mpm", ph.mpm},
        {"coupling", ph.coupling},
        {"regions", ph.regions},
        {"total", ph.total()},
        {"mpm_phases",
         {{"prepare", mph.prepare}, {"p2g", mph.p2g}, {"grid", mph.grid}, {"g2p", mph.g2p}, {"stress", mph.stress}}}}},
      {"events",
       {{"onsets", e.onsets},
        {"expansions", e.expansions},
        {"shrinks", e.shrinks},
        {"to_pd", e.to_pd},
        {"to_mpm", e.to_mpm}}},
      {"final_counts", {{"pd", c.pd}, {"transition", c.transition}, {"mpm", c.mpm}, {"removed", c.removed}}},
      {"metrics",
       {{"kinetic_energy", kinetic_},
        {"internal_energy", internal_},
        {"max_damage", max_damage},
        {"max_displacement", umax},
        {"max_speed", max_speed()},
        {"tips", h_.tips().size()}}}};
}

template <int D>
RunResult HybridRun<D>::run() {
  pd_stable_step();
  h_.start(s_.initial_pd);
  choose_time_step();
  start_outputs();
  kinetic_ = h_.kinetic_energy();
  internal_ = h_.internal_energy();
  initial_energy_ = kinetic_ + internal_;
  if (rec_.resuming()) {
    rec_.restore();
  } else {
    history_row(0, 0.0);
    if (rec_.frame_due(0)) frame(0, 0.0);
  }
  for (std::int64_t step = steps_done_ + 1; step <= total_steps_; ++step) {
    const bool last = step == total_steps_;
    const bool with_energy = step % energy_every_ == 0 || rec_.history_due(step) || last;
    if (!rec_.step_or_stop([&] { this->step(with_energy); })) break;
    steps_done_ = step;
    const double t = h_.time();
    if (with_energy && !stable(step, t)) {
      history_row(step, t);
      frame(step, t);
      break;
    }
    if (rec_.history_due(step)) history_row(step, t);
    if (rec_.frame_due(step)) frame(step, t);
    // The PD count from the mover list: counts() scans every particle, too much for each step.
    rec_.progress(step, t, static_cast<Index>(h_.pd().movers().size()));
    if (rec_.after_step(step, t)) break;
  }
  return rec_.finish(steps_done_, h_.time(), h_.counts().pd, p_.n_real, summary());
}

}  // namespace

template <int D>
RunResult run_hybrid(const io::Scene& scene, HybridSetup<D>& setup, const RunOptions& options) {
  HybridRun<D> run(scene, setup, options);
  return run.run();
}

template RunResult run_hybrid<2>(const io::Scene&, HybridSetup<2>&, const RunOptions&);
template RunResult run_hybrid<3>(const io::Scene&, HybridSetup<3>&, const RunOptions&);

}  // namespace pdmpm::sim
