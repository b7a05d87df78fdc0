#include "solver/sim/pd_run.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "solver/core/error.hpp"
#include "solver/dist/communicator.hpp"
#include "solver/pd/crack_observables.hpp"
#include "solver/pd/damage.hpp"
#include "solver/pd/j_samples.hpp"
#include "solver/pd/stress.hpp"
#include "solver/time/dynamic_relaxation.hpp"
#include "solver/sim/crack_report.hpp"
#include "solver/sim/frame_fields.hpp"
#include "solver/sim/run_recorder.hpp"
#include "solver/sim/run_metrics.hpp"
#include "solver/time/velocity_verlet.hpp"
#include "solver/time/stable_step.hpp"

namespace pdmpm::sim {
namespace {

template <int D>
class PdRun {
 public:
  PdRun(const io::Scene& scene, PdSetup<D>& setup, const RunOptions& options)
      : scene_(scene),
        s_(setup),
        p_(setup.system.particles),
        simulation_(make_simulation(setup)),
        rec_(scene, options),
        comm_(rec_.distributed() ? options.comm : nullptr) {}

  RunResult run();

 private:
  void choose_time_step();
  void start_outputs();
  void history_row(std::int64_t step, double t);
  void gather_bond_flags();
  void frame(std::int64_t step, double t);
  void maybe_frame(std::int64_t step, double t) {
    if (rec_.frame_due(step)) frame(step, t);
  }
  bool stable(std::int64_t step, double t, const time::VelocityVerlet<D>& stepper);
  void verlet();
  void adr();
  void state(core::StateArchive& a);  // what a checkpoint holds of this run (verlet)
  nlohmann::json summary() const;
  bool plastic() const { return s_.model->eq_plastic_strain() != nullptr; }
  // K + U + W_p − E₀ − W_ext: zero for an exact integrator (W_p = 0 for elastic models).
  double energy_error() const {
    return kinetic_energy_ + internal_energy_ + s_.model->plastic_work() - initial_energy_ - external_work_;
  }
  std::vector<pd::Tensor6> stresses() const;
  // Whole-body values: over every process of a distributed run (each holds its own
  // particles' share), the same on each; this process's own otherwise.
  std::int64_t everywhere(std::int64_t local) const { return comm_ ? comm_->sum(local) : local; }
  double largest(double local) const { return comm_ ? comm_->max(local) : local; }
  // The largest entry of a per-real-particle array over the whole body (0 if empty).
  double largest(const std::vector<double>& a) const {
    return largest(a.empty() ? 0.0 : *std::max_element(a.begin(), a.end()));
  }
  std::int64_t broken_bonds() const { return everywhere(simulation_.broken_sides()) / 2; }
  Index particles() const { return s_.ownership ? s_.ownership->global_count : p_.n_real; }
  std::vector<core::JSample> j_samples(const Vec<2>& tip, double radius) const;

  const io::Scene& scene_;
  PdSetup<D>& s_;
  core::Particles<D>& p_;
  pd::Simulation<D> simulation_;
  RunRecorder rec_;
  const dist::Communicator* comm_;  // null unless distributed

  double dt_ = 0.0, dt_sa_ = 0.0, dt_lanczos_ = 0.0;
  std::int64_t total_steps_ = 0, steps_done_ = 0, energy_every_ = 1;
  double end_time_ = 0.0;

  // Energies of the last evaluation with energy, and the booked external work.
  double kinetic_energy_ = 0.0, internal_energy_ = 0.0, initial_energy_ = 0.0, external_work_ = 0.0;
  time::RelaxationResult relax_;
  std::optional<pd::CrackObservables<D>> crack_;
  std::optional<time::VelocityVerlet<D>> stepper_;
};

template <int D>
void PdRun<D>::choose_time_step() {
  auto& sys = s_.system;
  const double contact_row = s_.contact ? s_.contact->stiffness_row_sum(sys) : 0.0;
  dt_sa_ = time::silling_askari_step<D>(sys, *s_.model, contact_row);
  if (scene_.time.estimate == io::StableStepEstimate::lanczos || scene_.time.dt.has_value()) {
    dt_lanczos_ = time::lanczos_step<D>(sys, *s_.model).dt;
    // Contact stiffness is not in the linearised operator; bound its effect as for S&A.
    if (contact_row > 0.0) dt_lanczos_ = std::min(dt_lanczos_, std::sqrt(2.0 * sys.material.rho / contact_row));
  }
  const double estimate = scene_.time.estimate == io::StableStepEstimate::lanczos ? dt_lanczos_ : dt_sa_;
  if (!std::isfinite(estimate))
    throw InputError(scene_.file, "shape",
                     "no particle has a bond: the body falls apart at once (horizon too small or body too thin)");
  if (scene_.time.dt) {
    dt_ = *scene_.time.dt;
    if (dt_ > dt_lanczos_) {
      std::ostringstream m;
      m << "dt = " << dt_ << " s is above the stable step " << dt_lanczos_ << " s (Lanczos; Silling–Askari bound "
        << dt_sa_ << " s); use a smaller dt or omit it";
      throw InputError(scene_.file, "time.dt", m.str());
    }
  } else {
    dt_ = scene_.time.safety_factor * estimate;
  }
  if (scene_.time.integrator == io::Integrator::verlet) {
    if (scene_.time.steps) {
      total_steps_ = *scene_.time.steps;
    } else {
      total_steps_ = static_cast<std::int64_t>(std::ceil(*scene_.time.end_time / dt_ * (1.0 - 1e-12)));
      dt_ = *scene_.time.end_time / static_cast<double>(total_steps_);  // land exactly on end_time
    }
    end_time_ = dt_ * static_cast<double>(total_steps_);
  } else {
    total_steps_ = scene_.time.load_steps;
    end_time_ = 1.0;
  }
}

template <int D>
void PdRun<D>::start_outputs() {
  // ADR: t is the load factor, one per load step.
  const bool dynamic = scene_.time.integrator == io::Integrator::verlet;
  rec_.plan(total_steps_, dynamic ? dt_ : 1.0 / static_cast<double>(total_steps_));
  energy_every_ = std::min<std::int64_t>(rec_.history_every(), 10);
  std::vector<std::string> cols{"step", "time", "kinetic_energy", "internal_energy", "external_work", "energy_error"};
  for (int a = 0; a < D; ++a) cols.push_back(std::string("momentum_") + axis_name(a));
  if constexpr (D == 2) cols.push_back("angular_momentum_z");
  if constexpr (D == 3)
    for (int a = 0; a < 3; ++a) cols.push_back(std::string("angular_momentum_") + axis_name(a));
  cols.insert(cols.end(), {"broken_bonds", "max_damage"});
  if (plastic()) cols.insert(cols.end(), {"plastic_work", "max_eq_plastic_strain"});
  if (s_.contact) cols.push_back("contact_pairs");
  if (s_.indenter)
    for (int a = 0; a < D; ++a) cols.push_back(std::string("indenter_force_") + axis_name(a));
  for (const auto& c : s_.boundaries.constraints)
    for (int a = 0; a < D; ++a) cols.push_back("reaction_" + c.name + "_" + axis_name(a));
  add_probe_columns<D>(s_.probes, cols);
  add_j_integral_columns(s_.j_integrals, cols);
  if (scene_.time.integrator == io::Integrator::adr) cols.insert(cols.end(), {"adr_iterations", "adr_residual"});
  if (s_.crack) {
    gather_bond_flags();
    crack_.emplace(s_.crack_system(), *s_.crack, s_.locations, s_.crack_exclude);
    const auto more = crack_columns(*crack_);
    cols.insert(cols.end(), more.begin(), more.end());
  }
  if (!dynamic)
    rec_.no_checkpoints("dynamic relaxation (ADR) runs have no checkpoints yet");
  else if (crack_)
    rec_.no_checkpoints("the [crack] observables keep a history of their own that checkpoints do not hold yet");
  else
    rec_.checkpoints([this](core::StateArchive& a) { state(a); });
  rec_.start(cols, D, dynamic ? end_time_ : 0.0);
}

template <int D>
void PdRun<D>::state(core::StateArchive& a) {
  a.sync("pd_run/dt", dt_);
  a.sync("pd_run/total_steps", total_steps_);
  a.sync("pd_run/steps_done", steps_done_);
  a.sync("pd_run/kinetic_energy", kinetic_energy_);
  a.sync("pd_run/internal_energy", internal_energy_);
  a.sync("pd_run/initial_energy", initial_energy_);
  a.sync("pd_run/external_work", external_work_);
  p_.checkpoint(a);
  simulation_.checkpoint(a);
  stepper_->checkpoint(a);
}

template <int D>
bool PdRun<D>::stable(std::int64_t step, double t, const time::VelocityVerlet<D>& stepper) {
  const double e = kinetic_energy_ + internal_energy_;
  const double allowed =
      scene_.time.energy_growth_limit * (initial_energy_ + stepper.absolute_work() + stepper.pending_work()) + 1e-200;
  if (std::isfinite(e) && e <= allowed) return true;
  const double estimate = dt_lanczos_ > 0 ? dt_lanczos_ : dt_sa_;
  std::ostringstream m;
  m << "unstable at step " << step << " (t = " << t << " s): total energy " << e << " J exceeds "
    << scene_.time.energy_growth_limit << " × (initial energy + work done) = " << allowed << " J. Time step " << dt_
    << " s; stable-step estimate " << estimate << " s (" << (dt_lanczos_ > 0 ? "Lanczos" : "Silling–Askari")
    << "), i.e. this run used " << dt_ / estimate << " × the estimate";
  rec_.stop("unstable", m.str());
  return false;
}

// The J-integral's samples in a disc: every process's, in the global particle order (each
// process's own particles in their order, the processes in rank order), on every process,
// so the domain sum is the one-process sum.
template <int D>
std::vector<core::JSample> PdRun<D>::j_samples(const Vec<2>& tip, double radius) const {
  if constexpr (D != 2) {
    (void)tip, (void)radius;
    return {};
  } else {
    return gather_j_samples(pd::elastic_j_samples(s_.system, tip, radius), comm_);
  }
}

// Distributed crack tracking: every process's bond flags, in rank order, are the whole
// body's (own families hold the one-process bonds in the one-process order).
template <int D>
void PdRun<D>::gather_bond_flags() {
  if (!s_.crack_body) return;
  const auto& own = s_.system.bonds.flags.trial;
  const std::vector<double> mine(own.begin(), own.begin() + s_.system.families.n_bonds());
  const auto all = comm_->all_gather(mine);
  auto& whole = s_.crack_body->bonds.flags;
  if (static_cast<BondIndex>(all.size()) != s_.crack_body->families.n_bonds())
    throw RunError("crack tracking: the processes' bonds do not make up the whole body's");
  for (std::size_t b = 0; b < all.size(); ++b) whole.trial[b] = whole.committed[b] = static_cast<std::uint8_t>(all[b]);
}

template <int D>
void PdRun<D>::history_row(std::int64_t step, double t) {
  std::vector<double> row{
      static_cast<double>(step), t, kinetic_energy_, internal_energy_, external_work_, energy_error()};
  const Vec<D> mom = simulation_.momentum();
  const Eigen::Vector3d ang = simulation_.angular_momentum();
  for (int a = 0; a < D; ++a) row.push_back(mom[a]);
  if constexpr (D == 2) row.push_back(ang[2]);
  if constexpr (D == 3)
    for (int a = 0; a < 3; ++a) row.push_back(ang[a]);
  row.push_back(static_cast<double>(broken_bonds()));
  const auto phi = pd::local_damage(s_.system);
  row.push_back(largest(phi));
  if (plastic()) {
    const auto& ep = *s_.model->eq_plastic_strain();
    row.push_back(s_.model->plastic_work());
    row.push_back(largest(ep));
  }
  if (s_.contact) row.push_back(static_cast<double>(simulation_.contact_pairs()));
  if (s_.indenter)
    for (int a = 0; a < D; ++a) row.push_back(simulation_.indenter_force()[a]);
  for (const auto& c : s_.boundaries.constraints) {
    // Force the support exerts on the body, quasi-static: −Σ V (f + b).
    const auto r = p_.template sum_in_order<D>([&](double* sum) {
      for (Index i : c.particles)
        for (int a = 0; a < D; ++a) sum[a] -= p_.volume[i] * (p_.f[i][a] + p_.b[i][a]);
    });
    row.insert(row.end(), r.begin(), r.end());
  }
  add_probe_values<D>(s_.probes, p_.u, p_.v, row, comm_);
  if constexpr (D == 2)
    add_j_integral_values(
        s_.j_integrals, [&](const Vec<2>& tip, double r) { return j_samples(tip, r); }, row);
  if (scene_.time.integrator == io::Integrator::adr) {
    row.push_back(static_cast<double>(relax_.iterations));
    row.push_back(relax_.residual);
  }
  if (crack_) {
    if (s_.crack_body) {
      gather_bond_flags();
      crack_->sample(*s_.crack_body, comm_->all_gather(phi), t);
    } else {
      crack_->sample(s_.system, phi, t);
    }
    crack_values(*crack_, row);
  }
  rec_.write_history(row);
}

// Every process of a distributed run builds its own particles' frame (a field may
// need a halo exchange), the recorder gathers them.
template <int D>
void PdRun<D>::frame(std::int64_t step, double t) {
  if (!rec_.writes_fields()) return;
  const Index n = p_.n_real;
  auto wants = [&](const char* name) { return wants_field(scene_, name); };
  auto vec3 = [&](const std::vector<Vec<D>>& v) { return vector_field<D>(n, [&](Index i) { return v[i]; }); };
  std::vector<io::Field> fields;
  if (wants("displacement")) fields.push_back({"displacement", io::FieldKind::vector, vec3(p_.u)});
  if (wants("velocity")) fields.push_back({"velocity", io::FieldKind::vector, vec3(p_.v)});
  if (wants("damage")) fields.push_back({"damage", io::FieldKind::scalar, pd::local_damage(s_.system)});
  if (wants("dilatation")) {
    std::vector<double> theta;
    s_.model->dilatation(s_.system, theta);
    if (const auto* ezz = s_.model->out_of_plane_strain()) {
      for (Index i = 0; i < n; ++i) theta[i] += (*ezz)[i];  // the model's own ε_zz (plastic plane stress)
    } else if (s_.system.setting == core::Setting::plane_stress) {
      // Report the 3D dilatation: add ε_zz = −ν/(1−ν) (ε_xx + ε_yy).
      const double nu = s_.system.material.nu;
      for (double& th : theta) th *= 1.0 - nu / (1.0 - nu);
    }
    fields.push_back({"dilatation", io::FieldKind::scalar, theta});
  }
  if (wants("stress") || wants("von_mises") || wants("triaxiality")) {
    const auto sigma = stresses();
    if (wants("stress"))
      fields.push_back({"stress", io::FieldKind::tensor6, tensor6_field(n, [&](Index i) { return sigma[i]; })});
    if (wants("von_mises")) {
      std::vector<double> vm(n);
      for (Index i = 0; i < n; ++i) vm[i] = pd::von_mises(sigma[i]);
      fields.push_back({"von_mises", io::FieldKind::scalar, vm});
    }
    if (wants("triaxiality")) {
      std::vector<double> eta(n);
      for (Index i = 0; i < n; ++i) eta[i] = pd::triaxiality(sigma[i]);
      fields.push_back({"triaxiality", io::FieldKind::scalar, eta});
    }
  }
  if (wants("eq_plastic_strain"))
    fields.push_back({"eq_plastic_strain", io::FieldKind::scalar, *s_.model->eq_plastic_strain()});
  rec_.write_frame(step, t, vector_field<D>(n, [&](Index i) { return p_.position(i); }), fields);
}

template <int D>
std::vector<pd::Tensor6> PdRun<D>::stresses() const {
  return pd_stresses<D>(s_.system, *s_.model);
}

template <int D>
void PdRun<D>::verlet() {
  auto& stepper = stepper_.emplace(simulation_, dt_);
  if (rec_.resuming()) {
    rec_.restore();
  } else {
    stepper.start();
    kinetic_energy_ = simulation_.kinetic_energy();
    internal_energy_ = simulation_.internal_energy();
    initial_energy_ = stepper.initial_energy();
    history_row(0, 0.0);
    maybe_frame(0, 0.0);
  }
  for (std::int64_t step = steps_done_ + 1; step <= total_steps_; ++step) {
    const bool with_energy = step % energy_every_ == 0 || rec_.history_due(step);
    if (!rec_.step_or_stop([&] { stepper.step(with_energy); })) return;
    const double t = stepper.time();
    steps_done_ = step;
    external_work_ = stepper.external_work();
    if (with_energy) {
      kinetic_energy_ = simulation_.kinetic_energy();
      internal_energy_ = simulation_.internal_energy();
      if (!stable(step, t, stepper)) {
        history_row(step, t);
        frame(step, t);
        return;
      }
    }
    if (rec_.history_due(step)) history_row(step, t);
    maybe_frame(step, t);
    rec_.progress(step, t, broken_bonds());
    if (rec_.after_step(step, t)) return;
  }
}

template <int D>
void PdRun<D>::adr() {
  time::DynamicRelaxation<D> relax(simulation_);
  s_.boundaries.apply_displacement(p_, 0.0, 0.0);
  p_.update_ghosts();
  simulation_.forces(0.0, true);
  simulation_.accept();
  kinetic_energy_ = 0.0;
  internal_energy_ = initial_energy_ = simulation_.internal_energy();
  history_row(0, 0.0);
  maybe_frame(0, 0.0);
  for (std::int64_t load = 1; load <= total_steps_; ++load) {
    const double t = static_cast<double>(load) / static_cast<double>(total_steps_);
    if (!rec_.step_or_stop([&] { relax_ = relax.solve(t, scene_.time.tolerance, scene_.time.max_steps); })) return;
    internal_energy_ = simulation_.internal_energy();
    steps_done_ = load;
    history_row(load, t);
    maybe_frame(load, t);
    rec_.progress(load, t, simulation_.broken_bonds());
    if (!relax_.converged) {
      std::ostringstream m;
      m << "adaptive dynamic relaxation did not converge at load step " << load << " of " << total_steps_
        << ": residual " << relax_.residual << " after " << relax_.iterations << " iterations (tolerance "
        << scene_.time.tolerance << "; raise time.max_steps or loosen time.tolerance)";
      rec_.stop("not_converged", m.str());
      return;
    }
    if (rec_.after_step(load, t)) return;
  }
}

template <int D>
nlohmann::json PdRun<D>::summary() const {
  const auto& sys = s_.system;
  const auto phi = pd::local_damage(sys);
  double umax = 0.0;
  for (Index i = 0; i < p_.n_real; ++i) umax = std::max(umax, p_.u[i].norm());
  umax = largest(umax);
  const Index halo = s_.ownership ? static_cast<Index>(s_.ownership->halo.size()) : 0;
  const double force_seconds = comm_ ? comm_->max(simulation_.force_seconds()) : simulation_.force_seconds();
  const std::int64_t bond_sides = everywhere(sys.families.n_bonds());
  nlohmann::json dt_est = {{"silling_askari", dt_sa_}};
  if (dt_lanczos_ > 0) dt_est["lanczos"] = dt_lanczos_;
  const bool dynamic = scene_.time.integrator == io::Integrator::verlet;
  nlohmann::json j = {
      {"solver", "pd"},
      {"model", s_.model->name()},
      {"influence", std::string(name(sys.influence))},
      {"partial_volume", std::string(name(sys.partial_volume))},
      {"weighted_volume", sys.continuum_weighted_volume ? "continuum" : "discrete"},
      {"dimension", D},
      {"setting", std::string(name(sys.setting))},
      {"spacing", sys.spacing()},
      {"horizon", sys.delta},
      {"horizon_ratio", sys.delta / sys.spacing()},
      {"particles", particles()},
      {"ghost_particles", s_.symmetry_ghosts},
      {"bonds", bond_sides / 2},
      {"bond_sides", bond_sides},
      {"integrator", dynamic ? "verlet" : "adr"},
      {"dt", dynamic ? dt_ : 1.0},
      {"dt_estimate", dt_est},
      {"end_time", dynamic ? dt_ * static_cast<double>(steps_done_) : 1.0},
      {"force_time_s", force_seconds},  // the slowest process's
      {"contact_time_s", simulation_.contact_seconds()},
      {"bond_updates_per_second",
       force_seconds > 0 ? static_cast<double>(everywhere(simulation_.bond_evaluations())) / force_seconds : 0.0},
      {"bytes_per_bond_side",
       (sizeof(Index) + sizeof(std::uint16_t) + sizeof(std::uint8_t))},  // neighbour, stencil offset, broken flag
      {"metrics",
       {{"broken_bonds", broken_bonds()},
        {"precrack_cut_bonds", everywhere(s_.precrack_cut) / 2},
        {"max_damage", largest(phi)},
        {"max_displacement", umax},
        {"kinetic_energy", kinetic_energy_},
        {"internal_energy", internal_energy_},
        {"external_work", external_work_},
        {"energy_error", energy_error()},
        {"critical_stretch", s_.critical_stretch}}}};
  if (plastic()) {
    const auto& ep = *s_.model->eq_plastic_strain();
    j["metrics"]["plastic_work"] = s_.model->plastic_work();
    j["metrics"]["max_eq_plastic_strain"] = largest(ep);
  }
  if (crack_) j["metrics"]["crack"] = crack_summary(*crack_, s_.crack_system());
  if (s_.ownership) j["halo_particles"] = everywhere(halo);
  if (s_.ownership && s_.contact) j["contact_pairs_across_processes"] = s_.contact->most_pairs_across_processes();
  if (s_.ownership && s_.symmetry_ghosts > 0) {
    // Mirrors of another process's particles (held in the halo): what shows the run tests them.
    Index of_halo = 0;
    for (const Index o : p_.ghost_owner) of_halo += o >= p_.n_real;
    j["mirrors_of_halo_particles"] = everywhere(of_halo);
  }
  if (!dynamic) {
    j["metrics"]["adr_iterations_last"] = relax_.iterations;
    j["metrics"]["adr_residual"] = relax_.residual;
  }
  return j;
}

template <int D>
RunResult PdRun<D>::run() {
  choose_time_step();
  start_outputs();
  if (scene_.time.integrator == io::Integrator::verlet)
    verlet();
  else
    adr();
  // t as the run counts it: time (verlet) or the load factor of the steps done (adr).
  const double t = scene_.time.integrator == io::Integrator::verlet
      ? static_cast<double>(steps_done_) * dt_
      : static_cast<double>(steps_done_) / static_cast<double>(total_steps_);
  const auto broken = broken_bonds();
  return rec_.finish(steps_done_, t, broken, particles(), summary());
}

}  // namespace

template <int D>
RunResult run_pd(const io::Scene& scene, PdSetup<D>& setup, const RunOptions& options) {
  PdRun<D> run(scene, setup, options);
  return run.run();
}

template RunResult run_pd<1>(const io::Scene&, PdSetup<1>&, const RunOptions&);
template RunResult run_pd<2>(const io::Scene&, PdSetup<2>&, const RunOptions&);
template RunResult run_pd<3>(const io::Scene&, PdSetup<3>&, const RunOptions&);

}  // namespace pdmpm::sim
