#pragma once
// The spherical-wave problem of Deryugin et al. 2023 §9 (docs/verification/), run in process: one of
// the four scene files (octant / full-cube reading × "layer" / "points" source),
// varied in model, influence function, ν, Δx, m and partial volume, stepped with
// velocity Verlet to exact sample times and compared with the closed form
// (solver/analytic/spherical_wave.hpp). Shared by spherical_wave_gate.cpp and
// convergence_gate.cpp.
//
// Error metrics at time t (the seed does not define its "relative error"):
//   set      free particles outside the source layer and behind the front:
//            max(|x|,|y|,|z|) > r₀ + δ  and  r ≤ r₀ + c_p t. The layer edge is the
//            same for both source choices, so their errors compare on one set.
//   L2       e₂ = sqrt(Σ_i (u_r,i − u_r(r_i, t))²) / sqrt(Σ_i u_r(r_i, t)²), u_r,i = u_i·x_i/r_i (seed eq 9.2)
//   max      e_∞ = max_i |u_r,i − u_r(r_i, t)| / w₀
// The sums run over the particles of the full body (equal volumes): in the
// octant a particle stands for its 2^k mirror images, k = number of its
// coordinates that are not 0 (a particle on a symmetry plane is its own image),
// so both readings at one Δx measure the same thing.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/analytic/spherical_wave.hpp"
#include "solver/io/scene.hpp"
#include "solver/sim/pd_setup.hpp"
#include "solver/time/velocity_verlet.hpp"
#include "solver/time/stable_step.hpp"
#include "verification/support/pd_fixtures.hpp"

namespace pdmpm::test::wave {

// Deryugin et al. 2023 §9.
constexpr double r0 = 0.01, r1 = 0.40, period = 1e-5, amplitude = 1e-4;
constexpr double youngs = 200e9, density = 7850.0;
constexpr double t_end = 7e-5, t_compare = 3e-5;
constexpr double paper_ratio = 3.015;
constexpr long paper_particles = 531414;  // 81³ − 27

enum class Reading { octant, cube };
enum class Source { layer, points };

using pdmpm::name;  // the name tables of pd enums, beside the two below
inline const char* name(Reading r) { return r == Reading::octant ? "octant" : "cube"; }
inline const char* name(Source s) { return s == Source::layer ? "layer" : "points"; }
// Paper resolution of each reading (81 sites across).
inline double paper_spacing(Reading r) { return r == Reading::octant ? 0.005 : 0.01; }

struct Case {
  std::string label;  // "PMB quadratic"
  std::string model;  // "pmb" | "lps"
  pd::Influence influence = pd::Influence::constant;
  double nu = 0.25;
  std::string key() const { return model + "_" + std::string(name(influence)); }
};

// The eight cases of Deryugin et al. 2023 §9: PMB (ν = 1/4) with the six ω of table 4.1,
// LPS (ν = 0.33) with ω = 1 and ω = 1/r.
inline std::vector<Case> paper_cases() {
  using pd::Influence;
  std::vector<Case> c;
  for (auto w : {Influence::constant, Influence::triangular, Influence::quadratic, Influence::semi_elliptical,
                 Influence::exponential, Influence::gaussian})
    c.push_back({"PMB " + std::string(name(w)), "pmb", w, 0.25});
  c.push_back({"LPS ω = 1", "lps", Influence::constant, 0.33});
  c.push_back({"LPS ω = 1/r", "lps", Influence::inverse_distance, 0.33});
  return c;
}

inline Case find_case(const std::string& model, pd::Influence w) {
  for (const auto& c : paper_cases())
    if (c.model == model && c.influence == w) return c;
  throw std::runtime_error("no such case");
}

struct Config {
  Reading reading = Reading::octant;
  Source source = Source::layer;
  double spacing = 0.005;
  double ratio = paper_ratio;  // m = δ/Δx
  pd::PartialVolume partial_volume = pd::PartialVolume::seed001;
  double extent = r1;            // outer half-size of the body (smaller only where the wave cannot reach it)
  double safety = 0.8;           // Δt ≤ safety × Lanczos stable step
  std::vector<double> times{t_compare};
  // Also measure e₂ against the closed form with c_p scaled by this ratio (the
  // lattice's own long-wave speed, see dispersion()); 0 = not measured.
  double lattice_speed_ratio = 0.0;
  bool keep_profiles = false;    // u_r along the +x axis at each time
  bool keep_slices = false;      // |v| on the z = 0 plane at each time
};

struct Metrics {
  double t = 0.0;
  double l2 = 0.0, max = 0.0;  // displacement errors (see above)
  double l2_velocity = 0.0;    // the same L2 measure for v_r
  double l2_lattice = 0.0;     // e₂ against the wave with the lattice's long-wave speed (if asked)
  long count = 0;              // particles in the set
};

struct Profile {
  double t = 0.0;
  std::vector<double> r, u, exact;
};

struct Slice {
  double t = 0.0;
  int n = 0;                    // n × n pixels covering the plane −extent … extent
  std::vector<double> speed;    // |v|, row-major, y up; NaN where there is no particle
};

struct Result {
  std::vector<Metrics> metrics;
  std::vector<Profile> profiles;
  std::vector<Slice> slices;
  long n_real = 0, n_free = 0, n_ghost = 0;
  long long bonds = 0;
  double dt = 0.0, dt_stable = 0.0;
  long long steps = 0;
  double stable_step_seconds = 0.0;  // Lanczos on the small copy (0 when cached)
  double setup_seconds = 0.0;        // particles, families, model, first forces
  double run_seconds = 0.0;          // time stepping and error evaluation
  double peak_rss_mb = 0.0;
  double cp = 0.0;
};

inline std::string scene_path(Reading r, Source s) {
  return std::string(PDMPM_SOURCE_DIR) + "/verification/scenes/spherical_wave_" + name(r) + "_" + name(s) + ".toml";
}

// Resets the kernel's peak-RSS mark of this process (Linux ≥ 4.0), so VmHWM
// afterwards is the peak of what follows.
inline void reset_peak_rss() {
  std::ofstream f("/proc/self/clear_refs");
  if (f) f << "5";
}
inline double peak_rss_mb() {
  std::ifstream f("/proc/self/status");
  std::string key;
  while (f >> key) {
    if (key == "VmHWM:") {
      double kb = 0;
      f >> kb;
      return kb / 1024.0;
    }
    std::string rest;
    std::getline(f, rest);
  }
  return 0.0;
}

// The scene of a configuration: the scene file with model, ω, ν, Δx, m, partial
// volume and extent replaced; the source layer's edge follows δ.
inline io::Scene make_scene(const Case& c, const Config& cfg) {
  io::Scene s = io::parse_scene(scene_path(cfg.reading, cfg.source));
  s.model = c.model;
  s.influence = c.influence;
  s.material.nu = c.nu;
  s.spacing = cfg.spacing;
  s.delta = cfg.ratio * cfg.spacing;
  s.partial_volume = cfg.partial_volume;
  auto& body = s.shapes.front();
  for (int a = 0; a < 3; ++a) {
    body.max[a] = cfg.extent;
    if (cfg.reading == Reading::cube) body.min[a] = -cfg.extent;
  }
  if (cfg.source == Source::layer) {
    const double edge = r0 + s.delta;
    for (int a = 0; a < 3; ++a) s.boundaries.front().region.front().min[a] = -edge, s.boundaries.front().region.front().max[a] = edge;
  }
  s.probes.clear();
  return s;
}

inline analytic::SphericalWave exact_wave(const io::Scene& s) {
  analytic::SphericalWave w;
  w.r0 = r0;
  w.period = period;
  w.amplitude = amplitude;
  w.cp = std::sqrt(s.material.wave_modulus(s.setting) / s.material.rho);
  return w;
}

// Stable step of the configuration from a small full-cube copy (the body out
// to r₀ + 3δ, no symmetry planes): the largest eigenvalue of the lattice
// operator is set by the local environments (interior, faces, edges, corners,
// source), which the small body has as well, at a fraction of the Lanczos cost.
// The octant uses the same step: its modes are the symmetric modes of the full
// cube, so its spectrum lies inside the cube's. (Lanczos on the octant itself
// over-estimates λ_max: with mirror ghosts the operator is not self-adjoint in
// the plain volume-weighted inner product, since a particle on a plane has one
// image where the others have two.) Both readings at one Δx thus take the same
// step and give the same answer.
inline double stable_step(const Case& c, Config cfg) {
  // Cached per configuration within a process (several runs share one).
  static std::map<std::string, double> cache;
  const std::string key = c.key() + "/" + std::to_string(cfg.spacing) + "/" + std::to_string(cfg.ratio) + "/" +
                          std::string(name(cfg.partial_volume));
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  cfg.reading = Reading::cube;
  cfg.extent = std::min(cfg.extent, r0 + 3.0 * cfg.ratio * cfg.spacing);
  const io::Scene s = make_scene(c, cfg);
  auto setup = sim::build_pd<3>(s);
  // λ_max to 1e-6 (relative change over 10 iterations) is ample under the 0.8 safety factor.
  return cache[key] = time::lanczos_step<3>(setup.system, *setup.model, 150, 1e-6).dt;
}

inline Metrics measure(const core::Particles<3>& p, const std::vector<std::uint8_t>& held, const analytic::SphericalWave& w,
                       double delta, double t, bool octant, const analytic::SphericalWave* lattice_wave) {
  Metrics m;
  m.t = t;
  const double edge = r0 + delta, front = w.front(t);
  double num = 0, den = 0, numv = 0, denv = 0, numl = 0, denl = 0;
  for (Index i = 0; i < p.n_real; ++i) {
    if (held[static_cast<std::size_t>(i)]) continue;
    const Vec<3>& x = p.x0[i];
    const double r = x.norm();
    if (x.cwiseAbs().maxCoeff() <= edge * (1 + 1e-12) || r > front) continue;
    const double ur = p.u[i].dot(x) / r, vr = p.v[i].dot(x) / r;
    const double ue = w.radial_displacement(r, t), ve = w.radial_velocity(r, t);
    double images = 1.0;
    if (octant)
      for (int a = 0; a < 3; ++a) images *= p.site[i][a] != 0 ? 2.0 : 1.0;
    num += images * (ur - ue) * (ur - ue);
    den += images * ue * ue;
    numv += images * (vr - ve) * (vr - ve);
    denv += images * ve * ve;
    m.max = std::max(m.max, std::abs(ur - ue) / amplitude);
    m.count += static_cast<long>(images);
    if (lattice_wave) {
      // Same particle set; the slower/faster wave's own front lies within it or
      // beyond it, where the closed form is zero.
      const double ul = lattice_wave->radial_displacement(r, t);
      numl += images * (ur - ul) * (ur - ul);
      denl += images * ul * ul;
    }
  }
  m.l2_lattice = denl > 0 ? std::sqrt(numl / denl) : 0.0;
  m.l2 = den > 0 ? std::sqrt(num / den) : 0.0;
  m.l2_velocity = denv > 0 ? std::sqrt(numv / denv) : 0.0;
  return m;
}

inline Result run(const Case& c, const Config& cfg) {
  Result res;
  reset_peak_rss();
  const double t0 = omp_get_wtime();
  const io::Scene s = make_scene(c, cfg);
  const auto w = exact_wave(s);
  res.cp = w.cp;
  auto lattice_wave = w;
  lattice_wave.cp *= cfg.lattice_speed_ratio;
  res.dt_stable = stable_step(c, cfg);
  const double t_build = omp_get_wtime();
  res.stable_step_seconds = t_build - t0;
  auto setup = sim::build_pd<3>(s);
  const auto& p = setup.system.particles;
  res.n_real = p.n_real;
  res.n_ghost = p.n_ghost();
  res.bonds = setup.system.families.n_bonds();
  std::vector<std::uint8_t> held(static_cast<std::size_t>(p.n_real), 0);
  for (const auto& con : setup.boundaries.constraints)
    for (Index i : con.particles) held[static_cast<std::size_t>(i)] = 1;
  res.n_free = res.n_real - static_cast<long>(std::count(held.begin(), held.end(), 1));

  // Δt divides the period, so every sample time (a multiple of T/…) is hit exactly.
  const auto per_period = static_cast<long long>(std::ceil(period / (cfg.safety * res.dt_stable)));
  res.dt = period / static_cast<double>(per_period);
  auto st = sim::make_simulation(setup);
  time::VelocityVerlet<3> stepper(st, res.dt);
  stepper.start();
  const double t1 = omp_get_wtime();
  res.setup_seconds = t1 - t_build;

  auto times = cfg.times;
  std::sort(times.begin(), times.end());
  for (double t : times) {
    const auto target = std::llround(t / res.dt);
    while (stepper.steps() < target) stepper.step(false);
    const double now = stepper.time();
    res.metrics.push_back(measure(p, held, w, s.delta, now, cfg.reading == Reading::octant,
                                  cfg.lattice_speed_ratio > 0 ? &lattice_wave : nullptr));
    if (cfg.keep_profiles) {
      Profile pr;
      pr.t = now;
      for (Index i = 0; i < p.n_real; ++i)
        if (p.site[i][1] == 0 && p.site[i][2] == 0 && p.x0[i][0] > 0) {
          pr.r.push_back(p.x0[i][0]);
          pr.u.push_back(p.u[i][0]);
          pr.exact.push_back(w.radial_displacement(p.x0[i][0], now));
        }
      std::vector<std::size_t> order(pr.r.size());
      for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
      std::sort(order.begin(), order.end(), [&](auto a, auto b) { return pr.r[a] < pr.r[b]; });
      Profile sorted{pr.t, {}, {}, {}};
      for (auto k : order) sorted.r.push_back(pr.r[k]), sorted.u.push_back(pr.u[k]), sorted.exact.push_back(pr.exact[k]);
      res.profiles.push_back(std::move(sorted));
    }
    if (cfg.keep_slices) {
      // Sites k = −K … K on both axes (the octant is mirrored: |v| is symmetric).
      const auto K = static_cast<int>(std::lround(cfg.extent / cfg.spacing));
      Slice sl;
      sl.t = now;
      sl.n = 2 * K + 1;
      sl.speed.assign(static_cast<std::size_t>(sl.n) * sl.n, std::nan(""));
      for (Index i = 0; i < p.n_real; ++i) {
        if (p.site[i][2] != 0) continue;
        const double sp = p.v[i].norm();
        const int kx = p.site[i][0], ky = p.site[i][1];
        for (int sx : {-1, 1})
          for (int sy : {-1, 1}) {
            if (cfg.reading == Reading::cube && (sx < 0 || sy < 0)) continue;
            const int X = sx * kx + K, Y = sy * ky + K;
            if (X < 0 || Y < 0 || X >= sl.n || Y >= sl.n) continue;
            sl.speed[static_cast<std::size_t>(sl.n - 1 - Y) * sl.n + X] = sp;
          }
      }
      res.slices.push_back(std::move(sl));
    }
  }
  res.steps = stepper.steps();
  res.run_seconds = omp_get_wtime() - t1;
  res.peak_rss_mb = peak_rss_mb();
  return res;
}

// ---- Lattice dispersion: why the error is what it is -------------------------
// A longitudinal plane wave u = A cos(k d·(x − x_c)) d on the infinite lattice
// has ρω²(k) A d = −f at x_c. The force on the centre particle of a block whose
// surfaces are farther than 2δ (LPS reaches 2δ through θ_j) is the infinite-
// lattice force, so one force evaluation gives ω²(k).
inline double omega_squared(const Case& c, double spacing, double ratio, pd::PartialVolume pv, double k, const Vec<3>& dir) {
  BlockSpec spec;
  spec.sites = 2 * (static_cast<int>(std::ceil(2.0 * ratio)) + 2) + 1;
  spec.spacing = spacing;
  spec.horizon_ratio = ratio;
  spec.influence = c.influence;
  spec.partial_volume = pv;
  spec.material = {youngs, c.nu, density};
  auto sys = make_block<3>(spec);
  auto model = pd::make_model<3>(c.model);
  model->initialise(sys);
  const Vec<3> centre = Vec<3>::Constant(0.5 * (spec.sites - 1) * spacing);
  const Vec<3> d = dir.normalized();
  const double A = 1e-9 * spacing;  // linear regime
  Index ic = 0;
  for (Index i = 0; i < sys.particles.n_real; ++i) {
    sys.particles.u[i] = A * std::cos(k * d.dot(sys.particles.x0[i] - centre)) * d;
    if ((sys.particles.x0[i] - centre).norm() < 0.5 * spacing) ic = i;
  }
  model->compute_forces(sys, {});
  return -sys.particles.f[ic].dot(d) / (density * A);
}

struct Dispersion {
  double speed_ratio = 0.0;     // phase speed / c_p of the wave the source drives, with velocity Verlet at Δt
  double long_wave_ratio = 0.0; // long-wave (k → 0) phase speed / c_p: the lattice's effective modulus
  double phase_error_l2 = 0.0;  // relative L2 error a pure phase lag would give at t (far field)
};

// The source drives frequency Ω = 2π/T. Velocity Verlet turns a lattice mode of
// frequency ω(k) into sin(Ω Δt/2) = ω(k) Δt/2, so the excited wave number k
// solves ω(k) = (2/Δt) sin(Ω Δt/2); its phase speed is Ω/k. A lag of phase
// speed gives, at distance r − r₀ from the source, a phase error
// Δφ = Ω (r − r₀)(1/c − 1/c_p); for a far field u ∝ 1/r and volume ∝ r² dr the
// relative L2 error of the lag alone is the root mean of 4 sin²(Δφ/2) over
// r₀ + δ … r₀ + c_p t (amplitude errors and the smeared front come on top).
inline Dispersion dispersion(const Case& c, double spacing, double ratio, pd::PartialVolume pv, double dt, double t,
                             const Vec<3>& dir = Vec<3>(1, 0, 0)) {
  Dispersion out;
  const double M = youngs * (1 - c.nu) / ((1 + c.nu) * (1 - 2 * c.nu));  // P-wave modulus λ + 2G
  const double cp = std::sqrt(M / density), Omega = 2.0 * std::numbers::pi / period;
  const double k_small = 1e-3 / (ratio * spacing);
  out.long_wave_ratio = std::sqrt(omega_squared(c, spacing, ratio, pv, k_small, dir)) / k_small / cp;
  const double target = dt > 0 ? 2.0 / dt * std::sin(0.5 * Omega * dt) : Omega;
  // Scan up from k = 0 for the first crossing, then bisect.
  const double k_exact = Omega / cp;
  double lo = 0.0, hi = 0.0;
  for (double k = 0.05 * k_exact;; k += 0.05 * k_exact) {
    if (std::sqrt(std::max(0.0, omega_squared(c, spacing, ratio, pv, k, dir))) >= target) {
      hi = k;
      break;
    }
    lo = k;
    if (k > 10 * k_exact) return out;  // no such mode: leave zeros
  }
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    (std::sqrt(std::max(0.0, omega_squared(c, spacing, ratio, pv, mid, dir))) >= target ? hi : lo) = mid;
  }
  const double k = 0.5 * (lo + hi), speed = Omega / k;
  out.speed_ratio = speed / cp;
  const double ra = r0 + ratio * spacing, rb = r0 + cp * t;
  double sum = 0.0;
  const int n = 400;
  for (int q = 0; q < n; ++q) {
    const double r = ra + (q + 0.5) * (rb - ra) / n;
    const double dphi = Omega * (r - r0) * (1.0 / speed - 1.0 / cp);
    sum += 4.0 * std::sin(0.5 * dphi) * std::sin(0.5 * dphi);
  }
  out.phase_error_l2 = std::sqrt(sum / n);
  return out;
}

}  // namespace pdmpm::test::wave
