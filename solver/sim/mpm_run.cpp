#include "solver/sim/mpm_run.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "solver/core/error.hpp"
#include "solver/dist/communicator.hpp"
#include "solver/mpm/j_samples.hpp"
#include "solver/mpm/parallel.hpp"
#include "solver/mpm/simulation.hpp"
#include "solver/sim/frame_fields.hpp"
#include "solver/sim/null_space_watch.hpp"
#include "solver/sim/output_schedule.hpp"
#include "solver/sim/run_metrics.hpp"
#include "solver/sim/run_recorder.hpp"

namespace pdmpm::sim {
namespace {

template <int D>
class MpmRun {
 public:
  MpmRun(const io::Scene& scene, MpmSetup<D>& setup, const RunOptions& options)
      : scene_(scene),
        s_(setup),
        p_(setup.particles),
        sim_(setup.settings, setup.particles, scene.file, "mpm", setup.others),
        rec_(scene, options),
        comm_(rec_.distributed() ? options.comm : nullptr) {
    check_boundary_nodes<D>(scene_, s_.grid_bc_source, sim_);
    set_initial_deformation<D>(s_.initial, sim_);
  }

  RunResult run();

 private:
  void choose_time_step();
  void start_outputs();
  void history_row(std::int64_t step, double t);
  void frame(std::int64_t step, double t);
  bool stable(std::int64_t step, double t);
  GridSampling sampling() const { return {sim_.cell_size() / scene_.spacing, s_.settings.flip}; }
  nlohmann::json summary() const;
  struct Peaks {
    double eq_plastic_strain = 0.0, von_mises = 0.0, displacement = 0.0;
  };
  Peaks peaks() const;
  void state(core::StateArchive& a);  // what a checkpoint holds of this run
  // Whole-body values: over every process of a distributed run (each holds its own points).
  std::int64_t everywhere(std::int64_t local) const { return comm_ ? comm_->sum(local) : local; }
  double largest(double local) const { return comm_ ? comm_->max(local) : local; }
  // MUSL's nodal momenta after a step are the current velocities' (grid_kinetic_energy).
  bool musl() const { return s_.settings.scheme == mpm::UpdateScheme::musl; }
  double null_space_kinetic(const mpm::Energies& e) const {
    const std::optional<double> grid = sim_.grid_kinetic_energy();
    return grid ? e.kinetic - *grid : 0.0;
  }

  const io::Scene& scene_;
  MpmSetup<D>& s_;
  core::Particles<D>& p_;
  mpm::Simulation<D> sim_;
  RunRecorder rec_;
  const dist::Communicator* comm_;  // null unless distributed
  NullSpaceWatch null_space_;

  double dt_ = 0.0, dt_cfl0_ = 0.0, end_time_ = 0.0, balance0_ = 0.0;
  std::int64_t total_steps_ = 0, steps_done_ = 0, failed_ = 0;
};

template <int D>
void MpmRun<D>::choose_time_step() {
  dt_cfl0_ = sim_.stable_dt();
  const StepPlan plan =
      plan_steps(scene_.time, scene_.time.dt ? *scene_.time.dt : scene_.time.safety_factor * dt_cfl0_);
  dt_ = plan.dt;
  total_steps_ = plan.steps;
  end_time_ = plan.end_time;
}

template <int D>
void MpmRun<D>::start_outputs() {
  rec_.plan(total_steps_, dt_);
  std::vector<std::string> cols{"step",          "time",          "kinetic_energy", "internal_energy", "plastic_work",
                                "external_work", "boundary_work", "damping_work",   "energy_error"};
  for (int a = 0; a < D; ++a) cols.push_back(std::string("momentum_") + axis_name(a));
  cols.insert(cols.end(), {"failed_particles", "max_eq_plastic_strain", "max_von_mises"});
  if (musl()) cols.push_back("null_space_kinetic_energy");
  for (const auto& b : scene_.boundaries)
    if (b.kind != io::BoundaryKind::traction)
      for (int a = 0; a < D; ++a) cols.push_back("reaction_" + b.name + "_" + axis_name(a));
  add_probe_columns<D>(s_.probes, cols);
  add_j_integral_columns(s_.j_integrals, cols);
  rec_.checkpoints([this](core::StateArchive& a) { state(a); });
  rec_.start(cols, D, end_time_, "failed");
}

template <int D>
void MpmRun<D>::state(core::StateArchive& a) {
  a.sync("mpm_run/dt", dt_);
  a.sync("mpm_run/total_steps", total_steps_);
  a.sync("mpm_run/steps_done", steps_done_);
  a.sync("mpm_run/failed", failed_);
  a.sync("mpm_run/balance0", balance0_);
  p_.checkpoint(a);
  sim_.checkpoint(a);
}

// The largest ε̄_p, von Mises stress and |u| over the real particles; a parallel max
// (the same value on any thread count). Every history row asks: serial, it was 4 % of a
// run writing a row per step.
template <int D>
typename MpmRun<D>::Peaks MpmRun<D>::peaks() const {
  double eps = 0.0, vm = 0.0, u = 0.0;
  const Index n = p_.n_real;
#pragma omp parallel for schedule(static) reduction(max : eps, vm, u) if (n >= mpm::kParallelMin)
  for (Index i = 0; i < n; ++i) {
    eps = std::max(eps, sim_.eq_plastic_strain(i));
    vm = std::max(vm, sim_.von_mises(i));
    u = std::max(u, p_.u[i].norm());
  }
  return {largest(eps), largest(vm), largest(u)};
}

template <int D>
void MpmRun<D>::history_row(std::int64_t step, double t) {
  const auto e = sim_.energies();
  std::vector<double> row{
      static_cast<double>(step), t, e.kinetic, e.strain, e.dissipated, e.external_work, e.boundary_work, e.damping_work,
      e.balance() - balance0_};
  const Vec<D> mom = sim_.momentum();
  for (int a = 0; a < D; ++a) row.push_back(mom[a]);
  const Peaks peak = peaks();
  row.insert(row.end(), {static_cast<double>(failed_), peak.eq_plastic_strain, peak.von_mises});
  if (musl()) row.push_back(null_space_kinetic(e));
  // Reactions summed per scene boundary (a boundary with several boxes has several grid conditions).
  for (std::size_t k = 0; k < scene_.boundaries.size(); ++k) {
    if (scene_.boundaries[k].kind == io::BoundaryKind::traction) continue;
    Vec<D> r = Vec<D>::Zero();
    for (std::size_t b = 0; b < s_.grid_bc_source.size(); ++b)
      if (s_.grid_bc_source[b] == static_cast<int>(k)) r += sim_.reactions()[b];
    for (int a = 0; a < D; ++a) row.push_back(r[a]);
  }
  add_probe_values<D>(s_.probes, p_.u, p_.v, row, comm_);
  if constexpr (D == 2)
    add_j_integral_values(
        s_.j_integrals,
        [&](const Vec<2>& tip, double r) { return gather_j_samples(mpm::j_samples(sim_, tip, r), comm_); }, row);
  rec_.write_history(row);
}

template <int D>
void MpmRun<D>::frame(std::int64_t step, double t) {
  if (!rec_.writes_fields()) return;
  const Index n = p_.n_real;
  auto wants = [&](const char* name) { return wants_field(scene_, name); };
  auto vec3 = [&](auto&& value) { return vector_field<D>(n, value); };
  auto scalar = [&](auto&& value) { return scalar_field(n, value); };
  std::vector<io::Field> fields;
  if (wants("displacement"))
    fields.push_back({"displacement", io::FieldKind::vector, vec3([&](Index i) { return p_.u[i]; })});
  if (wants("velocity")) fields.push_back({"velocity", io::FieldKind::vector, vec3([&](Index i) { return p_.v[i]; })});
  if (wants("stress"))
    fields.push_back({"stress", io::FieldKind::tensor6,
                      tensor6_field(n, [&](Index i) { return tensor6_of(sim_.state().cauchy(i)); })});
  if (wants("von_mises"))
    fields.push_back({"von_mises", io::FieldKind::scalar, scalar([&](Index i) { return sim_.von_mises(i); })});
  if (wants("triaxiality"))
    fields.push_back({"triaxiality", io::FieldKind::scalar, scalar([&](Index i) { return sim_.triaxiality(i); })});
  if (wants("eq_plastic_strain"))
    fields.push_back(
        {"eq_plastic_strain", io::FieldKind::scalar, scalar([&](Index i) { return sim_.eq_plastic_strain(i); })});
  if (wants("failed"))
    fields.push_back({"failed", io::FieldKind::scalar, scalar([&](Index i) { return sim_.failed(i) ? 1.0 : 0.0; })});
  rec_.write_frame(step, t, vec3([&](Index i) { return p_.position(i); }), fields);
}

// Unstable: non-finite energies, the stored + kinetic energy far above what the
// loads put in, or particles so fast that the fixed step exceeds the CFL limit.
template <int D>
bool MpmRun<D>::stable(std::int64_t step, double t) {
  const auto e = sim_.energies();
  const double stored = e.kinetic + e.strain;
  const double input = std::abs(e.external_work) + std::abs(e.boundary_work) + std::abs(balance0_);
  double allowed = scene_.time.energy_growth_limit * input + 1e-200;
  // Before calling it unstable, add the half step of boundary work the explicit
  // balance books only at the next step (it is all of the work after step 1 of a
  // grip that starts at full speed).
  if (std::isfinite(stored) && stored > allowed)
    allowed += scene_.time.energy_growth_limit * std::abs(sim_.pending_boundary_work(dt_));
  std::ostringstream m;
  if (!std::isfinite(stored) || stored > allowed) {
    m << "unstable at step " << step << " (t = " << t << " s): kinetic + stored energy " << stored << " J exceeds "
      << scene_.time.energy_growth_limit << " × (work done on the body) = " << allowed << " J; time step " << dt_
      << " s, CFL step at t = 0 " << dt_cfl0_ << " s";
  } else if (const double cfl = sim_.stable_dt(); dt_ > cfl) {
    m << "unstable at step " << step << " (t = " << t << " s): particles moved so fast that the step " << dt_
      << " s exceeds the CFL limit h / max(c + |v|) = " << cfl << " s; lower time.safety_factor or time.dt";
  } else {
    if (const std::optional<double> grid = sim_.grid_kinetic_energy())
      if (auto w = null_space_.check(e.kinetic, *grid, e.strain, step, t, sampling()))
        rec_.warn("null_space", *w, step, t);
    return true;
  }
  rec_.stop("unstable", m.str());
  return false;
}

template <int D>
nlohmann::json MpmRun<D>::summary() const {
  const auto e = sim_.energies();
  const Peaks peak = peaks();
  const auto& st = s_.settings;
  const mpm::StepPhaseSeconds& ph = sim_.phase_seconds();
  nlohmann::json j = {
      {"solver", "mpm"},
      {"model", "mpm"},
      {"constitutive", std::string(name(st.material.model))},
      {"shape_function", std::string(name(st.shape))},
      {"update_scheme", std::string(name(st.scheme))},
      {"dimension", D},
      {"setting", std::string(name(st.setting))},
      {"spacing", scene_.spacing},
      {"cell_size", sim_.cell_size()},
      {"particles", s_.global_count},
      {"grid_nodes", sim_.grid().size()},
      {"dt", dt_},
      {"dt_estimate", {{"cfl_step_at_start", dt_cfl0_}}},
      {"end_time", dt_ * static_cast<double>(steps_done_)},
      {"wall_time_phases",
       {{"prepare", ph.prepare}, {"p2g", ph.p2g}, {"grid", ph.grid}, {"g2p", ph.g2p}, {"stress", ph.stress}}},
      {"metrics",
       {{"failed_particles", failed_},
        {"max_eq_plastic_strain", peak.eq_plastic_strain},
        {"max_von_mises", peak.von_mises},
        {"max_displacement", peak.displacement},
        {"kinetic_energy", e.kinetic},
        {"internal_energy", e.strain},
        {"plastic_work", e.dissipated},
        {"external_work", e.external_work},
        {"boundary_work", e.boundary_work},
        {"damping_work", e.damping_work},
        {"energy_error", e.balance() - balance0_},
        {"total_mass", sim_.total_mass()}}}};
  // The other processes' points every process held in the last step (what the ghosts cost).
  if (comm_) j["ghost_points"] = everywhere(sim_.ghost_points());
  return j;
}

template <int D>
RunResult MpmRun<D>::run() {
  choose_time_step();
  start_outputs();
  const std::int64_t check_every = std::min<std::int64_t>(rec_.history_every(), 10);
  balance0_ = sim_.energies().balance();
  if (rec_.resuming()) rec_.restore();
  for (std::int64_t step = rec_.resuming() ? steps_done_ + 1 : 0; step <= total_steps_; ++step) {
    if (step > 0) {
      if (!rec_.step_or_stop([&] { sim_.step(dt_); })) break;
      steps_done_ = step;
      failed_ += everywhere(static_cast<std::int64_t>(sim_.newly_failed().size()));
    }
    const double t = dt_ * static_cast<double>(step);
    const bool last = step == total_steps_;
    if (step > 0 && (step % check_every == 0 || last) && !stable(step, t)) {
      history_row(step, t);
      frame(step, t);
      break;
    }
    if (rec_.history_due(step)) history_row(step, t);
    if (rec_.frame_due(step)) frame(step, t);
    if (step > 0) rec_.progress(step, t, failed_);
    if (step > 0 && rec_.after_step(step, t)) break;
  }
  return rec_.finish(steps_done_, dt_ * static_cast<double>(steps_done_), failed_, s_.global_count, summary());
}

}  // namespace

template <int D>
RunResult run_mpm(const io::Scene& scene, MpmSetup<D>& setup, const RunOptions& options) {
  MpmRun<D> run(scene, setup, options);
  return run.run();
}

template RunResult run_mpm<1>(const io::Scene&, MpmSetup<1>&, const RunOptions&);
template RunResult run_mpm<2>(const io::Scene&, MpmSetup<2>&, const RunOptions&);
template RunResult run_mpm<3>(const io::Scene&, MpmSetup<3>&, const RunOptions&);

}  // namespace pdmpm::sim
