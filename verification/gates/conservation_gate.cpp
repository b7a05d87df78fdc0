// Conservation in free bodies (no supports, no loads), velocity Verlet.
//
// Linear momentum (fracturing plate/block torn apart by its initial velocity):
// the solver gathers each particle's force from its own family, and the pair
// term of bond (i, j) is computed from ξ, u_j − u_i and the table entry of the
// offset, all of which change sign exactly for (j, i). So the pair terms are
// bitwise antisymmetric and Σ V_i f_i = 0 up to the rounding of the family sums
// and of the velocity updates. The gate compares the momentum change with the
// worst-case bound of that rounding, accumulated over the run.
//
// Angular momentum (spinning disk/ball): PD pair forces act along the deformed
// bond y = ξ + η (PMB and LPS alike), so the pair torques cancel, and velocity
// Verlet conserves Σ m x × v exactly for such forces (kick: torque-free; drift:
// x_{n+1} × v = x_n × v). What is left is rounding; gated against its bound.
//
// Energy: velocity Verlet is symplectic; for the linear(ised) system it conserves
// the shadow energy I_h = K + U − (Δt²/8) Σ V |f|²/ρ exactly (one line of algebra per
// normal mode), while E = K + U = I_h + (Δt²/8) Σ V |f|²/ρ oscillates, bounded, with
// no secular drift. 10⁴ steps at 0.8 of the Lanczos stable step.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "solver/io/scene.hpp"
#include "solver/pd/bond_kinematics.hpp"
#include "solver/pd/constants.hpp"
#include "solver/pd/lps.hpp"
#include "solver/sim/pd_setup.hpp"
#include "solver/time/velocity_verlet.hpp"
#include "solver/time/stable_step.hpp"
#include "verification/support/gate.hpp"
#include "verification/support/scene_text.hpp"

namespace pdmpm {
namespace {

using nlohmann::json;
constexpr double unit_roundoff = std::numeric_limits<double>::epsilon() / 2;

std::string dim_name(int D) { return D == 2 ? "2d" : "3d"; }

// A free body: plane-stress plate nx × ny (2D) or block nx × ny × nz (3D), Δx = 1 mm.
std::string body_scene(const std::string& model, int D, const std::string& shape, double critical_stretch,
                       const std::string& material_keys) {
  std::string s = "[scene]\nid = \"conservation\"\n[discretization]\ndimension = " + std::to_string(D) +
      "\nspacing = 1e-3\nhorizon_ratio = " + std::to_string(test::gate_horizon_ratio(model, D)) + "\n";
  if (D == 2) s += "plane = \"stress\"\nthickness = 1e-3\n";
  s += shape;
  s += "[material]\ndensity = 7850\nyoungs_modulus = 200e9\n";
  if (!pd::model_info(model).pair_potential) s += "poissons_ratio = 0.3\n";
  if (critical_stretch > 0) s += "critical_stretch = " + std::to_string(critical_stretch) + "\n";
  s += material_keys;
  s += "[model]\ntype = \"" + model + "\"\n[time]\nsteps = 1\n";
  return s;
}

std::string box(int D, int nx, int ny, int nz) {
  const double dx = 1e-3;
  if (D == 2)
    return "[[shape]]\ntype = \"box\"\nmin = [0, 0]\nmax = [" + std::to_string(nx * dx) + ", " +
        std::to_string(ny * dx) + "]\n";
  return "[[shape]]\ntype = \"box\"\nmin = [0, 0, 0]\nmax = [" + std::to_string(nx * dx) + ", " +
      std::to_string(ny * dx) + ", " + std::to_string(nz * dx) + "]\n";
}

std::string ball(int D, double radius) {
  const std::string c = D == 2 ? "[0, 0]" : "[0, 0, 0]";
  return "[[shape]]\ntype = \"ball\"\ncenter = " + c + "\nradius = " + std::to_string(radius) + "\n";
}

// Σ_j |pair term| of every particle (the quantities whose rounding the family
// sum commits), for the models whose pair term we know; otherwise |f_i|, which
// is not a rigorous bound (reported).
template <int D>
bool absolute_pair_sums(sim::PdSetup<D>& s, std::vector<double>& A) {
  auto& sys = s.system;
  const auto& p = sys.particles;
  const auto& fam = sys.families;
  const auto& t = sys.table;
  A.assign(p.n_real, 0.0);
  const std::string name = s.model->name();
  if (name == "pmb") {
    const double c = pd::pmb_micromodulus(sys.influence, sys.setting, sys.material, sys.delta, sys.measure);
    for (Index i = 0; i < p.n_real; ++i)
      for (BondIndex b = fam.begin(i); b < fam.end(i); ++b) {
        if (!sys.bonds.live(b)) continue;
        const int k = fam.shape[b];
        const Index j = fam.neighbor[b];
        const auto bond = pd::deform<D>(t.xi[k], t.length[k], p.u[j] - p.u[i]);
        A[i] += c * t.weight[k] * p.volume[j] * std::abs(bond.e / t.length[k]);
      }
    return true;
  }
  if (name == "lps") {
    const auto& lps = dynamic_cast<const pd::Lps<D>&>(*s.model);
    const auto& m = lps.weighted_volume();
    std::vector<double> theta;
    lps.dilatation(sys, theta);
    theta.resize(p.size());
    for (Index g = 0; g < p.n_ghost(); ++g) theta[p.n_real + g] = theta[p.ghost_owner[g]];
    const auto k = pd::lps_coefficients(sys.setting, sys.material);
    for (Index i = 0; i < p.n_real; ++i)
      for (BondIndex b = fam.begin(i); b < fam.end(i); ++b) {
        if (!sys.bonds.live(b)) continue;
        const int s2 = fam.shape[b];
        const Index j = fam.neighbor[b];
        const double L = t.length[s2];
        const auto bond = pd::deform<D>(t.xi[s2], L, p.u[j] - p.u[i]);
        const double tij = m[i] > 0 ? (k.A * theta[i] * L + k.B * bond.e) / m[i] : 0.0;
        const double tji = m[j] > 0 ? (k.A * theta[j] * L + k.B * bond.e) / m[j] : 0.0;
        A[i] += std::abs(tij + tji) * t.weight[s2] * p.volume[j];
      }
    return true;
  }
  for (Index i = 0; i < p.n_real; ++i) A[i] = p.f[i].norm();
  return false;
}

template <int D>
int max_family(const pd::System<D>& sys) {
  BondIndex n = 0;
  for (Index i = 0; i < sys.n_real(); ++i) n = std::max(n, sys.families.end(i) - sys.families.begin(i));
  return static_cast<int>(n);
}

// ---------------------------------------------------------------------------
// Linear and angular momentum.

struct MomentumRun {
  double drift = 0.0, bound = 0.0, scale = 0.0;  // max |ΔP| (or |ΔL|), rounding bound, Σ|p| (or Σ|x×p|)
  std::int64_t broken = 0;
  int steps = 0;
  bool rigorous = true;
};

template <int D>
MomentumRun momentum_run(const std::string& model, bool spin, int steps, std::vector<double>* series_t,
                         std::vector<double>* series_drift) {
  const std::string shape = spin ? ball(D, D == 2 ? 8e-3 : 4.5e-3) : box(D, D == 2 ? 40 : 16, D == 2 ? 20 : 8, 8);
  // Fracture: s₀ = 1e-3; the tearing velocity jump 2V = 40 m/s gives a stress of ~ρcV ≈ 0.8 GPa, strain ≈ 4e-3.
  auto setup = sim::build_pd<D>(
      io::parse_scene_text(body_scene(model, D, shape, spin ? 0.0 : 1e-3, test::flowing_keys(model)), "conservation"));
  auto& p = setup.system.particles;
  const double V = 20.0, spin_rate = 2e4;  // m/s; rad/s (rim speed 160 m/s in 2D, 90 m/s in 3D)
  Vec<D> drift = Vec<D>::Zero();
  drift[0] = 3.0, drift[1] = -2.0;
  const double xc = D == 2 ? 20e-3 : 8e-3;  // mid-length of the body
  for (Index i = 0; i < p.n_real; ++i) {
    const Vec<D> x = p.x0[i];
    if (spin) {
      // v = Ω × x about z (2D) / about the general axis (1,2,3)/√14 (3D).
      Eigen::Vector3d x3 = Eigen::Vector3d::Zero();
      for (int a = 0; a < D; ++a) x3[a] = x[a];
      const Eigen::Vector3d axis = D == 2 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d(1, 2, 3).normalized();
      const Eigen::Vector3d v3 = spin_rate * axis.cross(x3);
      for (int a = 0; a < D; ++a) p.v[i][a] = v3[a];
    } else {
      p.v[i] = drift;
      p.v[i][0] += V * std::tanh((x[0] - xc) / 2e-3);
    }
  }
  auto st = sim::make_simulation(setup);
  const double dt = 0.8 * time::silling_askari_step<D>(setup.system, *setup.model);
  time::VelocityVerlet<D> stepper(st, dt);
  stepper.start();
  const double rho = st.density();
  const int nb = max_family(setup.system);
  const auto P0 = st.momentum();
  const auto L0 = st.angular_momentum();
  auto abs_sums = [&](double& sv, double& sxv, double& suv) {
    sv = sxv = suv = 0.0;
    for (Index i = 0; i < p.n_real; ++i) {
      sv += rho * p.volume[i] * p.v[i].norm();
      sxv += rho * p.volume[i] * p.position(i).norm() * p.v[i].norm();
      suv += rho * p.volume[i] * p.u[i].norm() * p.v[i].norm();
    }
  };
  double sv, sxv, suv;
  abs_sums(sv, sxv, suv);
  MomentumRun r;
  r.steps = steps;
  r.scale = spin ? sxv : sv;
  const double n = p.n_real;
  // Rounding of the final sums Σ V v (and Σ x × V v), at t and at 0.
  const double sum_rounding = 2.0 * n * unit_roundoff * (spin ? sxv : sv);
  double accumulated = 0.0;
  std::vector<double> A;
  for (int k = 1; k <= steps; ++k) {
    r.rigorous = absolute_pair_sums(setup, A) && r.rigorous;
    double SA = 0.0, SxA = 0.0;
    for (Index i = 0; i < p.n_real; ++i) SA += p.volume[i] * A[i], SxA += p.volume[i] * p.position(i).norm() * A[i];
    abs_sums(sv, sxv, suv);
    // One step: two half kicks of ½Δt f/ρ (family sums of ≤ nb terms: (nb + 3)u Σ_j|term| each,
    // times ½Δt; for L also the lever arm and the rounding of x_i − x_j vs y, 2u|x|), two rounded
    // velocity updates (u|v| each), for L the rounded drift u += Δt v (u|u||v|).
    if (spin)
      accumulated += unit_roundoff * ((nb + 5) * dt * SxA + 2.0 * sxv + suv);
    else
      accumulated += unit_roundoff * ((nb + 3) * dt * SA + 2.0 * sv);
    stepper.step(false);
    const double d = spin ? (st.angular_momentum() - L0).norm() : (st.momentum() - P0).norm();
    r.drift = std::max(r.drift, d);
    if (series_t && k % 20 == 0) {
      series_t->push_back(stepper.time());
      series_drift->push_back(d / r.scale);
    }
  }
  r.bound = accumulated + sum_rounding;
  r.broken = st.broken_bonds();
  return r;
}

template <int D>
void momentum_gates(bool spin) {
  json rows = json::array();
  json plot = {
      {"kind", "plot"},         {"title", std::string(spin ? "Angular" : "Linear") + " momentum drift, " + dim_name(D)},
      {"xlabel", "t [s]"},      {"ylabel", spin ? "|L(t) − L(0)| / Σ ρV|x||v|" : "|P(t) − P(0)| / Σ ρV|v|"},
      {"xscale", "linear"},     {"yscale", "log"},
      {"series", json::array()}};
  for (const auto& model : pd::model_names()) {
    std::vector<double> t, d;
    const int steps = D == 2 ? 1500 : 600;
    const auto r = momentum_run<D>(model, spin, steps, &t, &d);
    const std::string id =
        std::string("conservation.") + (spin ? "angular_momentum." : "linear_momentum.") + model + "." + dim_name(D);
    if (!spin) {
      EXPECT_GT(r.broken, 100) << "the body did not fracture: the momentum claim would not be tested";
    }
    rows.push_back({model, dim_name(D), r.steps, r.broken, r.drift / r.scale, r.bound / r.scale, r.drift / r.bound,
                    r.rigorous ? "yes" : "no (|f_i| used)"});
    plot["series"].push_back({{"label", model}, {"x", t}, {"y", d}, {"style", "line"}});
    test::record_gate(
        {.id = id,
         .claim = spin ? "In a free spinning " + std::string(D == 2 ? "disk" : "ball") + " (" + model +
                 ", no damage) the angular momentum shall be conserved to rounding over " + std::to_string(r.steps) +
                 " Verlet steps (measured: max |L(t) − L(0)| / Σρ V|x||v|)"
                       : "In a free " + std::string(D == 2 ? "plate" : "block") + " (" + model +
                 ") torn apart by its initial velocity (" + std::to_string(r.broken) +
                 " bonds broken) the linear momentum shall be conserved to rounding over " + std::to_string(r.steps) +
                 " Verlet steps (measured: max |P(t) − P(0)| / Σρ V|v|)",
         .measured = r.drift / r.scale,
         .expected = r.bound / r.scale,
         .tolerance = 0.0,
         .compare = test::Compare::at_most,
         .tolerance_reason = spin
             ? "Pair forces act along the deformed bond, so pair torques cancel and Verlet conserves Σ m x × v "
               "exactly; the bound is the worst-case rounding accumulated over the run: per step (n_b + 5)u Δt "
               "Σ_i V|x_i| Σ_j|pair term| (family sums, lever arm, x_i − x_j vs y) + 2u Σ ρV|x||v| (velocity "
               "updates) + u Σ ρV|u||v| (drift), plus 2Nu Σ ρV|x||v| for the final sums."
             : "The pair terms are bitwise antisymmetric, so only rounding changes P; the bound is its worst case "
               "accumulated over the run: per step (n_b + 3)u Δt Σ_i V Σ_j|pair term| (family sums of ≤ n_b terms) "
               "+ 2u Σ ρV|v| (velocity updates), plus 2Nu Σ ρV|v| for the final sums.",
         .source =
             "Newton's third law for PD pair forces ([silling2000]; [silling2007] §4 for states); velocity Verlet "
             "conserves linear and angular momentum of central pair forces (Hairer, Lubich & Wanner, Geometric "
             "Numerical Integration, §IV.1)",
         .unit = "",
         .problem = "conservation"});
  }
  test::record_data("conservation", std::string(spin ? "angular_" : "linear_") + dim_name(D),
                    {{"kind", "table"},
                     {"title", std::string(spin ? "Angular" : "Linear") + " momentum, " + dim_name(D)},
                     {"columns",
                      {"model", "dim", "steps", "bonds broken", "max drift / scale", "rounding bound / scale",
                       "drift / bound", "bound rigorous"}},
                     {"rows", rows},
                     {"caption",
                      spin ? "Spinning disk (R = 8 mm) / ball (R = 4.5 mm), Ω = 2e4 rad/s (3D about (1,2,3)/√14), "
                             "Δt = 0.8 × Silling–Askari. Scale Σ ρV|x||v|."
                           : "Plate 40 × 20 mm (2D) / block 16 × 8 × 8 mm (3D), v_x = 20 tanh((x − x_c)/2 mm) m/s "
                             "plus a drift (3, −2) m/s, s₀ = 1e-3, Δt = 0.8 × Silling–Askari. Scale Σ ρV|v|."}});
  test::record_data("conservation", std::string(spin ? "angular_plot_" : "linear_plot_") + dim_name(D), plot);
}

TEST(FastConservation, LinearMomentumFracturing2d) { momentum_gates<2>(false); }
TEST(FastConservation, LinearMomentumFracturing3d) { momentum_gates<3>(false); }
TEST(FastConservation, AngularMomentumSpinning2d) { momentum_gates<2>(true); }
TEST(FastConservation, AngularMomentumSpinning3d) { momentum_gates<3>(true); }

// ---------------------------------------------------------------------------
// Energy: 10⁴ steps at 0.8 × the Lanczos stable step.

// Least-squares slope of y(t).
double slope(const std::vector<double>& t, const std::vector<double>& y) {
  double st = 0, sy = 0, stt = 0, sty = 0;
  const double n = static_cast<double>(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) st += t[k], sy += y[k], stt += t[k] * t[k], sty += t[k] * y[k];
  return (n * sty - st * sy) / (n * stt - st * st);
}

template <int D>
void energy_gates() {
  json rows = json::array();
  for (const auto& model : pd::model_names()) {
    auto setup = sim::build_pd<D>(io::parse_scene_text(
        body_scene(model, D, D == 2 ? box(2, 30, 15, 0) : box(3, 9, 8, 7), 0.0, test::elastic_range_keys(model)),
        "energy"));
    auto& p = setup.system.particles;
    const double a = 5e-3;  // m/s: strains ~ a/c ≈ 1e-6, so the body stays linear to ~1e-6
    for (Index i = 0; i < p.n_real; ++i) {
      const Vec<D> x = p.x0[i] / 1e-3;
      for (int c = 0; c < D; ++c) p.v[i][c] = a * std::sin(0.31 * x[(c + 1) % D] + 0.7 * c) * std::cos(0.23 * x[c]);
    }
    auto st = sim::make_simulation(setup);
    const auto lz = time::lanczos_step<D>(setup.system, *setup.model);
    const double dt = 0.8 * lz.dt;
    time::VelocityVerlet<D> stepper(st, dt);
    stepper.start();
    const double rho = st.density();
    auto shadow_term = [&] {
      double s = 0.0;
      for (Index i = 0; i < p.n_real; ++i) s += p.volume[i] * p.f[i].squaredNorm();
      return dt * dt / 8.0 * s / rho;
    };
    const double E0 = st.kinetic_energy() + st.internal_energy();
    const double I0 = E0 - shadow_term();
    const int steps = 10000;
    std::vector<double> t, E, I;
    double shadow_dev = 0.0, gmin = 1e300, gmax = -1e300, emax = 0.0;
    for (int k = 1; k <= steps; ++k) {
      stepper.step(true);
      const double e = st.kinetic_energy() + st.internal_energy();
      const double g = shadow_term();
      t.push_back(stepper.time());
      E.push_back(e / E0 - 1.0);
      I.push_back((e - g - I0) / E0);
      shadow_dev = std::max(shadow_dev, std::abs(e - g - I0) / E0);
      gmin = std::min(gmin, g / E0), gmax = std::max(gmax, g / E0);
      emax = std::max(emax, std::abs(e / E0 - 1.0));
    }
    const double T = t.back();
    const double drift_E = std::abs(slope(t, E)) * T, drift_I = std::abs(slope(t, I)) * T;
    const std::string id = "conservation.energy." + model + "." + dim_name(D);
    // Largest bond strain scale: a/c with c the longitudinal speed.
    const double c_long = std::sqrt(setup.system.material.wave_modulus(setup.system.setting) / rho);
    const double strain = a / c_long * std::sqrt(static_cast<double>(D));
    test::record_gate(
        {.id = id + ".shadow",
         .claim = "Over 10⁴ velocity-Verlet steps at 0.8 × the Lanczos stable step (" + model + ", " + dim_name(D) +
             ", free body, smooth initial velocity) the shadow energy K + U − (Δt²/8)ΣV|f|²/ρ shall "
             "stay constant (measured: max deviation / E₀)",
         .measured = shadow_dev,
         .expected = 0.0,
         .tolerance = 10.0 * strain,
         .compare = test::Compare::abs,
         .tolerance_reason =
             "For the linearised system the shadow energy is an exact invariant of velocity Verlet; the PD "
             "kinematics add relative terms of the order of the strain (≈ a/c_p √D = " +
             std::to_string(strain) +
             "), and the Δt² correction multiplies them by ≤ 0.64. 10 × strain covers the constants; "
             "a secular drift of a non-symplectic scheme would grow with the 10⁴ steps instead.",
         .source = "[hairer2006] §IX (modified energy); derivation in "
                   "conservation_gate.cpp",
         .unit = "",
         .problem = "conservation"});
    test::record_gate(
        {.id = id + ".drift",
         .claim = "Over the same run the fitted drift of E = K + U (least-squares slope × duration / E₀) shall "
                  "not exceed what a bounded oscillation of the measured amplitude can produce",
         .measured = drift_E,
         .expected = 1.5 * (gmax - gmin) + drift_I,
         .tolerance = 0.0,
         .compare = test::Compare::at_most,
         .tolerance_reason =
             "E = I_h + g(t) with g = (Δt²/8)ΣV|f|²/ρ ∈ [g_min, g_max]; the least-squares slope of a signal "
             "confined to a band of width a over a window T satisfies |b|T ≤ 1.5a (Σ|t − t̄| / Σ(t − t̄)² = "
             "3/T), so |b_E|T ≤ 1.5(g_max − g_min) + |b_I|T. A secular drift would exceed it.",
         .source = "Velocity Verlet: bounded energy error, no drift ([hairer2006] §IX.8)",
         .unit = "",
         .problem = "conservation"});
    rows.push_back(
        {model, dim_name(D), p.n_real, dt, lz.dt, steps, T, emax, gmax - gmin, shadow_dev, drift_E, drift_I});
    json plot = {
        {"kind", "plot"},         {"title", "Energy over 10⁴ steps at 0.8 Δt_crit, " + model + ", " + dim_name(D)},
        {"xlabel", "t [s]"},      {"ylabel", "relative to E₀"},
        {"xscale", "linear"},     {"yscale", "linear"},
        {"series", json::array()}};
    std::vector<double> ts, Es, Is;
    for (std::size_t k = 0; k < t.size(); k += 20) ts.push_back(t[k]), Es.push_back(E[k]), Is.push_back(I[k]);
    plot["series"].push_back({{"label", "E/E₀ − 1"}, {"x", ts}, {"y", Es}, {"style", "line"}});
    plot["series"].push_back({{"label", "(I_h − I_h(0))/E₀"}, {"x", ts}, {"y", Is}, {"style", "line"}});
    test::record_data("conservation", "energy_plot_" + model + "_" + dim_name(D), plot);
  }
  test::record_data("conservation", "energy_" + dim_name(D),
                    {{"kind", "table"},
                     {"title", "Energy over 10⁴ Verlet steps at 0.8 × Lanczos step, " + dim_name(D)},
                     {"columns",
                      {"model", "dim", "particles", "Δt [s]", "Lanczos Δt_crit [s]", "steps", "duration [s]",
                       "max |E/E₀ − 1|", "oscillation band of E (g_max − g_min)/E₀", "max |I_h − I_h(0)|/E₀",
                       "fitted drift of E (|b|T/E₀)", "fitted drift of I_h"}},
                     {"rows", rows},
                     {"caption",
                      "Free plate 30 × 15 mm (plane stress) / block 9 × 8 × 7 mm, smooth initial velocity of "
                      "amplitude 5 mm/s, no damage. I_h = K + U − (Δt²/8)ΣV|f|²/ρ."}});
}

TEST(FastConservation, Energy2d) { energy_gates<2>(); }
TEST(FastConservation, Energy3d) { energy_gates<3>(); }

}  // namespace
}  // namespace pdmpm
