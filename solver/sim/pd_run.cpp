#include "solver/sim/pd_run.hpp"

#include <omp.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>

#include "solver/core/error.hpp"
#include "solver/io/fields_writer.hpp"
#include "solver/io/history_writer.hpp"
#include "solver/io/output_directory.hpp"
#include "solver/io/progress.hpp"
#include "solver/pd/damage.hpp"
#include "solver/pd/stress.hpp"
#include "solver/time/stable_step.hpp"

namespace pdmpm::sim {
namespace {

const char* axis_name(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

template <int D>
class PdRun {
 public:
  PdRun(const io::Scene& scene, PdSetup<D>& setup, const RunOptions& options)
      : scene_(scene), s_(setup), p_(setup.system.particles), opt_(options) {}

  RunResult run();

 private:
  void choose_time_step();
  void external_forces(double t);
  void internal_forces(bool with_energy);
  void start_outputs();
  void history_row(std::int64_t step, double t);
  void frame(std::int64_t step, double t);
  void record_energy(std::int64_t step, double t);
  bool stable(std::int64_t step, double t);
  void verlet();
  void adr();
  nlohmann::json summary(double wall) const;

  double kinetic_energy() const;
  double internal_energy() const;

  const io::Scene& scene_;
  PdSetup<D>& s_;
  core::Particles<D>& p_;
  RunOptions opt_;

  // Time stepping
  double dt_ = 0.0, dt_sa_ = 0.0, dt_lanczos_ = 0.0;
  std::int64_t total_steps_ = 0, steps_done_ = 0, history_every_ = 1, energy_every_ = 1;
  std::vector<std::int64_t> frame_steps_;
  std::size_t next_frame_ = 0;
  double end_time_ = 0.0;

  // Bookkeeping
  std::vector<double> energy_;           // W_i
  std::int64_t broken_sides_ = 0;        // by the critical-stretch rule
  std::int64_t contact_pairs_ = 0;
  Vec<D> indenter_force_ = Vec<D>::Zero();
  double e0_ = 0.0, work_ = 0.0, work_abs_ = 0.0, last_u_ = 0.0, last_ke_ = 0.0;
  bool energy_valid_ = false;
  double force_seconds_ = 0.0;
  std::int64_t bond_evaluations_ = 0;
  std::string status_ = "completed", message_;
  std::int64_t adr_iterations_ = 0;
  double adr_residual_ = 0.0;

  // Outputs
  std::unique_ptr<io::OutputDirectory> out_;
  std::unique_ptr<io::HistoryWriter> history_;
  std::unique_ptr<io::FieldsWriter> fields_;
  std::unique_ptr<io::Progress> progress_;
};

template <int D>
double PdRun<D>::kinetic_energy() const {
  double ke = 0.0;
  for (Index i = 0; i < p_.n_real; ++i) ke += p_.volume[i] * p_.v[i].squaredNorm();
  return 0.5 * s_.system.material.rho * ke;
}

template <int D>
double PdRun<D>::internal_energy() const {
  double u = 0.0;
  for (Index i = 0; i < p_.n_real; ++i) u += energy_[i] * p_.volume[i];
  return u;
}

template <int D>
void PdRun<D>::choose_time_step() {
  auto& sys = s_.system;
  const double contact_row = s_.contact ? s_.contact->stiffness_row_sum(sys) : 0.0;
  dt_sa_ = time::silling_askari_step<D>(sys, *s_.model, contact_row);
  const bool need_lanczos = scene_.time.estimate == io::StableStepEstimate::lanczos || scene_.time.dt.has_value();
  if (need_lanczos) {
    dt_lanczos_ = time::lanczos_step<D>(sys, *s_.model).dt;
    // Contact stiffness is not in the linearised operator; bound its effect as for S&A.
    if (contact_row > 0.0) dt_lanczos_ = std::min(dt_lanczos_, std::sqrt(2.0 * sys.material.rho / contact_row));
  }
  const double estimate = scene_.time.estimate == io::StableStepEstimate::lanczos ? dt_lanczos_ : dt_sa_;
  if (!std::isfinite(estimate))
    throw InputError(scene_.file, "shape", "no particle has a bond: the body falls apart at once (horizon too small or body too thin)");
  if (scene_.time.dt) {
    dt_ = *scene_.time.dt;
    if (dt_ > dt_lanczos_) {
      std::ostringstream m;
      m << "dt = " << dt_ << " s is above the stable step " << dt_lanczos_
        << " s (Lanczos; Silling–Askari bound " << dt_sa_ << " s); use a smaller dt or omit it";
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
void PdRun<D>::external_forces(double t) {
  for (Index i = 0; i < p_.n_real; ++i) p_.b[i].setZero();
  if (s_.has_body_force) {
    bc::ExpressionVariables vars;
    vars.t = t;
    for (Index i = 0; i < p_.n_real; ++i) {
      vars.x = p_.x0[i][0];
      if constexpr (D > 1) vars.y = p_.x0[i][1];
      if constexpr (D > 2) vars.z = p_.x0[i][2];
      for (int a = 0; a < D; ++a) p_.b[i][a] = s_.body_force[a](vars);
    }
  }
  s_.boundaries.add_tractions(p_, t);
  if (s_.indenter) indenter_force_ = s_.indenter->add_forces(p_, t);
}

template <int D>
void PdRun<D>::internal_forces(bool with_energy) {
  pd::ForceRequest req;
  req.break_bonds = s_.damage;
  req.critical_stretch = s_.critical_stretch;
  req.energy = with_energy ? &energy_ : nullptr;
  const double t0 = omp_get_wtime();
  broken_sides_ += s_.model->compute_forces(s_.system, req);
  force_seconds_ += omp_get_wtime() - t0;
  bond_evaluations_ += s_.system.families.n_bonds();
  if (s_.contact) contact_pairs_ = s_.contact->add_forces(s_.system);
  energy_valid_ = with_energy;
}

template <int D>
void PdRun<D>::start_outputs() {
  out_ = std::make_unique<io::OutputDirectory>(opt_.out_dir);
  std::vector<std::string> cols{"step", "time", "kinetic_energy", "internal_energy", "external_work", "energy_error"};
  for (int a = 0; a < D; ++a) cols.push_back(std::string("momentum_") + axis_name(a));
  if constexpr (D == 2) cols.push_back("angular_momentum_z");
  if constexpr (D == 3)
    for (int a = 0; a < 3; ++a) cols.push_back(std::string("angular_momentum_") + axis_name(a));
  cols.insert(cols.end(), {"broken_bonds", "max_damage"});
  if (s_.contact) cols.push_back("contact_pairs");
  if (s_.indenter)
    for (int a = 0; a < D; ++a) cols.push_back(std::string("indenter_force_") + axis_name(a));
  for (const auto& c : s_.boundaries.constraints)
    for (int a = 0; a < D; ++a) cols.push_back("reaction_" + c.name + "_" + axis_name(a));
  for (const auto& pr : s_.probes)
    for (const char* q : {"u", "v"})
      for (int a = 0; a < D; ++a) cols.push_back("probe_" + pr.name + "_" + q + axis_name(a));
  if (scene_.time.integrator == io::Integrator::adr) cols.insert(cols.end(), {"adr_iterations", "adr_residual"});
  history_ = std::make_unique<io::HistoryWriter>(out_->path("history.csv"), cols);
  if (opt_.write_fields)
    fields_ = std::make_unique<io::FieldsWriter>(out_->path("fields.h5"), out_->path("fields.xdmf"), "fields.h5", D);
  if (opt_.progress)
    progress_ = std::make_unique<io::Progress>(std::cerr, io::Progress::stderr_is_terminal(),
                                               total_steps_, scene_.time.integrator == io::Integrator::verlet ? end_time_ : 0.0,
                                               scene_.id);
}

template <int D>
void PdRun<D>::record_energy(std::int64_t step, double t) {
  (void)step;
  (void)t;
  last_ke_ = kinetic_energy();
  last_u_ = internal_energy();
}

template <int D>
bool PdRun<D>::stable(std::int64_t step, double t) {
  // Work booked so far lags the last half-kick by up to one step; allow for the
  // work the current external forces can do within one step.
  double lag = 0.0;
  const double rho = s_.system.material.rho;
  for (Index i = 0; i < p_.n_real; ++i) {
    const double b = p_.b[i].norm();
    if (b > 0.0) lag += p_.volume[i] * b * (p_.v[i].norm() * dt_ + 0.5 * dt_ * dt_ * b / rho);
  }
  const double e = last_ke_ + last_u_;
  const double allowed = scene_.time.energy_growth_limit * (e0_ + work_abs_ + lag) + 1e-200;
  if (std::isfinite(e) && e <= allowed) return true;
  std::ostringstream m;
  m << "unstable at step " << step << " (t = " << t << " s): total energy " << e << " J exceeds "
    << scene_.time.energy_growth_limit << " × (initial energy + work done) = " << allowed << " J. Time step "
    << dt_ << " s; stable-step estimate " << (dt_lanczos_ > 0 ? dt_lanczos_ : dt_sa_) << " s ("
    << (dt_lanczos_ > 0 ? "Lanczos" : "Silling–Askari") << "), i.e. this run used "
    << dt_ / (dt_lanczos_ > 0 ? dt_lanczos_ : dt_sa_) << " × the estimate";
  status_ = "unstable";
  message_ = m.str();
  return false;
}

template <int D>
void PdRun<D>::history_row(std::int64_t step, double t) {
  std::vector<double> row{static_cast<double>(step), t, last_ke_, last_u_, work_, last_ke_ + last_u_ - e0_ - work_};
  const double rho = s_.system.material.rho;
  Vec<D> mom = Vec<D>::Zero();
  Eigen::Vector3d ang = Eigen::Vector3d::Zero();
  for (Index i = 0; i < p_.n_real; ++i) {
    const Vec<D> pi = rho * p_.volume[i] * p_.v[i];
    mom += pi;
    Eigen::Vector3d x3 = Eigen::Vector3d::Zero(), p3 = Eigen::Vector3d::Zero();
    const Vec<D> xi = p_.position(i);
    for (int a = 0; a < D; ++a) x3[a] = xi[a], p3[a] = pi[a];
    ang += x3.cross(p3);
  }
  for (int a = 0; a < D; ++a) row.push_back(mom[a]);
  if constexpr (D == 2) row.push_back(ang[2]);
  if constexpr (D == 3)
    for (int a = 0; a < 3; ++a) row.push_back(ang[a]);
  row.push_back(static_cast<double>(broken_sides_) / 2.0);
  const auto phi = pd::local_damage(s_.system);
  double phimax = 0.0;
  for (double x : phi) phimax = std::max(phimax, x);
  row.push_back(phimax);
  if (s_.contact) row.push_back(static_cast<double>(contact_pairs_));
  if (s_.indenter)
    for (int a = 0; a < D; ++a) row.push_back(indenter_force_[a]);
  for (const auto& c : s_.boundaries.constraints) {
    // Force the support exerts on the body, quasi-static: −Σ V (f + b).
    Vec<D> r = Vec<D>::Zero();
    for (Index i : c.particles) r -= p_.volume[i] * (p_.f[i] + p_.b[i]);
    for (int a = 0; a < D; ++a) row.push_back(r[a]);
  }
  for (const auto& pr : s_.probes) {
    for (int a = 0; a < D; ++a) row.push_back(p_.u[pr.particle][a]);
    for (int a = 0; a < D; ++a) row.push_back(p_.v[pr.particle][a]);
  }
  if (scene_.time.integrator == io::Integrator::adr) {
    row.push_back(static_cast<double>(adr_iterations_));
    row.push_back(adr_residual_);
  }
  history_->write_row(row);
}

template <int D>
void PdRun<D>::frame(std::int64_t step, double t) {
  if (!fields_) return;
  const Index n = p_.n_real;
  auto wants = [&](const char* name) {
    return std::find(scene_.output.fields.begin(), scene_.output.fields.end(), name) != scene_.output.fields.end();
  };
  auto vec3 = [&](const std::vector<Vec<D>>& v) {
    std::vector<double> out(static_cast<std::size_t>(n) * 3, 0.0);
    for (Index i = 0; i < n; ++i)
      for (int a = 0; a < D; ++a) out[3 * i + a] = v[i][a];
    return out;
  };
  std::vector<Vec<D>> pos(n);
  for (Index i = 0; i < n; ++i) pos[i] = p_.position(i);
  std::vector<io::Field> fields;
  if (wants("displacement")) fields.push_back({"displacement", io::FieldKind::vector, vec3(p_.u)});
  if (wants("velocity")) fields.push_back({"velocity", io::FieldKind::vector, vec3(p_.v)});
  if (wants("damage")) fields.push_back({"damage", io::FieldKind::scalar, pd::local_damage(s_.system)});
  if (wants("dilatation")) {
    std::vector<double> theta;
    s_.model->dilatation(s_.system, theta);
    if (s_.system.setting == pd::Setting::plane_stress) {
      // Report the 3D dilatation: add ε_zz = −ν/(1−ν) (ε_xx + ε_yy).
      const double nu = s_.system.material.nu;
      for (double& th : theta) th *= 1.0 - nu / (1.0 - nu);
    }
    fields.push_back({"dilatation", io::FieldKind::scalar, theta});
  }
  if (wants("stress") || wants("von_mises")) {
    const auto sigma = pd::particle_stress(s_.system);
    if (wants("stress")) {
      std::vector<double> flat(static_cast<std::size_t>(n) * 6);
      for (Index i = 0; i < n; ++i)
        for (int c = 0; c < 6; ++c) flat[6 * i + c] = sigma[i][c];
      fields.push_back({"stress", io::FieldKind::tensor6, flat});
    }
    if (wants("von_mises")) {
      std::vector<double> vm(n);
      for (Index i = 0; i < n; ++i) vm[i] = pd::von_mises(sigma[i]);
      fields.push_back({"von_mises", io::FieldKind::scalar, vm});
    }
  }
  fields_->write_frame(step, t, vec3(pos), fields);
}

template <int D>
void PdRun<D>::verlet() {
  auto& bcs = s_.boundaries;
  const double rho = s_.system.material.rho;
  const double dt = dt_;
  const Index n = p_.n_real;
  // Constrained (particle, component) pairs, for the work the supports do.
  std::vector<std::pair<Index, int>> held;
  for (Index i = 0; i < n; ++i)
    for (int a = 0; a < D; ++a)
      if (bcs.constrained(i, a)) held.emplace_back(i, a);
  std::vector<double> held_f(held.size()), held_v(held.size());
  std::vector<Vec<D>> u_old(n), b_old(n);
  const auto& mask = bcs.mask();

  double t = 0.0;
  bcs.apply_displacement(p_, 0.0, 0.0);
  p_.update_ghosts();
  external_forces(0.0);
  internal_forces(true);
  record_energy(0, 0.0);
  e0_ = last_ke_ + last_u_;
  history_row(0, 0.0);
  if (next_frame_ < frame_steps_.size() && frame_steps_[next_frame_] == 0) frame(0, 0.0), ++next_frame_;

  for (std::int64_t step = 1; step <= total_steps_; ++step) {
    for (std::size_t k = 0; k < held.size(); ++k) {
      held_f[k] = p_.f[held[k].first][held[k].second] + p_.b[held[k].first][held[k].second];
      held_v[k] = p_.v[held[k].first][held[k].second];
    }
#pragma omp parallel for schedule(static)
    for (Index i = 0; i < n; ++i) {
      for (int a = 0; a < D; ++a)
        if (!mask[static_cast<std::size_t>(i) * D + a]) p_.v[i][a] += 0.5 * dt * (p_.f[i][a] + p_.b[i][a]) / rho;
      u_old[i] = p_.u[i];
      b_old[i] = p_.b[i];
    }
    bcs.apply_velocity(p_, t + 0.5 * dt);
#pragma omp parallel for schedule(static)
    for (Index i = 0; i < n; ++i) p_.u[i] += dt * p_.v[i];
    t = dt * static_cast<double>(step);
    bcs.apply_displacement(p_, t, dt);
    p_.update_ghosts();
    external_forces(t);
    const bool with_energy = step % energy_every_ == 0 || step % history_every_ == 0 || step == total_steps_;
    internal_forces(with_energy);
#pragma omp parallel for schedule(static)
    for (Index i = 0; i < n; ++i)
      for (int a = 0; a < D; ++a)
        if (!mask[static_cast<std::size_t>(i) * D + a]) p_.v[i][a] += 0.5 * dt * (p_.f[i][a] + p_.b[i][a]) / rho;
    bcs.apply_velocity(p_, t);

    // Work of external forces (trapezoidal) and of the supports on held components.
    double dw = 0.0;
    for (Index i = 0; i < n; ++i) dw += p_.volume[i] * 0.5 * (b_old[i] + p_.b[i]).dot(p_.u[i] - u_old[i]);
    for (std::size_t k = 0; k < held.size(); ++k) {
      const auto [i, a] = held[k];
      const double du = p_.u[i][a] - u_old[i][a];
      const double fnew = p_.f[i][a] + p_.b[i][a];
      dw += p_.volume[i] * (0.5 * rho * (p_.v[i][a] * p_.v[i][a] - held_v[k] * held_v[k]) - 0.5 * (held_f[k] + fnew) * du);
    }
    work_ += dw;
    work_abs_ += std::abs(dw);
    steps_done_ = step;

    if (with_energy) {
      record_energy(step, t);
      if (!stable(step, t)) {
        history_row(step, t);
        frame(step, t);
        return;
      }
    }
    if (step % history_every_ == 0 || step == total_steps_) history_row(step, t);
    if (next_frame_ < frame_steps_.size() && frame_steps_[next_frame_] == step) frame(step, t), ++next_frame_;
    if (progress_) progress_->update(step, t, broken_sides_ / 2);
  }
}

template <int D>
void PdRun<D>::adr() {
  // Adaptive dynamic relaxation (Kilic & Madenci 2010) with Δt = 1 and a
  // fictitious density λ_i from the stiffness row sum, large enough for stability.
  auto& bcs = s_.boundaries;
  auto& sys = s_.system;
  const Index n = p_.n_real;
  const auto& mask = bcs.mask();
  const double contact_row = s_.contact ? s_.contact->stiffness_row_sum(sys) : 0.0;
  std::vector<double> lambda(n);
  for (Index i = 0; i < n; ++i) lambda[i] = 0.625 * (s_.model->stiffness_row_sum(sys, i) + contact_row) + 1e-300;
  std::vector<Vec<D>> vhalf(n, Vec<D>::Zero()), fprev(n, Vec<D>::Zero());

  bcs.apply_displacement(p_, 0.0, 0.0);
  p_.update_ghosts();
  external_forces(0.0);
  internal_forces(true);
  record_energy(0, 0.0);
  e0_ = last_ke_ + last_u_;
  history_row(0, 0.0);
  if (!frame_steps_.empty() && frame_steps_.front() == 0) frame(0, 0.0), ++next_frame_;

  for (std::int64_t load = 1; load <= total_steps_; ++load) {
    const double t = static_cast<double>(load) / static_cast<double>(total_steps_);
    bool converged = false;
    std::int64_t it = 0;
    for (auto& v : vhalf) v.setZero();
    for (; it < scene_.time.max_steps; ++it) {
      bcs.apply_displacement(p_, t, 0.0);
      p_.update_ghosts();
      external_forces(t);
      internal_forces(false);
      // Residual over free components, against the load scale.
      double r2 = 0.0, scale2 = 0.0, num = 0.0, den = 0.0;
      for (Index i = 0; i < n; ++i)
        for (int a = 0; a < D; ++a) {
          const double F = p_.f[i][a] + p_.b[i][a];
          const double V = p_.volume[i];
          if (mask[static_cast<std::size_t>(i) * D + a]) {
            scale2 += V * V * F * F;  // reaction at supports
            continue;
          }
          r2 += V * V * F * F;
          scale2 += V * V * p_.b[i][a] * p_.b[i][a];
          if (it > 0 && vhalf[i][a] != 0.0) {
            const double k = -(F - fprev[i][a]) / (lambda[i] * vhalf[i][a]);
            num += p_.u[i][a] * k * p_.u[i][a];
          }
          den += p_.u[i][a] * p_.u[i][a];
        }
      adr_residual_ = scale2 > 0.0 ? std::sqrt(r2 / scale2) : std::sqrt(r2);
      if (it > 0 && (adr_residual_ < scene_.time.tolerance || r2 == 0.0)) {
        converged = true;
        break;
      }
      const double c = (it > 0 && num > 0.0 && den > 0.0) ? std::min(2.0 * std::sqrt(num / den), 1.999) : 0.0;
      for (Index i = 0; i < n; ++i)
        for (int a = 0; a < D; ++a) {
          if (mask[static_cast<std::size_t>(i) * D + a]) continue;
          const double F = p_.f[i][a] + p_.b[i][a];
          vhalf[i][a] = it == 0 ? 0.5 * F / lambda[i] : ((2.0 - c) * vhalf[i][a] + 2.0 * F / lambda[i]) / (2.0 + c);
          fprev[i][a] = F;
          p_.u[i][a] += vhalf[i][a];
        }
      if (!p_.u[0].allFinite()) break;
    }
    adr_iterations_ = it;
    internal_forces(true);
    for (auto& v : p_.v) v.setZero();
    record_energy(load, t);
    steps_done_ = load;
    history_row(load, t);
    if (next_frame_ < frame_steps_.size() && frame_steps_[next_frame_] == load) frame(load, t), ++next_frame_;
    if (progress_) progress_->update(load, t, broken_sides_ / 2);
    if (!converged) {
      std::ostringstream m;
      m << "adaptive dynamic relaxation did not converge at load step " << load << " of " << total_steps_
        << ": residual " << adr_residual_ << " after " << it << " iterations (tolerance " << scene_.time.tolerance
        << "; raise time.max_steps or loosen time.tolerance)";
      status_ = "not_converged";
      message_ = m.str();
      return;
    }
  }
}

template <int D>
nlohmann::json PdRun<D>::summary(double wall) const {
  const auto& sys = s_.system;
  const auto phi = pd::local_damage(sys);
  double phimax = 0.0, umax = 0.0;
  for (double x : phi) phimax = std::max(phimax, x);
  for (Index i = 0; i < p_.n_real; ++i) umax = std::max(umax, p_.u[i].norm());
  nlohmann::json dt_est = {{"silling_askari", dt_sa_}};
  if (dt_lanczos_ > 0) dt_est["lanczos"] = dt_lanczos_;
  nlohmann::json j = {
      {"scene", scene_.id},
      {"file", scene_.file},
      {"description", scene_.description},
      {"status", status_},
      {"message", message_},
      {"solver", "pd"},
      {"model", s_.model->name()},
      {"influence", std::string(pd::name(sys.influence))},
      {"partial_volume", std::string(pd::name(sys.partial_volume))},
      {"dimension", D},
      {"setting", std::string(pd::name(sys.setting))},
      {"spacing", sys.spacing()},
      {"horizon", sys.delta},
      {"horizon_ratio", sys.delta / sys.spacing()},
      {"particles", p_.n_real},
      {"ghost_particles", p_.n_ghost()},
      {"bonds", sys.families.n_bonds() / 2},
      {"bond_sides", sys.families.n_bonds()},
      {"integrator", scene_.time.integrator == io::Integrator::verlet ? "verlet" : "adr"},
      {"steps", steps_done_},
      {"steps_requested", total_steps_},
      {"dt", scene_.time.integrator == io::Integrator::verlet ? dt_ : 1.0},
      {"dt_estimate", dt_est},
      {"end_time", scene_.time.integrator == io::Integrator::verlet ? dt_ * static_cast<double>(steps_done_) : 1.0},
      {"threads", omp_get_max_threads()},
      {"wall_time_s", wall},
      {"force_time_s", force_seconds_},
      {"bond_updates_per_second", force_seconds_ > 0 ? static_cast<double>(bond_evaluations_) / force_seconds_ : 0.0},
      {"particle_steps_per_second", wall > 0 ? static_cast<double>(p_.n_real) * static_cast<double>(steps_done_) / wall : 0.0},
      {"metrics",
       {{"broken_bonds", broken_sides_ / 2},
        {"precrack_cut_bonds", s_.precrack_cut / 2},
        {"max_damage", phimax},
        {"max_displacement", umax},
        {"kinetic_energy", last_ke_},
        {"internal_energy", last_u_},
        {"external_work", work_},
        {"energy_error", last_ke_ + last_u_ - e0_ - work_},
        {"critical_stretch", s_.critical_stretch}}},
      {"provenance", {{"git_sha", PDMPM_GIT_SHA}, {"compiler", PDMPM_COMPILER}, {"flags", PDMPM_FLAGS}}}};
  if (scene_.time.integrator == io::Integrator::adr) {
    j["metrics"]["adr_iterations_last"] = adr_iterations_;
    j["metrics"]["adr_residual"] = adr_residual_;
  }
  return j;
}

template <int D>
RunResult PdRun<D>::run() {
  const auto t0 = std::chrono::steady_clock::now();
  choose_time_step();
  energy_.assign(p_.n_real, 0.0);
  history_every_ = scene_.output.history_every.value_or(std::max<std::int64_t>(1, total_steps_ / 1000));
  energy_every_ = std::min<std::int64_t>(history_every_, 10);
  if (scene_.output.every) {
    for (std::int64_t s = 0; s <= total_steps_; s += *scene_.output.every) frame_steps_.push_back(s);
  } else {
    const std::int64_t frames = scene_.output.frames.value_or(std::min<std::int64_t>(11, total_steps_ + 1));
    for (std::int64_t k = 0; k < frames; ++k)
      frame_steps_.push_back(frames == 1 ? total_steps_ : (k * total_steps_) / (frames - 1));
    frame_steps_.erase(std::unique(frame_steps_.begin(), frame_steps_.end()), frame_steps_.end());
  }
  if (frame_steps_.empty() || frame_steps_.back() != total_steps_) frame_steps_.push_back(total_steps_);

  start_outputs();
  if (scene_.time.integrator == io::Integrator::verlet) verlet();
  else adr();
  if (progress_) progress_->finish(steps_done_, static_cast<double>(steps_done_) * dt_, broken_sides_ / 2);
  if (fields_) fields_->close();
  history_.reset();

  RunResult r;
  r.status = status_;
  r.message = message_;
  r.summary = summary(seconds_since(t0));
  {
    std::ofstream js(out_->path("summary.json"));
    js << r.summary.dump(2) << '\n';
  }
  out_->commit();
  r.exit_code = status_ == "completed" ? 0 : 3;
  return r;
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
