// Gates of the adaptive SBPD–MPM hybrid (Noorian et al., adaptive SBPD–MPM §2,
// docs/models/hybrid.md): its limits (no PD particle: the MPM run; mode pd: the PD
// run), momentum across the coupling, a yielded particle's state across a
// conversion, thread invariance with regions moving, and the measurements not yet
// gated (ghost forces under affine motion, an edge crack against the all-PD run).
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/hybrid/conversion.hpp"
#include "solver/pd/damage.hpp"
#include "solver/sim/mpm_setup.hpp"
#include "solver/time/velocity_verlet.hpp"
#include "verification/support/gate.hpp"
#include "verification/support/hybrid_body.hpp"

namespace pdmpm {
namespace {

using core::ParticleKind;
using test::Compare;
using test::Gate;

const char* kProblem = "hybrid";
const char* kSource = "[noorian] §2 (coupling eq 10, regions eqs 11–12); docs/models/hybrid.md";
constexpr double kRho = 7850.0, kDx = 1e-3;
constexpr double kDt = 2e-8;  // below both stable steps (PD ≈ 6e-8 s, grid ≈ 1.6e-7 s at Δx = 1 mm)

// A smooth velocity field, large enough to yield within a hundred steps.
void kick_field(core::Particles<2>& p) {
  for (Index i = 0; i < p.n_real; ++i) {
    const Vec<2> x = p.x0[i];
    p.v[i] = Vec<2>(20.0 * std::sin(300 * x[1]) + 5.0, 15.0 * std::cos(250 * x[0]));
  }
}

// Particles whose displacement or velocity differ in any bit.
Index differing(const core::Particles<2>& a, const core::Particles<2>& b) {
  Index n = 0;
  for (Index i = 0; i < a.n_real; ++i) n += a.u[i] != b.u[i] || a.v[i] != b.v[i];
  return n;
}

TEST(FastHybrid, WithNoPdParticleItIsThePureMpmRunBitwise) {
  const test::HybridPlate plate;
  auto mpm_setup = sim::build_mpm<2>(plate.scene("mpm"));
  kick_field(mpm_setup.particles);
  mpm::Simulation<2> alone(mpm_setup.settings, mpm_setup.particles);
  test::HybridBody body(hybrid::Settings{}, plate);
  kick_field(body.particles());
  body.hybrid->start();
  ASSERT_EQ(body.hybrid->counts().mpm, body.particles().n_real);
  for (int s = 0; s < 100; ++s) {
    alone.step(kDt);
    body.hybrid->step(kDt);
  }
  double eq = 0.0;
  for (Index i = 0; i < body.particles().n_real; ++i) eq = std::max(eq, body.mpm->eq_plastic_strain(i));
  EXPECT_GT(eq, 0.0) << "the run must yield, or J2 is not exercised";
  test::record_gate(Gate{.id = "hybrid.limit.mpm_bitwise",
                         .claim = "a hybrid run in which no particle becomes PD shall equal the pure MPM run bitwise "
                                  "(GIMP/MUSL/J2 plate, yielding, 100 steps; particles differing in any bit of u or v)",
                         .measured = static_cast<double>(differing(body.particles(), mpm_setup.particles)),
                         .expected = 0.0,
                         .compare = Compare::at_most,
                         .tolerance_reason = "exact: with no PD particle the PD side evaluates nothing and the grid "
                                             "step is MPM's own",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
}

TEST(FastHybrid, ModePdIsThePurePdRunBitwise) {
  // A pre-crack and a critical stretch, so bond breaking is part of the comparison.
  test::HybridPlate plate;
  plate.pd_tables = "[[precrack]]\nfrom = [0.0, 0.0075]\nto = [0.01, 0.0075]\n";
  plate.pd_material_keys = "critical_stretch = 0.002";
  auto pd_alone = sim::build_pd<2>(plate.scene("pd"));
  kick_field(pd_alone.system.particles);
  auto alone = sim::make_simulation(pd_alone);
  time::VelocityVerlet<2> verlet(alone, kDt);
  verlet.start();
  hybrid::Settings settings;
  settings.mode = hybrid::Mode::pd;
  test::HybridBody body(settings, plate);
  kick_field(body.particles());
  body.hybrid->start();
  ASSERT_EQ(body.hybrid->counts().pd, body.particles().n_real);
  for (int s = 0; s < 100; ++s) {
    verlet.step(s % 10 == 0);
    body.hybrid->step(kDt, s % 10 == 0);
  }
  EXPECT_GT(alone.broken_bonds(), 0) << "bonds must break, or breaking is not compared";
  EXPECT_EQ(body.hybrid->internal_energy(), alone.internal_energy());
  test::record_gate(Gate{.id = "hybrid.limit.pd_bitwise",
                         .claim = "a hybrid run in mode \"pd\" shall equal the pure PD run (velocity Verlet, "
                                  "lps_plastic, pre-crack, critical stretch) bitwise over 100 steps",
                         .measured = static_cast<double>(differing(body.particles(), pd_alone.system.particles)),
                         .expected = 0.0,
                         .compare = Compare::at_most,
                         .tolerance_reason = "exact: the hybrid's step is velocity Verlet's sequence of operations",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
}

TEST(FastHybrid, CouplingConservesMomentum) {
  // The pre-crack's faces start PD with a region of R_pd = 1.5δ around them; the rest is
  // transition and MPM. Free body, no load: P + ½Δt Σ V f_transition is constant.
  hybrid::Settings settings;
  settings.mode = hybrid::Mode::expand;
  settings.radii = {.pd_radius = 1.5, .expand_trigger = 0.5, .expand_radius = 1.0, .keep_radius = 1.0};
  test::HybridPlate plate;
  plate.pd_tables = "[[precrack]]\nfrom = [0.012, 0.0075]\nto = [0.018, 0.0075]\n";
  test::HybridBody body(settings, plate);
  kick_field(body.particles());
  body.hybrid->start();
  const hybrid::KindCounts c = body.hybrid->counts();
  ASSERT_GT(c.pd, 0);
  ASSERT_GT(c.transition, 0);
  ASSERT_GT(c.mpm, 0);
  const Vec<2> p0 = body.hybrid->momentum();
  double scale = 0.0;  // Σ m|v|: what round-off in a momentum sum is relative to
  for (Index i = 0; i < body.particles().n_real; ++i)
    scale += kRho * body.particles().volume[i] * body.particles().v[i].norm();
  double worst = 0.0;
  for (int s = 0; s < 200; ++s) {
    body.hybrid->step(kDt);
    worst = std::max(worst, (body.hybrid->momentum() - p0).norm() / scale);
  }
  test::record_gate(Gate{.id = "hybrid.momentum.coupling",
                         .claim = "the paper's coupling (PD pair forces of transition particles into the grid, "
                                  "reactions on the PD particles) shall conserve linear momentum over 200 steps of a "
                                  "free PD | transition | MPM plate (drift relative to Σ m|v|)",
                         .measured = worst,
                         .expected = 1e-12,
                         .compare = Compare::at_most,
                         .tolerance_reason = "round-off of ~10⁴-term sums per step over 200 steps: 1e-12 leaves "
                                             "three decades above the measured 1e-15",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
}

TEST(FastHybrid, AYieldedBlockKeepsItsStateMpmToPdToMpm) {
  test::HybridBody body(hybrid::Settings{});
  auto& p = body.particles();
  body.hybrid->start();
  Mat<2> F;
  F << 1.003, 0.001, 0.0005, 0.999;
  for (Index i = 0; i < p.n_real; ++i) {
    p.u[i] = (F - Mat<2>::Identity()) * p.x0[i];
    body.mpm->set_deformation_gradient(i, F);
  }
  Index probe = -1;  // an interior particle, far from every face
  for (Index i = 0; i < p.n_real; ++i)
    if ((p.x0[i] - Vec<2>(0.015, 0.0075)).norm() < 0.6e-3) probe = i;
  ASSERT_GE(probe, 0);
  const Mat<3> stress0 = body.mpm->state().stress[probe];
  const mpm::PointHistory h0 = body.mpm->state().history[probe];
  ASSERT_GT(h0.eq_plastic_strain, 1e-3) << "the block must have yielded";

  for (Index i = 0; i < p.n_real; ++i) p.kind[i] = ParticleKind::pd;
  for (Index i = 0; i < p.n_real; ++i) hybrid::to_pd<2>(*body.mpm, body.pd_setup.system, body.pd->model(), i);
  body.pd->refresh_kinds();
  body.pd->internal_forces(false);
  body.pd->accept();
  for (Index i = 0; i < p.n_real; ++i) hybrid::to_mpm<2>(body.pd_setup.system, body.pd->model(), *body.mpm, i);
  const auto Fpd = hybrid::bond_deformation_gradient<2>(body.pd_setup.system, probe);
  ASSERT_TRUE(Fpd.has_value());
  EXPECT_LT((*Fpd - F).norm(), 1e-12) << "F from bonds is exact for an affine motion";

  const double stress_change = (body.mpm->state().stress[probe] - stress0).norm() / stress0.norm();
  test::record_gate(Gate{.id = "hybrid.conversion.stress",
                         .claim = "a homogeneously stretched, yielded block (ε̄_p = 1.9e-3) converted MPM → PD → MPM "
                                  "shall keep its stress within 1 % (interior particle)",
                         .measured = stress_change,
                         .expected = 0.01,
                         .compare = Compare::at_most,
                         .tolerance_reason = "the issue's bound; the PD force state is exact only to first order in "
                                             "the strain and its bond extensions are not MPM's log strain",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
  // The plastic strain may move by what the 1 % stress budget moves it on the hardening
  // line, 0.01 σ_eq/(3G + H): the PD evaluation in between flows a little further.
  const double G = 200e9 / 2.6, H = 200e9 * 2e9 / (200e9 - 2e9);
  const double budget = 0.01 * body.mpm->von_mises(probe) / (3.0 * G + H);
  const mpm::PointHistory h1 = body.mpm->state().history[probe];
  EXPECT_LT((h1.plastic_strain - h0.plastic_strain).norm(), std::sqrt(1.5) * budget);
  test::record_gate(Gate{.id = "hybrid.conversion.plastic_strain",
                         .claim = "the same round trip shall keep ε̄_p within 0.01 σ_eq/(3G + H), the plastic strain "
                                  "a 1 % stress error moves on the hardening line",
                         .measured = std::abs(h1.eq_plastic_strain - h0.eq_plastic_strain),
                         .expected = budget,
                         .compare = Compare::at_most,
                         .tolerance_reason = "consistent with the stress gate's 1 %",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
}

// A brittle edge crack (critical stretch, no yield) in a plate pulled at both edges
// (velocity ramped over 10 µs): the same scene in the three modes.
struct CrackRun {
  std::vector<double> t, front_x;  // furthest particle with φ > 0.35 (m)
  std::vector<double> tip_gap;     // distance from that particle to the nearest tracked tip (m)
  std::vector<int> far_tips;       // tracked tips farther than 3Δx from it (the crack has one end)
  std::vector<double> pd_count;
  hybrid::Events events;
  std::int64_t pd_steps = 0, mpm_steps = 0;
  hybrid::PhaseSeconds seconds;
  std::vector<ParticleKind> kinds;
  std::vector<Vec<2>> u;
  Index region_violations = 0;  // summed over the steps
  Index healed = 0;             // steps after which fewer bonds were broken than before
  Index damaged_reverted = 0;   // particle-steps: a PD particle with a broken bond that left PD
};

CrackRun run_edge_crack(hybrid::Mode mode, int steps, double speed) {
  hybrid::Settings s;
  s.mode = mode;
  s.radii = {.pd_radius = 2.0, .expand_trigger = 1.0, .expand_radius = 2.0, .keep_radius = 2.0};
  const std::string v = std::to_string(speed) + "*min(t/1e-5, 1)";
  const std::string pull =
      "[[boundary]]\nname = \"bottom\"\nkind = \"velocity\"\n"
      "region = { type = \"box\", min = [-1, -1], max = [1, 1.5e-3] }\n"
      "value = [\"free\", \"-" +
      v +
      "\"]\n"
      "[[boundary]]\nname = \"top\"\nkind = \"velocity\"\n"
      "region = { type = \"box\", min = [-1, 28.5e-3], max = [1, 1] }\n"
      "value = [\"free\", \"" +
      v + "\"]\n";
  test::HybridPlate plate;
  plate.size = {0.06, 0.03};
  plate.tables = pull;
  plate.pd_tables = "[[precrack]]\nfrom = [-1e-3, 0.0155]\nto = [0.015, 0.0155]\n";
  plate.pd_material_keys = "critical_stretch = 0.003";
  plate.hardening = "yield_stress = 1e12\ntangent_modulus = 0";
  test::HybridBody body(s, plate);
  body.hybrid->start();
  CrackRun r;
  const auto& p = body.particles();
  const auto& sys = body.pd_setup.system;
  auto broken_bonds = [&] {
    Index b = 0;
    for (BondIndex k = 0; k < sys.families.n_bonds(); ++k) b += sys.bonds.broken(k);
    return b;
  };
  Index broken = broken_bonds();
  std::vector<ParticleKind> before = p.kind;
  for (int n = 1; n <= steps; ++n) {
    body.hybrid->step(kDt);
    r.region_violations += body.hybrid->region_violations();
    const Index now = broken_bonds();
    r.healed += now < broken;
    broken = now;
    for (Index i = 0; i < p.n_real; ++i)
      if (before[i] == ParticleKind::pd && p.kind[i] != ParticleKind::pd && pd::particle_damage(sys, i) > 0.0)
        ++r.damaged_reverted;
    before = p.kind;
    if (n % 50 != 0) continue;
    Vec<2> front = Vec<2>::Zero();
    for (const Index i : body.pd->movers())
      if (pd::particle_damage(body.pd_setup.system, i) > 0.35 && p.x0[i][0] > front[0]) front = p.x0[i];
    double gap = std::numeric_limits<double>::infinity();
    int far = 0;
    for (const auto& c : body.hybrid->track_tips()) {
      gap = std::min(gap, (c.position - front).norm());
      far += (c.position - front).norm() > 3.0 * kDx;
    }
    r.far_tips.push_back(far);
    r.t.push_back(body.hybrid->time());
    r.front_x.push_back(front[0]);
    r.tip_gap.push_back(gap);
    r.pd_count.push_back(static_cast<double>(body.hybrid->counts().pd));
  }
  r.events = body.hybrid->events();
  r.pd_steps = body.hybrid->pd_particle_steps();
  r.mpm_steps = body.hybrid->mpm_particle_steps();
  r.seconds = body.hybrid->phase_seconds();
  r.kinds = p.kind;
  r.u = p.u;
  return r;
}

TEST(FastHybrid, ThreadCountDoesNotChangeARunWithMovingRegions) {
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const CrackRun one = run_edge_crack(hybrid::Mode::expand_shrink, 2000, 1.0);
  omp_set_num_threads(2);
  const CrackRun two = run_edge_crack(hybrid::Mode::expand_shrink, 2000, 1.0);
  omp_set_num_threads(threads);
  ASSERT_GT(one.events.to_pd, 0);
  ASSERT_GT(one.events.to_mpm, 0) << "regions must shrink, or conversions back are not compared";
  Index differ = 0;
  for (std::size_t i = 0; i < one.u.size(); ++i) differ += one.u[i] != two.u[i] || one.kinds[i] != two.kinds[i];
  test::record_gate(
      Gate{.id = "hybrid.thread_invariance",
           .claim = "a hybrid run with regions growing and shrinking (edge crack, 2000 steps) shall give "
                    "bitwise the same displacements and particle kinds on 1 and 2 threads",
           .measured = static_cast<double>(differ),
           .expected = 0.0,
           .compare = Compare::at_most,
           .tolerance_reason = "exact: every PD and MPM sum has a fixed order; region management is serial",
           .source = kSource,
           .unit = "",
           .problem = kProblem});
}

TEST(FastHybrid, EdgeCrackAgainstTheAllPdRun) {
  const int steps = 4000;
  const CrackRun pd = run_edge_crack(hybrid::Mode::pd, steps, 0.3);
  // The tracker against the damage front, in the all-PD run, once the crack runs.
  int samples = 0, with_false = 0;
  double worst = 0.0;
  for (std::size_t k = 0; k < pd.t.size(); ++k) {
    if (pd.front_x[k] <= 0.017) continue;
    ++samples;
    worst = std::max(worst, pd.tip_gap[k] / kDx);  // ∞ when no tip was found
    with_false += pd.far_tips[k] > 0;
  }
  ASSERT_GT(samples, 5) << "the crack must run";
  test::record_gate(Gate{.id = "hybrid.tips.follow_pd_crack",
                         .claim = "the crack-tip tracker shall find a tip within 2Δx of the damage front (furthest "
                                  "particle with φ > 0.35) of a running PD edge crack at every sample (every 50 steps)",
                         .measured = worst,
                         .expected = 2.0,
                         .compare = Compare::at_most,
                         .tolerance_reason = "the issue's bound: the front is known to ±Δx on the lattice, and the "
                                             "tip lies up to 1Δx ahead of the last particle with φ > 0.35",
                         .source = "[noorian] eqs 13–15",
                         .unit = "Δx",
                         .problem = kProblem});
  test::record_data(kProblem, "04_tip_tracking",
                    {{"kind", "table"},
                     {"title", "Crack-tip tracker on the running all-PD edge crack"},
                     {"columns",
                      {"samples (every 50 steps)", "largest gap front–nearest tip (Δx)",
                       "samples with a tip > 3Δx from the front (false tips)"}},
                     {"rows", {{samples, worst, with_false}}},
                     {"caption",
                      "Front: the furthest particle with φ > 0.35. False tips are not gated yet: a running "
                      "crack's damage band is several spacings wide and uneven, and a side lobe of it can "
                      "pass the crack-end test."}});

  nlohmann::json series = nlohmann::json::array(), rows = nlohmann::json::array();
  auto us = [](std::vector<double> t) {
    for (double& x : t) x *= 1e6;
    return t;
  };
  auto mm = [](std::vector<double> x) {
    for (double& v : x) v *= 1e3;
    return x;
  };
  series.push_back({{"label", "all PD"}, {"x", us(pd.t)}, {"y", mm(pd.front_x)}, {"style", "line"}});
  auto row = [&](const std::string& label, const CrackRun& r, double deviation) {
    const auto pd_steps = static_cast<double>(r.pd_steps), mpm_steps = static_cast<double>(r.mpm_steps);
    const double ns_pd = pd_steps > 0 ? 1e9 * r.seconds.pd / pd_steps : 0.0;
    const double ns_mpm = mpm_steps > 0 ? 1e9 * r.seconds.mpm / mpm_steps : 0.0;
    rows.push_back({label, deviation, r.events.to_pd, r.events.to_mpm, r.events.expansions, r.events.shrinks,
                    pd_steps / (pd_steps + mpm_steps), ns_pd, ns_mpm, r.seconds.coupling / r.seconds.total(),
                    r.seconds.regions / r.seconds.total()});
  };
  row("pd", pd, 0.0);
  Index violations = 0, healed = 0, damaged_reverted = 0;
  double region_share = 0.0;
  for (auto mode : {hybrid::Mode::expand, hybrid::Mode::expand_shrink}) {
    const CrackRun h = run_edge_crack(mode, steps, 0.3);
    violations += h.region_violations;
    healed += h.healed;
    damaged_reverted += h.damaged_reverted;
    region_share = std::max(region_share, h.seconds.regions / h.seconds.total());
    double deviation = 0.0;
    for (std::size_t k = 0; k < pd.t.size(); ++k)
      deviation = std::max(deviation, std::abs(h.front_x[k] - pd.front_x[k]) / kDx);
    series.push_back({{"label", std::string(name(mode))}, {"x", us(h.t)}, {"y", mm(h.front_x)}, {"style", "line"}});
    row(std::string(name(mode)), h, deviation);
  }
  test::record_gate(Gate{.id = "hybrid.regions.consistent",
                         .claim = "after every step of the edge-crack runs in modes expand and expand_shrink (8000 "
                                  "steps, regions growing and shrinking), every non-PD particle within bond reach of a "
                                  "PD particle shall be transition and no other, and removed particles shall be "
                                  "exactly the marked ones (particle-steps violating it)",
                         .measured = static_cast<double>(violations),
                         .expected = 0.0,
                         .compare = Compare::at_most,
                         .tolerance_reason = "exact: the classification is integer lattice arithmetic",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
  test::record_gate(Gate{.id = "hybrid.no_healing",
                         .claim =
                             "in the edge-crack runs in modes expand and expand_shrink (8000 steps, thousands of "
                             "conversions both ways) no broken bond shall ever be restored and no PD particle with "
                             "a broken bond shall leave PD (steps with fewer broken bonds + such departures)",
                         .measured = static_cast<double>(healed + damaged_reverted),
                         .expected = 0.0,
                         .compare = Compare::at_most,
                         .tolerance_reason = "exact: a broken bit is never cleared and shrink keeps damaged particles",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
  test::record_gate(Gate{.id = "hybrid.speed.region_share",
                         .claim = "region management (onset, expansion, tips, shrink, conversions, bond refresh) shall "
                                  "take at most 5 % of the wall time of a hybrid step (edge crack, modes expand and "
                                  "expand_shrink, the larger share)",
                         .measured = region_share,
                         .expected = 0.05,
                         .compare = Compare::at_most,
                         .tolerance_reason = "the issue's bound; a ratio of times in one process",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
  test::record_data(kProblem, "02_edge_crack_front",
                    {{"kind", "plot"},
                     {"title", "Edge crack: crack front against time, three modes of one scene"},
                     {"xlabel", "t (µs)"},
                     {"ylabel", "furthest particle with φ > 0.35 (mm)"},
                     {"xscale", "linear"},
                     {"yscale", "linear"},
                     {"series", series},
                     {"caption",
                      "60 × 30 mm plate, Δx = 1 mm, δ = 3.015Δx, edge pre-crack to x = 15 mm, edges pulled "
                      "at 0.3 m/s (ramp 10 µs), critical stretch 0.003, no yield; regions R_pd = l_ext = "
                      "l_con = 2δ, l_crit = δ (small for a small plate). Not gated yet: the paper's coupling "
                      "leaves ghost forces at the interface (table 01), and the hybrid cracks run ahead of "
                      "the all-PD crack once the front meets the region's edge."}});
  test::record_data(kProblem, "03_edge_crack_runs",
                    {{"kind", "table"},
                     {"title", "Edge crack: the three modes"},
                     {"columns",
                      {"mode", "max front deviation (Δx)", "MPM→PD", "PD→MPM", "expansions", "shrinks",
                       "PD share of particle-steps", "ns per PD particle-step", "ns per MPM particle-step",
                       "coupling share of wall time", "region share of wall time"}},
                     {"rows", rows},
                     {"caption",
                      "One process, one thread count. The cost per particle-step of each method, measured "
                      "in the same runs, decides how much the hybrid can save."}});
}

// Accelerations of an affine displacement u = H x (no velocity) after one tiny step,
// relative to σ/(ρΔx), the acceleration of a particle on a free face carrying the
// affine state's traction; particles within 4Δx of the plate's edges are skipped (a
// free edge is not in equilibrium under an affine field).
struct GhostForces {
  double pd = 0.0, transition = 0.0, mpm = 0.0;
};

GhostForces ghost_forces(const Mat<2>& H, bool with_pd) {
  GhostForces g;
  const Vec<2> size(0.04, 0.03), centre = 0.5 * size;
  hybrid::Settings s;
  s.mode = hybrid::Mode::expand;
  test::HybridPlate plate;
  plate.size = {size[0], size[1]};
  test::HybridBody body(s, plate);
  auto& p = body.particles();
  std::vector<Index> disc;
  for (Index i = 0; i < p.n_real; ++i) {
    p.u[i] = H * p.x0[i];
    body.mpm->set_deformation_gradient(i, Mat<2>::Identity() + H);
    if (with_pd && (p.x0[i] - centre).norm() < 7e-3) disc.push_back(i);
  }
  body.hybrid->start(disc);
  const double a_scale = body.mpm->state().stress[0].norm() / (kRho * kDx);
  const double dt = 1e-13;
  body.hybrid->step(dt);
  for (Index i = 0; i < p.n_real; ++i) {
    const Vec<2> x = p.x0[i];
    if (x[0] < 4 * kDx || x[1] < 4 * kDx || x[0] > size[0] - 4 * kDx || x[1] > size[1] - 4 * kDx) continue;
    const double a = p.v[i].norm() / dt / a_scale;
    double& worst = p.kind[i] == ParticleKind::pd ? g.pd : p.kind[i] == ParticleKind::transition ? g.transition : g.mpm;
    worst = std::max(worst, a);
  }
  return g;
}

TEST(FastHybrid, GhostForcesUnderAffineMotion) {
  Mat<2> stretch, shear;
  stretch << 1e-4, 0.0, 0.0, -0.3e-4;
  shear << 0.0, 1e-4, 1e-4, 0.0;
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& [label, H] : {std::pair{"stretch", stretch}, std::pair{"shear", shear}}) {
    const GhostForces g = ghost_forces(H, true), mpm_only = ghost_forces(H, false);
    rows.push_back({label, g.pd, g.transition, g.mpm, mpm_only.mpm});
    EXPECT_LT(mpm_only.mpm, 1e-12) << "the all-MPM body is in equilibrium under an affine motion";
  }
  test::record_data(kProblem, "01_ghost_forces",
                    {{"kind", "table"},
                     {"title", "Ghost forces of the paper's coupling under affine motion"},
                     {"columns", {"motion", "PD", "transition", "MPM", "all MPM"}},
                     {"rows", rows},
                     {"caption",
                      "Largest acceleration of interior particles of each kind relative to σ/(ρΔx) (a free "
                      "face's particle under the same stress), 40 × 30 mm plate, PD disc of radius 7 mm. The "
                      "transition particles' PD state comes from half a family and the grid sees a hole "
                      "where the PD region is: the residual is of the order of a free face's traction. Not "
                      "gated: a consistent coupling is the next step (docs/models/hybrid.md)."}});
}

}  // namespace
}  // namespace pdmpm
