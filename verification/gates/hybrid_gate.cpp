// Gates of the adaptive SBPD–MPM hybrid (Noorian et al., adaptive SBPD–MPM §2,
// docs/models/hybrid.md): its limits (no PD particle: the MPM run; mode pd: the PD
// run), momentum across the coupling and through conversions, a yielded particle's
// state across a conversion, the energy conversions change, thread invariance with
// regions moving, an edge crack against the all-PD run, waves across the interface, and
// what is measured but not gated (the paper coupling's ghost forces, the grips' effect).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>

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
// The shrink's residual bound of the energy-consistent runs (hybrid.revert_residual): on the
// edge crack it costs one to two points of PD share (table 07).
constexpr double kRevertResidual = 0.1;
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

// The pre-crack's faces start PD with a region of R_pd = 1.5δ around them; the rest is
// transition and MPM. Free body, no load: P + ½Δt Σ V f_transition is constant. Returns the
// largest drift over 200 steps relative to Σ m|v| (what round-off in a momentum sum is relative to).
double momentum_drift(hybrid::Coupling coupling) {
  hybrid::Settings settings;
  settings.mode = hybrid::Mode::expand;
  settings.coupling = coupling;
  settings.radii = {.pd_radius = 1.5, .expand_trigger = 0.5, .expand_radius = 1.0, .keep_radius = 1.0};
  test::HybridPlate plate;
  plate.pd_tables = "[[precrack]]\nfrom = [0.012, 0.0075]\nto = [0.018, 0.0075]\n";
  // The blended band (two bond reaches and 2δ beyond the region) would cover the default plate.
  if (coupling == hybrid::Coupling::blended) plate.size = {0.06, 0.04};
  test::HybridBody body(settings, plate);
  kick_field(body.particles());
  body.hybrid->start();
  const hybrid::KindCounts c = body.hybrid->counts();
  EXPECT_GT(c.pd, 0);
  EXPECT_GT(c.transition, 0);
  EXPECT_GT(c.mpm, 0);
  const Vec<2> p0 = body.hybrid->momentum();
  double scale = 0.0;
  for (Index i = 0; i < body.particles().n_real; ++i)
    scale += kRho * body.particles().volume[i] * body.particles().v[i].norm();
  double worst = 0.0;
  for (int s = 0; s < 200; ++s) {
    body.hybrid->step(kDt);
    worst = std::max(worst, (body.hybrid->momentum() - p0).norm() / scale);
  }
  return worst;
}

TEST(FastHybrid, CouplingConservesMomentum) {
  struct Case {
    hybrid::Coupling coupling;
    const char *id, *claim;
  };
  for (const Case& c :
       {Case{hybrid::Coupling::paper, "hybrid.momentum.coupling",
             "the paper's coupling (PD pair forces of transition particles into the grid, reactions on the PD "
             "particles) shall conserve linear momentum over 200 steps of a free PD | transition | MPM plate (drift "
             "relative to Σ m|v|)"},
        Case{hybrid::Coupling::full_state, "hybrid.momentum.coupling_full_state",
             "so shall the full-state coupling (a transition particle's bonds to grid particles count in its state "
             "and exchange no force), on the same plate"},
        Case{hybrid::Coupling::blended, "hybrid.momentum.coupling_blended",
             "so shall the blended coupling (the grid's stress weighted by 1 − β, each force state by its owner's "
             "β over a band), on the same plate"}})
    test::record_gate(Gate{.id = c.id,
                           .claim = c.claim,
                           .measured = momentum_drift(c.coupling),
                           .expected = 1e-12,
                           .compare = Compare::at_most,
                           .tolerance_reason = "round-off of ~10⁴-term sums per step over 200 steps: 1e-12 leaves "
                                               "three decades above the measured 1e-15",
                           .source = kSource,
                           .unit = "",
                           .problem = kProblem});
}

// The edge-crack plate: 60 × 30 mm, brittle (critical stretch 0.003, no yield), pre-crack
// from the left edge to x = 15 mm; `tables` adds its loads. Its regions: R_pd = l_ext =
// l_con = 2δ, l_crit = δ (the paper's 7δ would cover this small plate).
test::HybridPlate edge_crack_plate(const std::string& tables) {
  test::HybridPlate plate;
  plate.size = {0.06, 0.03};
  plate.tables = tables;
  plate.pd_tables = "[[precrack]]\nfrom = [-1e-3, 0.0155]\nto = [0.015, 0.0155]\n";
  plate.pd_material_keys = "critical_stretch = 0.003";
  plate.hardening = "yield_stress = 1e12\ntangent_modulus = 0";
  return plate;
}
const hybrid::RegionRadii kEdgeCrackRadii{
    .pd_radius = 2.0, .expand_trigger = 1.0, .expand_radius = 2.0, .keep_radius = 2.0};

// An edge-cracked plate, free, whose halves are thrown apart (±12 m/s across the crack's
// line at t = 0): the crack runs and branches, regions grow and shrink every few steps.
// Returns the largest momentum drift over 3000 steps relative to Σ m|v|, and the run's
// conversions with their largest energy jump (audited).
struct FreeCrackRun {
  double drift = 0.0;
  hybrid::Events events;
  double largest_conversion_jump = 0.0;
  int largest_jump_step = 0;              // the step of the largest jump
  double kinetic_over_internal = 0.0;     // at that step
  double later_jump = 0.0;                // the largest jump after the first 100 steps
  double largest_jump_into_pd = 0.0;      // … of the steps whose conversions were all MPM → PD
  double largest_jump_with_breaks = 0.0;  // with the bonds the converting steps' evaluations break
};

FreeCrackRun free_crack(hybrid::Coupling coupling, hybrid::PlasticTransfer transfer, double revert_residual = 1.0) {
  hybrid::Settings settings;
  settings.revert_residual = revert_residual;
  settings.mode = hybrid::Mode::expand_shrink;
  settings.coupling = coupling;
  settings.plastic_transfer = transfer;
  settings.audit_conversions = true;
  settings.radii = kEdgeCrackRadii;
  test::HybridBody body(settings, edge_crack_plate(""));
  auto& p = body.particles();
  for (Index i = 0; i < p.n_real; ++i) p.v[i] = Vec<2>(0.0, p.x0[i][1] > 0.0155 ? 12.0 : -12.0);
  body.hybrid->start();
  const Vec<2> p0 = body.hybrid->momentum();
  double scale = 0.0;
  for (Index i = 0; i < p.n_real; ++i) scale += kRho * p.volume[i] * p.v[i].norm();
  FreeCrackRun r;
  for (int s = 1; s <= 3000; ++s) {
    const std::int64_t reverted = body.hybrid->events().to_mpm;
    body.hybrid->step(kDt, true);
    r.drift = std::max(r.drift, (body.hybrid->momentum() - p0).norm() / scale);
    const double jump = body.hybrid->last_conversion_jump();
    if (jump > r.largest_conversion_jump)
      r.largest_conversion_jump = jump, r.largest_jump_step = s,
      r.kinetic_over_internal = body.hybrid->kinetic_energy() / body.hybrid->internal_energy();
    if (s > 100) r.later_jump = std::max(r.later_jump, jump);
    if (body.hybrid->events().to_mpm == reverted) r.largest_jump_into_pd = std::max(r.largest_jump_into_pd, jump);
  }
  r.events = body.hybrid->events();
  r.largest_jump_with_breaks = body.hybrid->largest_jump_with_breaks();
  return r;
}

TEST(FastHybrid, ConversionsConserveMomentum) {
  const FreeCrackRun paper = free_crack(hybrid::Coupling::paper, hybrid::PlasticTransfer::strain);
  const FreeCrackRun consistent = free_crack(hybrid::Coupling::full_state, hybrid::PlasticTransfer::elastic_state);
  const FreeCrackRun bounded =
      free_crack(hybrid::Coupling::full_state, hybrid::PlasticTransfer::elastic_state, kRevertResidual);
  for (const FreeCrackRun* r : {&paper, &consistent, &bounded}) {
    EXPECT_GT(r->events.to_pd, 500) << "the run must convert both ways, many times";
    EXPECT_GT(r->events.to_mpm, 500);
  }
  test::record_gate(Gate{.id = "hybrid.momentum.conversions",
                         .claim = "a free plate whose edge crack runs and branches (expand_shrink, 3000 steps, "
                                  "hundreds to thousands of conversions each way, both couplings) shall keep its "
                                  "linear momentum through every conversion (largest drift relative to Σ m|v|)",
                         .measured = std::max({paper.drift, consistent.drift, bounded.drift}),
                         .expected = 1e-12,
                         .compare = Compare::at_most,
                         .tolerance_reason = "a conversion carries mass and velocity, so only round-off may move the "
                                             "sum: 1e-12 leaves three decades above the measured 1e-15",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
  test::record_gate(Gate{.id = "hybrid.conversion.energy_consistent_free",
                         .claim = fmt::format("so shall no step's conversions in it change the body's strain energy "
                                              "by more than 1e-3 of it (coupling full_state, plastic_transfer "
                                              "elastic_state, revert_residual = {})",
                                              kRevertResidual),
                         .measured = bounded.largest_conversion_jump,
                         .expected = 1e-3,
                         .compare = Compare::at_most,
                         .tolerance_reason = "the issue's bound, on a violent problem: waves cross the regions and "
                                             "without the shrink's bound the largest step loses 1.5 % (table 07b)",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
  auto row = [](const std::string& options, const FreeCrackRun& r) {
    return nlohmann::json::array({options, r.events.to_pd, r.events.to_mpm, r.events.expansions, r.drift,
                                  r.largest_conversion_jump, r.largest_jump_step, r.kinetic_over_internal, r.later_jump,
                                  r.largest_jump_into_pd, r.largest_jump_with_breaks});
  };
  test::record_data(
      kProblem, "07b_free_crack_conversions",
      {{"kind", "table"},
       {"title", "Conversions in a free plate thrown apart across its edge crack (expand_shrink, 3000 steps)"},
       {"columns",
        {"coupling, plastic transfer, shrink bound", "MPM→PD", "PD→MPM", "expansions", "momentum drift / Σ m|v|",
         "largest energy jump of one step / strain energy", "at step", "kinetic / strain energy then",
         "largest jump after step 100", "… of a step converting MPM → PD only",
         "… with the bonds the step's evaluation breaks"}},
       {"rows",
        {row("paper, strain", paper), row("full_state, elastic_state", consistent),
         row(fmt::format("full_state, elastic_state, revert_residual = {}", kRevertResidual), bounded)}},
       {"caption",
        "Gates hybrid.momentum.conversions and hybrid.conversion.energy_consistent_free. The halves are thrown "
        "apart at ±12 m/s: stress waves cross the PD regions, so a particle's deformation within its horizon "
        "is far from affine, and without the shrink's bound the first shrink (step 8, the kinetic energy 37 "
        "times the strain energy) returns most of the pre-crack's region to the grid and loses 1.5 %. The "
        "jumps are at fixed bonds; the last column adds the bonds the converting step's evaluation breaks: "
        "a particle turned PD can bring bonds the grid had stretched past the critical stretch, and they "
        "break at once — the crack's energy release, late by the region's arrival, not a conversion error."}});
}

// A homogeneously deformed, yielded block converted MPM → PD (one PD evaluation, accepted)
// → MPM, at an interior particle far from every face.
struct RoundTrip {
  double stress_change = 0.0;  // |σ after − σ before| / |σ before|
  double eq_strain_before = 0.0, eq_strain_after = 0.0;
  Mat<3> plastic_before, plastic_after;
  double von_mises = 0.0;     // MPM's σ_eq after (Pa)
  double energy_ratio = 0.0;  // PD strain energy just after the conversion / MPM's stored energy
  double grad_error = 0.0;    // |F from the bonds − F|
};

RoundTrip mpm_pd_mpm(const Mat<2>& F, hybrid::PlasticTransfer transfer = hybrid::PlasticTransfer::strain) {
  test::HybridBody body(hybrid::Settings{});
  auto& p = body.particles();
  body.hybrid->start();
  for (Index i = 0; i < p.n_real; ++i) {
    p.u[i] = (F - Mat<2>::Identity()) * p.x0[i];
    body.mpm->set_deformation_gradient(i, F);
  }
  Index probe = -1;  // an interior particle, far from every face
  for (Index i = 0; i < p.n_real; ++i)
    if ((p.x0[i] - Vec<2>(0.015, 0.0075)).norm() < 0.6e-3) probe = i;
  EXPECT_GE(probe, 0);
  RoundTrip r;
  const Mat<3> stress0 = body.mpm->state().cauchy(probe);
  r.eq_strain_before = body.mpm->state().history(probe).eq_plastic_strain;
  r.plastic_before = body.mpm->state().history(probe).plastic_strain;
  double stored = 0.0;
  for (Index i = 0; i < p.n_real; ++i) stored += body.mpm->state().energy[i] * p.volume[i];

  for (Index i = 0; i < p.n_real; ++i) p.kind[i] = ParticleKind::pd;
  for (Index i = 0; i < p.n_real; ++i) hybrid::to_pd<2>(*body.mpm, body.pd_setup.system, body.pd->model(), i);
  body.pd->refresh_kinds();
  if (transfer == hybrid::PlasticTransfer::elastic_state)
    for (Index i = 0; i < p.n_real; ++i)
      hybrid::to_pd_elastic_state<2>(*body.mpm, body.pd_setup.system, body.pd->model(), i);
  body.pd->internal_forces(true);
  r.energy_ratio = body.pd->internal_energy() / stored;
  body.pd->accept();
  for (Index i = 0; i < p.n_real; ++i)
    hybrid::to_mpm<2>(body.pd_setup.system, body.pd->model(), *body.mpm, i, transfer);
  const auto Fpd = hybrid::bond_deformation_gradient<2>(body.pd_setup.system, probe);
  r.grad_error = Fpd ? (*Fpd - F).norm() : std::numeric_limits<double>::infinity();
  r.stress_change = (body.mpm->state().cauchy(probe) - stress0).norm() / stress0.norm();
  r.eq_strain_after = body.mpm->state().history(probe).eq_plastic_strain;
  r.plastic_after = body.mpm->state().history(probe).plastic_strain;
  r.von_mises = body.mpm->von_mises(probe);
  return r;
}

TEST(FastHybrid, AYieldedBlockKeepsItsStateMpmToPdToMpm) {
  Mat<2> F;
  F << 1.003, 0.001, 0.0005, 0.999;
  const RoundTrip r = mpm_pd_mpm(F);
  ASSERT_GT(r.eq_strain_before, 1e-3) << "the block must have yielded";
  EXPECT_LT(r.grad_error, 1e-12) << "F from bonds is exact for an affine motion";
  test::record_gate(Gate{.id = "hybrid.conversion.stress",
                         .claim = "a homogeneously stretched, yielded block (ε̄_p = 1.9e-3) converted MPM → PD → MPM "
                                  "shall keep its stress within 1 % (interior particle)",
                         .measured = r.stress_change,
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
  const double budget = 0.01 * r.von_mises / (3.0 * G + H);
  EXPECT_LT((r.plastic_after - r.plastic_before).norm(), std::sqrt(1.5) * budget);
  test::record_gate(Gate{.id = "hybrid.conversion.plastic_strain",
                         .claim = "the same round trip shall keep ε̄_p within 0.01 σ_eq/(3G + H), the plastic strain "
                                  "a 1 % stress error moves on the hardening line",
                         .measured = std::abs(r.eq_strain_after - r.eq_strain_before),
                         .expected = budget,
                         .compare = Compare::at_most,
                         .tolerance_reason = "consistent with the stress gate's 1 %",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});

  // The same round trip at the strains a neck reaches (uniaxial, isochoric: F = diag(λ, λ^-½)):
  // the conversion maps the grid's log plastic strain onto small-strain bonds, whose
  // extension λ − 1 and dilatation outgrow ln λ and 0 (docs/models/hybrid.md, Conversions).
  nlohmann::json rows = nlohmann::json::array();
  double elastic_state_worst = 0.0;
  for (const double lambda : {1.003, 1.01, 1.05, 1.2, 1.5, 1.9}) {
    Mat<2> Fu = Mat<2>::Zero();
    Fu(0, 0) = lambda;
    Fu(1, 1) = 1.0 / std::sqrt(lambda);
    const RoundTrip u = mpm_pd_mpm(Fu), v = mpm_pd_mpm(Fu, hybrid::PlasticTransfer::elastic_state);
    rows.push_back({lambda, std::log(lambda), u.eq_strain_before, u.energy_ratio, u.stress_change, v.energy_ratio,
                    v.stress_change});
    elastic_state_worst = std::max(elastic_state_worst, v.stress_change);
  }
  test::record_gate(Gate{.id = "hybrid.conversion.elastic_state",
                         .claim = "with hybrid.plastic_transfer = \"elastic_state\" the MPM → PD → MPM round trip of a "
                                  "yielded block shall keep its stress to round-off at every stretch λ = 1.003 … 1.9 "
                                  "(uniaxial, isochoric; ε̄_p up to 0.63)",
                         .measured = elastic_state_worst,
                         .expected = 1e-10,
                         .compare = Compare::at_most,
                         .tolerance_reason =
                             "the two transfers are inverse at the particle's own bond geometry and the PD "
                             "evaluation between them does not flow (its σ̄ is the grid's, on the yield surface); "
                             "what is left is round-off in ln U and the least-squares fit (≤ 2e-14 measured)",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
  test::record_data(kProblem, "08_conversion_strain",
                    {{"kind", "table"},
                     {"title", "MPM → PD → MPM of a yielded block against the strain it is converted at"},
                     {"columns",
                      {"stretch λ", "ln λ", "ε̄_p (MPM)", "strain: PD strain energy after conversion / MPM stored",
                       "strain: stress change after the round trip", "elastic_state: PD / MPM energy",
                       "elastic_state: stress change after the round trip"}},
                     {"rows", rows},
                     {"caption",
                      "30 × 15 mm block, Δx = 1 mm, δ = 3.015Δx, σ_y = 250 MPa, E_t = 2 GPa, F = diag(λ, λ^-½) "
                      "(isochoric uniaxial), all particles converted, one PD evaluation accepted, back to MPM; "
                      "stress at an interior particle, energies over the whole block (its free faces make the "
                      "small-strain ratio differ from 1). The gate above is the first row's strain level."}});
}

// A brittle edge crack (critical stretch, no yield) in a plate pulled at both edges
// (velocity ramped over 10 µs): the same scene in the three modes.
struct CrackRun {
  std::vector<double> t, front_x;  // furthest particle with φ > 0.35 (m)
  std::vector<double> tip_gap;     // distance from that particle to the nearest tracked tip (m)
  std::vector<int> far_tips;       // tracked tips farther than 3Δx from it (the crack has one end)
  std::vector<double> pd_count;
  std::vector<double> mouth_opening;  // u_y(above) − u_y(below) at the pre-crack's mouth (m)
  hybrid::Events events;
  std::int64_t pd_steps = 0, mpm_steps = 0;
  hybrid::PhaseSeconds seconds;
  std::vector<ParticleKind> kinds;
  std::vector<Vec<2>> u;
  Index region_violations = 0;            // summed over the steps
  Index healed = 0;                       // steps after which fewer bonds were broken than before
  Index damaged_reverted = 0;             // particle-steps: a PD particle with a broken bond that left PD
  double largest_conversion_jump = 0.0;   // with audit: one step's conversions over the internal energy
  double largest_jump_into_pd = 0.0;      // … of the steps whose conversions were all MPM → PD
  double largest_jump_with_breaks = 0.0;  // … with the bonds the converting steps' evaluations break
  double internal_energy = 0.0;           // at the end
  double conversion_energy = 0.0;         // with audit: summed over the run (J)
};

// One run of the edge-crack plate. The grips hold every particle within `grip` of the top
// and bottom edges (PD) and every grid node there (MPM): 1.5 mm holds two particle rows but
// only the edge's node row of the 2 mm grid; 2.2 mm holds the nodes at 2 mm too, so both
// methods hold the same 2 mm of material (table 03b).
struct EdgeCrack {
  hybrid::Mode mode = hybrid::Mode::expand_shrink;
  int steps = 4000;
  double speed = 0.3;  // pull of each grip (m/s), ramped over 10 µs
  bool audit = false;  // book the conversions' energy
  hybrid::Coupling coupling = hybrid::Coupling::paper;
  hybrid::PlasticTransfer transfer = hybrid::PlasticTransfer::strain;
  double grip = 1.5e-3;  // m
  double revert_residual = 1.0;
  bool pd_grips = false;  // the grips' particles start PD (and stay PD: they are held)
};

CrackRun run_edge_crack(const EdgeCrack& c) {
  hybrid::Settings s;
  s.mode = c.mode;
  s.coupling = c.coupling;
  s.plastic_transfer = c.transfer;
  s.audit_conversions = c.audit;
  s.revert_residual = c.revert_residual;
  s.radii = kEdgeCrackRadii;
  const std::string v = std::to_string(c.speed) + "*min(t/1e-5, 1)";
  const std::string pull = fmt::format(
      "[[boundary]]\nname = \"bottom\"\nkind = \"velocity\"\n"
      "region = {{ type = \"box\", min = [-1, -1], max = [1, {:.6g}] }}\nvalue = [\"free\", \"-{}\"]\n"
      "[[boundary]]\nname = \"top\"\nkind = \"velocity\"\n"
      "region = {{ type = \"box\", min = [-1, {:.6g}], max = [1, 1] }}\nvalue = [\"free\", \"{}\"]\n",
      c.grip, v, 0.03 - c.grip, v);
  test::HybridBody body(s, edge_crack_plate(pull));
  std::vector<Index> grips;
  if (c.pd_grips)  // the grips' boxes, closed as a scene's region is: the row at y = grip is held too
    for (Index i = 0; i < body.particles().n_real; ++i)
      if (body.particles().x0[i][1] <= c.grip || body.particles().x0[i][1] >= 0.03 - c.grip) grips.push_back(i);
  body.hybrid->start(grips);
  CrackRun r;
  const auto& p = body.particles();
  const auto& sys = body.pd_setup.system;
  auto broken_bonds = [&] {
    Index b = 0;
    for (BondIndex k = 0; k < sys.families.n_bonds(); ++k) b += sys.bonds.broken(k);
    return b;
  };
  Index broken = broken_bonds();
  Index above = -1, below = -1;  // the mouth: first column, one row either side of the cut
  for (Index i = 0; i < p.n_real; ++i) {
    if (std::abs(p.x0[i][0] - 0.5e-3) > 1e-9) continue;
    if (std::abs(p.x0[i][1] - 16.5e-3) < 1e-9) above = i;
    if (std::abs(p.x0[i][1] - 14.5e-3) < 1e-9) below = i;
  }
  // PD particles with a broken bond when the step began: the step's shrink decides on
  // them. (A particle that reverts undamaged becomes transition, and its bond to a PD
  // particle can break in the same step's force evaluation, as in the paper; the
  // expansion that break triggers takes it back.)
  std::vector<std::uint8_t> damaged(static_cast<std::size_t>(p.n_real), 0);
  for (int n = 1; n <= c.steps; ++n) {
    for (Index i = 0; i < p.n_real; ++i)
      damaged[i] = p.kind[i] == ParticleKind::pd && pd::particle_damage(sys, i) > 0.0;
    const std::int64_t reverted = body.hybrid->events().to_mpm;
    body.hybrid->step(kDt);
    if (body.hybrid->events().to_mpm == reverted)
      r.largest_jump_into_pd = std::max(r.largest_jump_into_pd, body.hybrid->last_conversion_jump());
    r.region_violations += body.hybrid->region_violations();
    const Index now = broken_bonds();
    r.healed += now < broken;
    broken = now;
    for (Index i = 0; i < p.n_real; ++i) r.damaged_reverted += damaged[i] && p.kind[i] != ParticleKind::pd;
    if (n % 50 != 0) continue;
    Vec<2> front = Vec<2>::Zero();
    for (const Index i : body.pd->movers())
      if (pd::particle_damage(body.pd_setup.system, i) > 0.35 && p.x0[i][0] > front[0]) front = p.x0[i];
    double gap = std::numeric_limits<double>::infinity();
    int far = 0;
    for (const auto& tip : body.hybrid->track_tips()) {
      gap = std::min(gap, (tip.position - front).norm());
      far += (tip.position - front).norm() > 3.0 * kDx;
    }
    r.far_tips.push_back(far);
    r.t.push_back(body.hybrid->time());
    r.front_x.push_back(front[0]);
    r.tip_gap.push_back(gap);
    r.pd_count.push_back(static_cast<double>(body.hybrid->counts().pd));
    r.mouth_opening.push_back(p.u[above][1] - p.u[below][1]);
  }
  r.events = body.hybrid->events();
  r.pd_steps = body.hybrid->pd_particle_steps();
  r.mpm_steps = body.hybrid->mpm_particle_steps();
  r.seconds = body.hybrid->phase_seconds();
  r.kinds = p.kind;
  for (const Index i : grips) EXPECT_EQ(p.kind[i], ParticleKind::pd) << "a held PD particle must stay PD";
  r.u = p.u;
  r.largest_conversion_jump = body.hybrid->largest_conversion_jump();
  r.largest_jump_with_breaks = body.hybrid->largest_jump_with_breaks();
  r.conversion_energy = body.hybrid->conversion_energy();
  r.internal_energy = body.hybrid->internal_energy();
  return r;
}

TEST(FastHybrid, ThreadCountDoesNotChangeARunWithMovingRegions) {
  const int threads = omp_get_max_threads();
  Index differ = 0;
  for (const auto coupling : {hybrid::Coupling::paper, hybrid::Coupling::full_state, hybrid::Coupling::blended}) {
    omp_set_num_threads(1);
    const CrackRun one = run_edge_crack({.steps = 2000, .speed = 1.0, .coupling = coupling});
    omp_set_num_threads(2);
    const CrackRun two = run_edge_crack({.steps = 2000, .speed = 1.0, .coupling = coupling});
    omp_set_num_threads(threads);
    ASSERT_GT(one.events.to_pd, 0);
    ASSERT_GT(one.events.to_mpm, 0) << "regions must shrink, or conversions back are not compared";
    for (std::size_t i = 0; i < one.u.size(); ++i) differ += one.u[i] != two.u[i] || one.kinds[i] != two.kinds[i];
  }
  test::record_gate(Gate{
      .id = "hybrid.thread_invariance",
      .claim = "a hybrid run with regions growing and shrinking (edge crack, 2000 steps, the paper's coupling, "
               "the full-state and the blended one) shall give bitwise the same displacements and particle kinds on 1 "
               "and 2 threads",
      .measured = static_cast<double>(differ),
      .expected = 0.0,
      .compare = Compare::at_most,
      .tolerance_reason = "exact: every PD and MPM sum has a fixed order; region management is serial",
      .source = kSource,
      .unit = "",
      .problem = kProblem});
}

// A hybrid run's edge crack against the all-PD run's, sample by sample. Front: the furthest
// damaged particle (a lattice site: a whole number of spacings apart). Opening: the mouth's,
// relative to the all-PD run's largest; "early" while neither crack has grown yet.
struct Agreement {
  double ahead = 0.0, behind = 0.0;  // largest lead and lag of the front (Δx)
  double opening_early = 0.0, opening_all = 0.0;
  double front() const { return std::max(ahead, behind); }
};

Agreement agreement(const CrackRun& h, const CrackRun& pd) {
  const double peak_opening = *std::max_element(pd.mouth_opening.begin(), pd.mouth_opening.end());
  Agreement a;
  for (std::size_t k = 0; k < pd.t.size(); ++k) {
    const double lead = std::round((h.front_x[k] - pd.front_x[k]) / kDx);
    a.ahead = std::max(a.ahead, lead);
    a.behind = std::max(a.behind, -lead);
    const double opening = std::abs(h.mouth_opening[k] - pd.mouth_opening[k]) / peak_opening;
    a.opening_all = std::max(a.opening_all, opening);
    if (std::max(h.front_x[k], pd.front_x[k]) <= pd.front_x.front())
      a.opening_early = std::max(a.opening_early, opening);
  }
  return a;
}

TEST(FastHybrid, EdgeCrackAgainstTheAllPdRun) {
  const int steps = 4000;
  const CrackRun pd = run_edge_crack({.mode = hybrid::Mode::pd, .steps = steps});
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
  test::record_gate(Gate{.id = "hybrid.tips.no_false_tips",
                         .claim =
                             "on the same running PD edge crack (one crack, one tip) the tracker shall find no tip "
                             "farther than 3Δx from the damage front at any sample (samples with such a tip)",
                         .measured = static_cast<double>(with_false),
                         .expected = 0.0,
                         .compare = Compare::at_most,
                         .tolerance_reason = "exact (the issue's \"no false tips\"): 3Δx is the tracker's merge "
                                             "radius, within which a crack end's minima are one tip",
                         .source = "[noorian] eqs 13–15",
                         .unit = "",
                         .problem = kProblem});
  test::record_data(kProblem, "04_tip_tracking",
                    {{"kind", "table"},
                     {"title", "Crack-tip tracker on the running all-PD edge crack"},
                     {"columns",
                      {"samples (every 50 steps)", "largest gap front–nearest tip (Δx)",
                       "samples with a tip > 3Δx from the front (false tips)"}},
                     {"rows", {{samples, worst, with_false}}},
                     {"caption",
                      "Front: the furthest particle with φ > 0.35. A running crack's damage band is several "
                      "spacings wide and uneven along it; before the ridge test (hybrid.tips.ridge_fraction) "
                      "a site on its flank could pass the crack-end test, and 1 of these samples had such a "
                      "false tip."}});

  nlohmann::json series = nlohmann::json::array(), rows = nlohmann::json::array();
  auto us = [](std::vector<double> t) {
    for (double& x : t) x *= 1e6;
    return t;
  };
  auto mm = [](std::vector<double> x) {
    for (double& v : x) v *= 1e3;
    return x;
  };
  auto um = [](std::vector<double> x) {
    for (double& v : x) v *= 1e6;
    return x;
  };
  series.push_back({{"label", "all PD"}, {"x", us(pd.t)}, {"y", mm(pd.front_x)}, {"style", "line"}});
  auto row = [&](const std::string& label, const CrackRun& r, double deviation, double opening_early,
                 double opening_all) {
    const auto pd_steps = static_cast<double>(r.pd_steps), mpm_steps = static_cast<double>(r.mpm_steps);
    const double ns_pd = pd_steps > 0 ? 1e9 * r.seconds.pd / pd_steps : 0.0;
    const double ns_mpm = mpm_steps > 0 ? 1e9 * r.seconds.mpm / mpm_steps : 0.0;
    rows.push_back({label, deviation, opening_early, opening_all, r.events.to_pd, r.events.to_mpm, r.events.expansions,
                    r.events.shrinks, pd_steps / (pd_steps + mpm_steps), ns_pd, ns_mpm,
                    r.seconds.coupling / r.seconds.total(), r.seconds.regions / r.seconds.total()});
  };
  row("pd", pd, 0.0, 0.0, 0.0);
  double worst_front = 0.0, worst_opening_early = 0.0;
  nlohmann::json openings = nlohmann::json::array();
  openings.push_back({{"label", "all PD"}, {"x", us(pd.t)}, {"y", um(pd.mouth_opening)}, {"style", "line"}});
  Index violations = 0, healed = 0, damaged_reverted = 0;
  double region_share = 0.0;
  CrackRun shrinking, shrinking_full_state;
  for (auto coupling : {hybrid::Coupling::paper, hybrid::Coupling::full_state})
    for (auto mode : {hybrid::Mode::expand, hybrid::Mode::expand_shrink}) {
      const bool paper = coupling == hybrid::Coupling::paper;
      // The full-state runs measure their conversions' energy as they go (table 07).
      const CrackRun h = run_edge_crack({.mode = mode, .steps = steps, .audit = !paper, .coupling = coupling});
      if (mode == hybrid::Mode::expand_shrink) (paper ? shrinking : shrinking_full_state) = h;
      const Agreement a = agreement(h, pd);
      const double deviation = a.front(), opening_early = a.opening_early, opening_all = a.opening_all;
      const std::string label = std::string(name(mode)) + (paper ? "" : " (full_state)");
      openings.push_back({{"label", label}, {"x", us(h.t)}, {"y", um(h.mouth_opening)}, {"style", "line"}});
      series.push_back({{"label", label}, {"x", us(h.t)}, {"y", mm(h.front_x)}, {"style", "line"}});
      row(label, h, deviation, opening_early, opening_all);
      if (!paper) continue;  // the gates below are the paper's coupling's
      violations += h.region_violations;
      healed += h.healed;
      damaged_reverted += h.damaged_reverted;
      region_share = std::max(region_share, h.seconds.regions / h.seconds.total());
      worst_front = std::max(worst_front, deviation);
      worst_opening_early = std::max(worst_opening_early, opening_early);
    }
  test::record_gate(Gate{.id = "hybrid.agreement.crack_front",
                         .claim = "the edge crack's front (furthest particle with φ > 0.35) in modes expand and "
                                  "expand_shrink shall stay within 2Δx of the all-PD run's at every sample (every 50 "
                                  "steps, 4000 steps)",
                         .measured = worst_front,
                         .expected = 2.0,
                         .compare = Compare::at_most,
                         .tolerance_reason = "the issue's bound: a front on the lattice moves by whole spacings, and a "
                                             "crack one sample ahead of another is 1–2 spacings ahead",
                         .source = kSource,
                         .unit = "Δx",
                         .problem = kProblem});
  test::record_gate(Gate{.id = "hybrid.agreement.opening",
                         .claim = "the pre-crack's mouth opening in modes expand and expand_shrink shall stay within "
                                  "2 % (of the all-PD run's largest) of the all-PD run's until the crack grows",
                         .measured = worst_opening_early,
                         .expected = 0.02,
                         .compare = Compare::at_most,
                         .tolerance_reason = "the issue's 2 % for the load–displacement curve, applied to the opening "
                                             "history; once the crack runs the deviation is larger (table 03) and not "
                                             "gated",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
  test::record_data(kProblem, "02b_edge_crack_opening",
                    {{"kind", "plot"},
                     {"title", "Edge crack: opening of the pre-crack's mouth against time, three modes, two couplings"},
                     {"xlabel", "t (µs)"},
                     {"ylabel", "u_y(above) − u_y(below) at x = 0.5 mm (µm)"},
                     {"xscale", "linear"},
                     {"yscale", "linear"},
                     {"series", openings},
                     {"caption",
                      "The mouth is PD in every mode (the pre-crack starts PD). The crack starts running at "
                      "about 65 µs."}});
  // The same comparison where the grips end elsewhere (2.2 mm: the grid's node rows at 0 and
  // 2 mm, the particle rows at 0.5 and 1.5 mm), and with grips made of PD particles, which
  // hold exactly the all-PD run's particles (held particles stay PD).
  {
    const auto full = hybrid::Coupling::full_state;
    const CrackRun pd_deeper = run_edge_crack({.mode = hybrid::Mode::pd, .steps = steps, .grip = 2.2e-3});
    nlohmann::json grip_rows = nlohmann::json::array();
    double pd_grips_front = 0.0, pd_grips_opening = 0.0;
    auto grip_row = [&](const char* grip, hybrid::Mode mode, hybrid::Coupling coupling, const CrackRun& h,
                        const CrackRun& ref) {
      const Agreement a = agreement(h, ref);
      grip_rows.push_back({grip, name(mode), name(coupling), a.ahead, a.behind, a.opening_early, a.opening_all});
      return a;
    };
    const auto es = hybrid::Mode::expand_shrink;
    grip_row("1.5 mm (the gates')", es, hybrid::Coupling::paper, shrinking, pd);
    grip_row("1.5 mm (the gates')", es, full, shrinking_full_state, pd);
    for (auto coupling : {hybrid::Coupling::paper, full})
      grip_row("2.2 mm", es, coupling, run_edge_crack({.steps = steps, .coupling = coupling, .grip = 2.2e-3}),
               pd_deeper);
    for (auto coupling : {hybrid::Coupling::paper, full, hybrid::Coupling::blended})
      for (auto mode : {hybrid::Mode::expand, es}) {
        const Agreement a =
            grip_row("1.5 mm of PD particles", mode, coupling,
                     run_edge_crack({.mode = mode, .steps = steps, .coupling = coupling, .pd_grips = true}), pd);
        if (coupling != hybrid::Coupling::blended) continue;
        pd_grips_front = std::max(pd_grips_front, a.front());
        pd_grips_opening = std::max(pd_grips_opening, a.opening_early);
      }
    // The all-PD run against itself with its grips 0.016 % faster: how well the fronts and the
    // opening are defined at all (a break a step earlier somewhere shifts the rest of the run).
    const CrackRun perturbed = run_edge_crack({.mode = hybrid::Mode::pd, .steps = steps, .speed = 0.3 * 1.00016});
    const Agreement noise = agreement(perturbed, pd);
    grip_rows.push_back({"1.5 mm, grips 0.016 % faster", "pd (all-PD itself)", "—", noise.ahead, noise.behind,
                         noise.opening_early, noise.opening_all});
    test::record_data(
        kProblem, "03b_edge_crack_grips",
        {{"kind", "table"},
         {"title", "Edge crack against the all-PD run: what the grips hold"},
         {"columns",
          {"grips", "mode", "coupling", "front ahead of all-PD, largest (Δx)", "front behind, largest (Δx)",
           "opening deviation before growth", "opening deviation, whole run"}},
         {"rows", grip_rows},
         {"caption",
          "The grid holds node rows (cell 2 mm), PD holds particle rows (Δx = 1 mm). With the gates' 1.5 mm the "
          "grid holds only the edge's node row while PD holds two particle rows: before the crack grows "
          "the hybrid carries 8.7 % less grip load than the all-PD plate (pdmpm run, 59 µs, "
          "docs/models/hybrid.md); with 2.2 mm, whose grid also holds the node row at 2 mm and, through "
          "its shape functions, part of the third particle row, 2.7 % more. Grips of PD particles (the "
          "grips' particles start PD and stay PD) hold exactly the all-PD run's particles: gates "
          "hybrid.agreement.crack_front_blended and hybrid.agreement.opening_blended (the blended coupling); "
          "full_state runs 5Δx ahead there, the paper's coupling 11–21Δx. The last row is the all-PD run "
          "against itself with its grips 0.016 % faster: the resolution of these measures once the crack "
          "runs."}});
    test::record_gate(Gate{.id = "hybrid.agreement.crack_front_blended",
                           .claim = "with grips of PD particles (the all-PD run's grips exactly) and coupling "
                                    "blended, the edge crack's front in modes expand and expand_shrink shall stay "
                                    "within 2Δx of the all-PD run's at every sample (every 50 steps, 4000 steps)",
                           .measured = pd_grips_front,
                           .expected = 2.0,
                           .compare = Compare::at_most,
                           .tolerance_reason = "the issue's bound, as hybrid.agreement.crack_front; the all-PD "
                                               "run against itself with grips 0.016 % faster moves by 1Δx (table "
                                               "03b), so 2Δx is above the problem's own resolution",
                           .source = kSource,
                           .unit = "Δx",
                           .problem = kProblem});
    test::record_gate(Gate{.id = "hybrid.agreement.opening_blended",
                           .claim = "with the same grips and coupling, the pre-crack's mouth opening shall stay within "
                                    "2 % (of the all-PD run's largest) of the all-PD run's until the crack grows",
                           .measured = pd_grips_opening,
                           .expected = 0.02,
                           .compare = Compare::at_most,
                           .tolerance_reason = "the issue's 2 % for the load–displacement curve, as "
                                               "hybrid.agreement.opening; over the whole run 1.9–2.4 % (table 03b)",
                           .source = kSource,
                           .unit = "",
                           .problem = kProblem});
  }

  // The same expand_shrink run, measuring the energy each step's conversions add, with
  // each coupling and plastic transfer, the shrink's residual bound, both grips (the
  // full-state, strain run is the loop's).
  const CrackRun audited = run_edge_crack({.steps = steps, .audit = true});
  EXPECT_EQ(audited.u, shrinking.u) << "the audit's extra evaluations must not change the run";
  const auto elastic = hybrid::PlasticTransfer::elastic_state;
  const auto full = hybrid::Coupling::full_state;
  const CrackRun audited_elastic = run_edge_crack({.steps = steps, .audit = true, .transfer = elastic});
  std::vector<CrackRun> consistent;  // grips 1.5, 2.2 mm; without and with the residual bound
  for (const double bound : {1.0, kRevertResidual})
    for (const double grip : {1.5e-3, 2.2e-3})
      consistent.push_back(run_edge_crack({.steps = steps,
                                           .audit = true,
                                           .coupling = full,
                                           .transfer = elastic,
                                           .grip = grip,
                                           .revert_residual = bound}));
  auto energy_row = [](const std::string& options, const CrackRun& r) {
    const auto pd_steps = static_cast<double>(r.pd_steps), mpm_steps = static_cast<double>(r.mpm_steps);
    return nlohmann::json::array({options, r.events.to_pd, r.events.to_mpm, r.largest_conversion_jump,
                                  r.largest_jump_into_pd, r.largest_jump_with_breaks, r.conversion_energy,
                                  r.internal_energy, pd_steps / (pd_steps + mpm_steps)});
  };
  const std::string bounded = fmt::format("full_state, elastic_state, revert_residual = {}", kRevertResidual);
  test::record_data(
      kProblem, "07_conversion_energy",
      {{"kind", "table"},
       {"title", "Energy changed by conversions (edge crack, expand_shrink)"},
       {"columns",
        {"coupling, plastic transfer, shrink bound (grips)", "MPM→PD", "PD→MPM",
         "largest jump of one step / strain energy", "… of a step converting MPM → PD only",
         "… with the bonds the step's evaluation breaks", "sum of all jumps (J)", "strain energy at the end (J)",
         "PD share of particle-steps"}},
       {"rows",
        {energy_row("paper, strain", audited), energy_row("paper, elastic_state", audited_elastic),
         energy_row("full_state, strain", shrinking_full_state), energy_row("full_state, elastic_state", consistent[0]),
         energy_row("full_state, elastic_state (2.2 mm, table 03b)", consistent[1]), energy_row(bounded, consistent[2]),
         energy_row(bounded + " (2.2 mm)", consistent[3])}},
       {"caption",
        "Jump: the body's strain energy at tⁿ⁺¹ after the step's conversions minus before them, both "
        "evaluated with the bonds as they are (hybrid.audit_conversions); kinetic energy does not change "
        "(velocities are carried). The plate is elastic (no yield): the plastic transfer elastic_state gives "
        "a particle turned PD the grid's strain as its PD elastic state (a bond's difference from it becomes "
        "that bond's plastic extension), strain the bonds' own extensions. With elastic_state, MPM → PD "
        "conversions keep the energy (gate hybrid.conversion.energy_into_pd); PD → MPM ones lose the part "
        "of the particle's PD elastic state no F describes (non-affine within its horizon): up to 1 % with "
        "the paper's coupling, whose states near the region's edge are far from affine (table 01), 0.06–0.2 % "
        "with the full-state one. revert_residual bounds it: a shrink reverts only particles whose "
        "non-affine share is at most the bound (gate hybrid.conversion.energy_consistent)."}});
  test::record_gate(
      Gate{.id = "hybrid.conversion.energy_into_pd",
           .claim = "with plastic_transfer elastic_state, no step whose conversions are all MPM → PD "
                    "shall change the body's strain energy by more than 1e-3 of it (edge crack, "
                    "expand_shrink, 4000 steps, either coupling, both grips)",
           .measured = std::max(audited_elastic.largest_jump_into_pd,
                                std::max(consistent[0].largest_jump_into_pd, consistent[1].largest_jump_into_pd)),
           .expected = 1e-3,
           .compare = Compare::at_most,
           .tolerance_reason = "the issue's bound for the energy jump of a conversion",
           .source = kSource,
           .unit = "",
           .problem = kProblem});
  test::record_gate(Gate{
      .id = "hybrid.conversion.energy_consistent",
      .claim = fmt::format("with coupling full_state, plastic_transfer elastic_state and revert_residual = {}, no "
                           "step's conversions on the edge crack (expand_shrink, 4000 steps, both directions, both "
                           "grips) shall change the body's strain energy by more than 1e-3 of it",
                           kRevertResidual),
      .measured = std::max(consistent[2].largest_conversion_jump, consistent[3].largest_conversion_jump),
      .expected = 1e-3,
      .compare = Compare::at_most,
      .tolerance_reason = "the issue's bound. Without the shrink's bound it holds on the gates' "
                          "grips and not on the other (table 07); the paper's coupling and "
                          "transfer give about 1e-2",
      .source = kSource,
      .unit = "",
      .problem = kProblem});
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
                             "in the edge-crack runs in modes expand and expand_shrink (8000 steps, about 1900 "
                             "conversions both ways) no broken bond shall ever be restored and no PD particle with "
                             "a broken bond when a step begins shall leave PD in it (steps with fewer broken bonds "
                             "+ such departures)",
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
                     {"title", "Edge crack: crack front against time, three modes of one scene, two couplings"},
                     {"xlabel", "t (µs)"},
                     {"ylabel", "furthest particle with φ > 0.35 (mm)"},
                     {"xscale", "linear"},
                     {"yscale", "linear"},
                     {"series", series},
                     {"caption",
                      "60 × 30 mm plate, Δx = 1 mm, δ = 3.015Δx, edge pre-crack to x = 15 mm, edges pulled "
                      "at 0.3 m/s (ramp 10 µs), critical stretch 0.003, no yield; regions R_pd = l_ext = "
                      "l_con = 2δ, l_crit = δ (small for a small plate). Gated (the paper's coupling): every "
                      "sample within 2Δx of the all-PD front (hybrid.agreement.crack_front); expand_shrink "
                      "reaches the bound. With the full-state coupling the crack starts ≈ 4 µs later than in "
                      "the all-PD run and stays 5–6Δx behind (shown, not gated)."}});
  test::record_data(
      kProblem, "03_edge_crack_runs",
      {{"kind", "table"},
       {"title", "Edge crack: the three modes, two couplings"},
       {"columns",
        {"mode", "max front deviation (Δx)", "opening deviation before growth", "opening deviation, whole run",
         "MPM→PD", "PD→MPM", "expansions", "shrinks", "PD share of particle-steps", "ns per PD particle-step",
         "ns per MPM particle-step", "coupling share of wall time", "region share of wall time"}},
       {"rows", rows},
       {"caption",
        "One process, one thread count. Opening deviations relative to the all-PD run's largest "
        "mouth opening; once the crack runs they exceed the issue's 2 % (not gated). Rows marked "
        "full_state: transition particles measure their PD state over their whole family "
        "(hybrid.coupling). The cost "
        "per particle-step of each method, measured in the same runs, decides how much the "
        "hybrid can save."}});
}

// Accelerations of an affine displacement u = H x (no velocity) after one tiny step,
// relative to σ/(ρΔx), the acceleration of a particle on a free face carrying the
// affine state's traction; particles within 4Δx of the plate's edges are skipped (a
// free edge is not in equilibrium under an affine field).
struct GhostForces {
  double pd = 0.0, transition = 0.0, mpm = 0.0;
};
// The blended coupling's band widths (δ) of the ghost-force table; the default 2 is the middle.
constexpr std::array<double, 3> kBlendWidths{1.0, 2.0, 4.0};

GhostForces ghost_forces(const Mat<2>& H, bool with_pd, hybrid::Coupling coupling = hybrid::Coupling::paper,
                         double blend_width = 2.0, const Vec<2>& size = Vec<2>(0.04, 0.03)) {
  GhostForces g;
  const Vec<2> centre = 0.5 * size;
  hybrid::Settings s;
  s.mode = hybrid::Mode::expand;
  s.coupling = coupling;
  s.blend_width = blend_width;
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
  const double a_scale = body.mpm->state().cauchy(0).norm() / (kRho * kDx);
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
  double full_state_pd = 0.0, blended_pd = 0.0, blended_transition = 0.0,
         blended_order = std::numeric_limits<double>::infinity();
  for (const auto& [label, H] : {std::pair{"stretch", stretch}, std::pair{"shear", shear}}) {
    const GhostForces mpm_only = ghost_forces(H, false);
    EXPECT_LT(mpm_only.mpm, 1e-12) << "the all-MPM body is in equilibrium under an affine motion";
    for (const auto coupling : {hybrid::Coupling::paper, hybrid::Coupling::full_state}) {
      const GhostForces g = ghost_forces(H, true, coupling);
      rows.push_back({label, std::string(name(coupling)), g.pd, g.transition, g.mpm, mpm_only.mpm});
      if (coupling == hybrid::Coupling::full_state) full_state_pd = std::max(full_state_pd, g.pd);
    }
    // The blended band needs room: a larger plate, so that it ends inside.
    std::vector<double> transition;
    for (const double width : kBlendWidths) {
      const GhostForces g = ghost_forces(H, true, hybrid::Coupling::blended, width, Vec<2>(0.08, 0.08));
      rows.push_back({label, fmt::format("blended, blend_width = {}", width), g.pd, g.transition, g.mpm, mpm_only.mpm});
      blended_pd = std::max(blended_pd, g.pd);
      transition.push_back(g.transition);
    }
    blended_transition = std::max(blended_transition, transition[1]);
    blended_order = std::min(
        blended_order,
        std::log(transition.front() / transition.back()) / std::log(kBlendWidths.back() / kBlendWidths.front()));
  }
  test::record_gate(Gate{.id = "hybrid.ghost_forces.blended_pd",
                         .claim = "with the blended coupling the PD particles of the same plate under the same affine "
                                  "stretch and shear shall be in equilibrium (band widths 1, 2, 4 δ): largest "
                                  "acceleration ≤ 1e-12 σ/(ρΔx)",
                         .measured = blended_pd,
                         .expected = 1e-12,
                         .compare = Compare::at_most,
                         .tolerance_reason = "as hybrid.ghost_forces.full_state_pd: round-off of ~30 cancelling bond "
                                             "terms; a PD particle's neighbours all have β = 1",
                         .source = kSource,
                         .unit = "σ/(ρΔx)",
                         .problem = kProblem});
  test::record_gate(
      Gate{.id = "hybrid.ghost_forces.blended_transition",
           .claim = "with the blended coupling (blend_width = 2, the default) the largest acceleration of "
                    "a transition particle under the affine stretch and shear shall be at most 0.05 "
                    "σ/(ρΔx) (full_state: 0.30, the paper's coupling: 0.61)",
           .measured = blended_transition,
           .expected = 0.05,
           .compare = Compare::at_most,
           .tolerance_reason = "either method alone would leave σ∇β, an acceleration of Δx/(band width) ≈ 1/6 "
                               "σ/(ρΔx) at the default width; the blend cancels most of it. 0.05 is under a "
                               "third of that and six times below what full_state leaves",
           .source = "[badia2008]; docs/models/hybrid.md",
           .unit = "σ/(ρΔx)",
           .problem = kProblem});
  test::record_gate(Gate{.id = "hybrid.ghost_forces.blended_order",
                         .claim = "the blended coupling's largest transition ghost force shall fall with the band's "
                                  "width at first order: observed order between widths δ and 4δ ≥ 0.9 (both motions)",
                         .measured = blended_order,
                         .expected = 0.9,
                         .compare = Compare::at_least,
                         .tolerance_reason = "what the cancellation leaves is the difference of the two "
                                             "discretisations' σ∇β, proportional to the weight's gradient, 1/width: "
                                             "order 1; 0.9 allows the lattice's rounding of the band's edges",
                         .source = "[badia2008]; docs/models/hybrid.md",
                         .unit = "",
                         .problem = kProblem});
  test::record_gate(Gate{.id = "hybrid.ghost_forces.full_state_pd",
                         .claim = "with the full-state coupling (transition particles' PD state over their whole "
                                  "family) the PD particles of a hybrid plate under an affine stretch and shear "
                                  "shall be in equilibrium: largest acceleration ≤ 1e-12 σ/(ρΔx) (the paper's "
                                  "coupling: 1.9)",
                         .measured = full_state_pd,
                         .expected = 1e-12,
                         .compare = Compare::at_most,
                         .tolerance_reason = "round-off: each PD force is a sum of ~30 bond terms of order σΔx "
                                             "that cancel (1e-16 each); 1e-12 is far below any coupling error",
                         .source = kSource,
                         .unit = "σ/(ρΔx)",
                         .problem = kProblem});
  test::record_data(
      kProblem, "01_ghost_forces",
      {{"kind", "table"},
       {"title", "Ghost forces under affine motion: the paper's coupling, the full-state and the blended one"},
       {"columns", {"motion", "coupling", "PD", "transition", "MPM", "all MPM"}},
       {"rows", rows},
       {"caption",
        "Largest acceleration of interior particles of each kind relative to σ/(ρΔx) (a free "
        "face's particle under the same stress), 40 × 30 mm plate, PD disc of radius 7 mm. "
        "paper: a transition particle's PD state comes from half a family and the grid sees a "
        "hole where the PD region is — the residual is of the order of a free face's traction. "
        "full_state (hybrid.coupling): transition particles measure their state over their "
        "whole family, so the PD particles are in equilibrium to round-off (gated); the grid's "
        "hole remains, and with it half the transition particles' residual and a fifth of the "
        "MPM particles'. blended (80 × 80 mm plate, so that its band ends inside): the grid's "
        "stress weighted by 1 − β, each force state by its owner's β; PD in equilibrium to "
        "round-off, transition and MPM residuals falling as 1/blend_width (gated)."}});
}

// A free plate with a PD disc in the middle (none: the all-MPM plate), set vibrating by
// a smooth velocity field in the elastic range: its energy against time — kinetic, the
// grid's stored energy and the PD energy of PD and transition particles (the pair forces
// derive from both: transition_pd_energy). Nothing dissipates in the model, so every
// change is the discretisation's.
struct FreeVibration {
  std::vector<double> t, energy;  // µs, E / E(0)
};

constexpr double kVibrationTime = 200e-6;  // ≈ 8 periods of the plate's lowest modes

// The smooth velocity field that sets the plate vibrating: peak strain ≈ 1e-4, elastic.
Vec<2> vibration_velocity(const Vec<2>& x) { return {0.5 * std::sin(300 * x[1]), 0.4 * std::cos(250 * x[0])}; }

FreeVibration free_vibration(hybrid::Coupling coupling, double disc_radius, int refine = 1) {
  const int steps = static_cast<int>(std::lround(kVibrationTime / kDt)) * refine, every = steps / 20;
  hybrid::Settings s;
  s.mode = hybrid::Mode::expand;
  s.coupling = coupling;
  test::HybridPlate plate;
  plate.size = {0.03, 0.02};
  test::HybridBody body(s, plate);
  auto& p = body.particles();
  const Vec<2> centre(0.015, 0.01);
  std::vector<Index> disc;
  for (Index i = 0; i < p.n_real; ++i) {
    const Vec<2> x = p.x0[i];
    p.v[i] = vibration_velocity(x);
    if ((x - centre).norm() < disc_radius) disc.push_back(i);
  }
  body.hybrid->start(disc);
  FreeVibration r;
  double e0 = 0.0;
  for (int k = 0; k <= steps; ++k) {
    if (k % every == 0) {
      const double e =
          body.hybrid->kinetic_energy() + body.hybrid->internal_energy() + body.hybrid->transition_pd_energy();
      if (k == 0) e0 = e;
      r.t.push_back(body.hybrid->time() * 1e6);
      r.energy.push_back(e / e0);
    }
    if (k < steps) body.hybrid->step(kDt / refine, (k + 1) % every == 0);
  }
  return r;
}

// The all-MPM plate with a conservative force on a ring of particles only — springs to
// their reference positions, f = −k V u — applied as the coupling applies the PD pair
// forces, as particle external forces through the grid. E / E(0) at the end, E counting
// the springs' energy.
double ring_springs_vibration(int refine) {
  test::HybridPlate plate;
  plate.size = {0.03, 0.02};
  test::HybridBody body(hybrid::Settings{}, plate);
  auto& p = body.particles();
  body.hybrid->start();
  const Vec<2> centre(0.015, 0.01);
  std::vector<Index> ring;
  for (Index i = 0; i < p.n_real; ++i) {
    p.v[i] = vibration_velocity(p.x0[i]);
    const double r = (p.x0[i] - centre).norm();
    if (r > 5e-3 && r < 8e-3) ring.push_back(i);
  }
  const double k = 0.1 * 200e9 / (kDx * kDx);  // per volume: a tenth of E/Δx², a bond's order
  auto energy = [&] {
    const mpm::Energies e = body.mpm->energies();
    double springs = 0.0;
    for (const Index i : ring) springs += 0.5 * k * p.volume[i] * p.u[i].squaredNorm();
    return e.kinetic + e.strain + springs;
  };
  double e0 = 0.0;
  const int steps = static_cast<int>(std::lround(kVibrationTime / kDt)) * refine;
  for (int s = 0; s <= steps; ++s) {
    for (const Index i : ring) p.b[i] = -k * p.u[i];
    if (s == 0) e0 = energy();
    if (s < steps) body.mpm->step(kDt / refine);
  }
  return energy() / e0;
}

TEST(FastHybrid, AFreelyVibratingPlateGainsNoEnergy) {
  nlohmann::json series = nlohmann::json::array();
  const FreeVibration mpm_only = free_vibration(hybrid::Coupling::paper, 0.0);
  series.push_back({{"label", "all MPM"}, {"x", mpm_only.t}, {"y", mpm_only.energy}, {"style", "line"}});
  double gain = 0.0;
  for (const auto coupling : {hybrid::Coupling::paper, hybrid::Coupling::full_state, hybrid::Coupling::blended}) {
    const FreeVibration r = free_vibration(coupling, 5e-3);
    series.push_back({{"label", std::string("PD disc, ") + std::string(name(coupling))},
                      {"x", r.t},
                      {"y", r.energy},
                      {"style", "line"}});
    gain = std::max(gain, *std::max_element(r.energy.begin(), r.energy.end()) - 1.0);
  }
  test::record_gate(
      Gate{.id = "hybrid.stability.free_vibration",
           .claim = "a free plate with a PD disc (paper, full-state and blended couplings), set vibrating in the "
                    "elastic range, shall gain no energy over 10 000 steps (200 µs): largest "
                    "(E − E₀)/E₀ ≤ 0.01",
           .measured = gain,
           .expected = 0.01,
           .compare = Compare::at_most,
           .tolerance_reason = "the all-MPM plate's own energy error over the run is 0.2 % (measured, "
                               "plot 09); 1 % is five times that, far below the ×60 growth of an "
                               "unstable coupling (docs/models/hybrid.md)",
           .source = kSource,
           .unit = "",
           .problem = kProblem});
  test::record_data(kProblem, "09_free_vibration",
                    {{"kind", "plot"},
                     {"title", "A freely vibrating plate: total energy against time"},
                     {"xlabel", "t (µs)"},
                     {"ylabel", "E / E(0)"},
                     {"xscale", "linear"},
                     {"yscale", "linear"},
                     {"series", series},
                     {"caption",
                      "30 × 20 mm plate, Δx = 1 mm, Δt = 20 ns, free edges, a smooth initial velocity field "
                      "(peak strain ≈ 1e-4, no yield); E = kinetic energy + the grid's stored energy + the PD "
                      "energy of PD and transition particles (the pair forces derive from both). The all-MPM "
                      "plate keeps its energy within 0.2 %; with a PD disc of radius 5 mm the interface takes "
                      "energy out steadily (paper coupling 11 % in 200 µs; full_state 7 %, after a first "
                      "0.6 % rise: its state-only bonds are not derived from an energy; blended 23 %: its band "
                      "moves more particles with PD forces through the grid). Gated: no gain above 1 %. A coupling "
                      "whose grid feels the PD particles' stress (no ghost forces) grew ×62 "
                      "in 30 000 steps here (docs/models/hybrid.md)."}});
}

// Is the interface's energy loss the time step's? Δt and Δt/2 over the same time, and the
// same for the grid alone under a ring of springs (full tier: 40 000 steps, ≈ 10 s).
TEST(FullHybrid, InterfaceDissipationIsFirstOrderInTime) {
  const double paper_dt = free_vibration(hybrid::Coupling::paper, 5e-3).energy.back();
  const double paper_half = free_vibration(hybrid::Coupling::paper, 5e-3, 2).energy.back();
  const double springs_dt = ring_springs_vibration(1), springs_half = ring_springs_vibration(2);
  nlohmann::json rows = nlohmann::json::array();
  rows.push_back(
      {"hybrid, PD disc, paper coupling", 1.0 - paper_dt, 1.0 - paper_half, (1.0 - paper_dt) / (1.0 - paper_half)});
  rows.push_back({"all MPM, springs on a ring (k = 0.1 E/Δx²)", 1.0 - springs_dt, 1.0 - springs_half,
                  (1.0 - springs_dt) / (1.0 - springs_half)});
  test::record_data(kProblem, "10_interface_dissipation",
                    {{"kind", "table"},
                     {"title", "Energy lost in 200 µs of free vibration, at Δt = 20 ns and at Δt/2"},
                     {"columns", {"plate", "loss at Δt", "loss at Δt/2", "ratio"}},
                     {"rows", rows},
                     {"caption",
                      "A loss of first order in Δt halves with Δt (ratio 2); both plates come near it "
                      "(1.6–1.7). The all-MPM plate with a ring of springs loses energy as the hybrid "
                      "does, so the cause is the route of the force, not PD: a force concentrated on "
                      "particles and handed to them through the grid's shape functions makes the nodal "
                      "velocity increments Δv_I rough, and with a lumped mass and the FLIP update each "
                      "step loses ½ Σ_p m_p Var_p(Δv), the variance of Δv_I over each particle's stencil, "
                      "beyond leapfrog's bounded fluctuation (docs/models/hybrid.md; Love & Sulsky 2006 "
                      "quantify the lumped mass's dissipation). Smooth increments have almost none, which "
                      "is why the free all-MPM plate keeps its energy. The transition particles get the PD "
                      "pair forces this way (eq 10)."}});
  // The observed order log₂(ratio): 1 for a loss first order in Δt, 0 for one Δt cannot
  // reduce (a property of the coupling alone), 2 for second order. Within [0.5, 1.5] it is
  // nearer first order than either (measured 0.80 and 0.67: part of the loss at the end
  // sample is leapfrog's bounded, Δt-independent fluctuation).
  for (const double ratio : {(1.0 - paper_dt) / (1.0 - paper_half), (1.0 - springs_dt) / (1.0 - springs_half)}) {
    EXPECT_GE(std::log2(ratio), 0.5) << "ratio " << ratio;
    EXPECT_LE(std::log2(ratio), 1.5) << "ratio " << ratio;
  }
}

// A plane P pulse (uniaxial strain: rollers on the long edges) running along a strip
// MPM | PD band | MPM, and the same pulse in the all-MPM strip. Probes average v_x over
// the central rows, one before the band and one after it. Until the pulse reaches the
// band the two runs are the same; afterwards their difference at the first probe is the
// wave the band reflects (both its faces).
struct WaveRun {
  std::vector<double> t, before, after;  // probe velocities (m/s)
};

// Lengths in pulse widths w (w ≥ 4 cells: MPM's dispersion would scatter a shorter
// pulse by itself); probes on lattice columns.
struct Strip {
  double w;
  double length() const { return 30 * w; }
  double centre() const { return 5 * w; }
  double band_from() const { return 12.5 * w; }
  double band_to() const { return 17.5 * w; }
  double probe_before() const { return column(8.8 * w); }
  double probe_after() const { return column(23.8 * w); }
  static double column(double x) { return (std::floor(x / kDx) + 0.5) * kDx; }
};
constexpr double kStripHeight = 0.016, kStrainPeak = 1e-4;

// Long-wave speed of uniaxial strain in plane stress: E/(1 − ν²) (both methods calibrate to it).
double uniaxial_wave_speed() { return std::sqrt(200e9 / (1.0 - 0.09) / kRho); }

WaveRun run_wave(const Strip& strip, hybrid::Mode mode, bool band,
                 hybrid::Coupling coupling = hybrid::Coupling::paper) {
  hybrid::Settings s;
  s.mode = mode;
  s.coupling = coupling;
  test::HybridPlate plate;
  plate.size = {strip.length(), kStripHeight};
  plate.hardening = "yield_stress = 1e12\ntangent_modulus = 0";
  plate.tables =
      "[[boundary]]\nname = \"bottom\"\nkind = \"velocity\"\n"
      "region = { type = \"box\", min = [-1, -1], max = [1, 0.5e-3] }\nvalue = [\"free\", \"0\"]\n"
      "[[boundary]]\nname = \"top\"\nkind = \"velocity\"\n"
      "region = { type = \"box\", min = [-1, 15.5e-3], max = [1, 1] }\nvalue = [\"free\", \"0\"]\n";
  test::HybridBody body(s, plate);
  auto& p = body.particles();
  const double c = uniaxial_wave_speed();
  // Right-going: u = A g(x − ct), so v = −c A g'(x) and ε_xx = A g'(x) at t = 0.
  const double w = strip.w, A = kStrainPeak * w * std::exp(0.5);
  std::vector<Index> pd_band, before, after;
  for (Index i = 0; i < p.n_real; ++i) {
    const double x = p.x0[i][0], y = p.x0[i][1], xi = (x - strip.centre()) / w;
    const double g = A * std::exp(-0.5 * xi * xi), dg = -xi / w * g;
    p.u[i] = Vec<2>(g, 0.0);
    p.v[i] = Vec<2>(-c * dg, 0.0);
    Mat<2> F = Mat<2>::Identity();
    F(0, 0) += dg;
    body.mpm->set_deformation_gradient(i, F);
    if (band && x > strip.band_from() && x < strip.band_to()) pd_band.push_back(i);
    const bool central = std::abs(y - 0.5 * kStripHeight) < 3e-3;  // PD's free-edge layer is δ wide
    if (central && std::abs(x - strip.probe_before()) < 0.5 * kDx) before.push_back(i);
    if (central && std::abs(x - strip.probe_after()) < 0.5 * kDx) after.push_back(i);
  }
  body.hybrid->start(pd_band);
  WaveRun r;
  auto mean_vx = [&](const std::vector<Index>& at) {
    double v = 0.0;
    for (const Index i : at) v += p.v[i][0];
    return v / static_cast<double>(at.size());
  };
  // Until the pulse has passed the second probe, before the far edge's echo comes back.
  const int steps = static_cast<int>((strip.probe_after() - strip.centre() + 3 * w) / c / kDt);
  for (int n = 1; n <= steps; ++n) {
    body.hybrid->step(kDt);
    r.t.push_back(body.hybrid->time());
    r.before.push_back(mean_vx(before));
    r.after.push_back(mean_vx(after));
  }
  return r;
}

double largest_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) m = std::max(m, std::abs(a[k] - b[k]));
  return m;
}

// Speed of the pulse between the probes: the lag maximising the cross-correlation of
// the two probe signals, refined by a parabola through the peak.
double pulse_speed(const WaveRun& r, const Strip& strip) {
  const auto n = static_cast<long>(r.t.size());
  auto correlation = [&](long lag) {
    double c = 0.0;
    for (long k = 0; k + lag < n; ++k) c += r.before[k] * r.after[k + lag];
    return c;
  };
  long best = 1;
  for (long lag = 1; lag < n - 1; ++lag)
    if (correlation(lag) > correlation(best)) best = lag;
  const double y0 = correlation(best - 1), y1 = correlation(best), y2 = correlation(best + 1);
  const double lag = static_cast<double>(best) + 0.5 * (y0 - y2) / (y0 - 2 * y1 + y2);
  return (strip.probe_after() - strip.probe_before()) / (lag * kDt);
}

TEST(FastHybrid, PlaneWaveCrossesTheInterface) {
  std::vector<double> widths, reflections, full_state_reflections;
  nlohmann::json rows = nlohmann::json::array(), series = nlohmann::json::array();
  double impedance_reflection = 0.0;
  for (const double w : {8e-3, 16e-3}) {
    const Strip strip{w};
    const WaveRun mpm = run_wave(strip, hybrid::Mode::expand, false);
    const WaveRun hybrid = run_wave(strip, hybrid::Mode::expand, true);
    const double incident = largest_difference(mpm.before, std::vector<double>(mpm.t.size(), 0.0));
    const double reflected = largest_difference(hybrid.before, mpm.before) / incident;
    const WaveRun full = run_wave(strip, hybrid::Mode::expand, true, hybrid::Coupling::full_state);
    full_state_reflections.push_back(largest_difference(full.before, mpm.before) / incident);
    widths.push_back(w);
    reflections.push_back(reflected);
    const double c_mpm = pulse_speed(mpm, strip);
    if (w == 8e-3) {
      // The impedance mismatch of the two discretisations (same ρ, their own long-wave
      // speeds): the reflection a perfect coupling of these two methods would still show.
      const double c_pd = pulse_speed(run_wave(strip, hybrid::Mode::pd, false), strip);
      impedance_reflection = std::abs(c_pd - c_mpm) / (c_pd + c_mpm);
      rows.push_back({"speed MPM, PD (m/s); uniaxial-strain theory 5291", c_mpm, c_pd});
      std::vector<double> t_us, in, diff;
      for (std::size_t k = 0; k < mpm.t.size(); ++k) {
        t_us.push_back(1e6 * mpm.t[k]);
        in.push_back(mpm.before[k] / incident);
        diff.push_back((hybrid.before[k] - mpm.before[k]) / incident);
      }
      series.push_back({{"label", "all MPM (incident)"}, {"x", t_us}, {"y", in}, {"style", "line"}});
      series.push_back({{"label", "hybrid − all MPM (reflected)"}, {"x", t_us}, {"y", diff}, {"style", "line"}});
    }
    const std::string width = "pulse width " + std::to_string(static_cast<int>(std::round(w * 1e3))) + " mm (" +
        std::to_string(static_cast<int>(std::round(w / (3.015 * kDx)))) + " δ)";
    rows.push_back({width, reflected, largest_difference(hybrid.after, mpm.after) / incident});
    rows.push_back({width + ", full_state coupling", full_state_reflections.back(),
                    largest_difference(full.after, mpm.after) / incident});
  }
  // Reflection ∝ (δ/w)^q: an interface whose error is confined to a δ-wide layer
  // reflects a long wave at first order (q = 1); at w = 3–5δ it is not yet asymptotic.
  const double order = std::log(reflections[0] / reflections[1]) / std::log(widths[1] / widths[0]);
  rows.push_back({"impedance-mismatch reflection |c_PD − c_MPM|/(c_PD + c_MPM)", impedance_reflection, ""});
  rows.push_back({"observed order of the reflection in δ/w", order, ""});
  test::record_gate(Gate{.id = "hybrid.wave.reflection_order",
                         .claim = "the reflection of a plane P pulse by a PD band in MPM (the paper's coupling, "
                                  "Δx = 1 mm) shall vanish as the pulse lengthens: observed order in δ/w ≥ 0.5 "
                                  "between pulse widths of 8 and 16 mm",
                         .measured = order,
                         .expected = 0.5,
                         .compare = Compare::at_least,
                         .tolerance_reason = "a coupling error confined to a δ-wide layer reflects at first order in "
                                             "δ/w; half of it allows the pre-asymptotic range at w = 2.7–5.3δ",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
  test::record_gate(Gate{.id = "hybrid.wave.reflection",
                         .claim = "the same band shall reflect at most 15 % of a 16 mm (5δ) pulse (the impedance-"
                                  "matched value is 0)",
                         .measured = reflections[1],
                         .expected = 0.15,
                         .compare = Compare::at_most,
                         .tolerance_reason = "regression bound, not the paper's: the paper's coupling is not "
                                             "consistent (ghost forces, table 01); 15 % is 1.5 × the measured 10 %",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
  test::record_gate(Gate{.id = "hybrid.wave.reflection_full_state",
                         .claim = "with the full-state coupling the band shall reflect at most 5 % of a 16 mm (5δ) "
                                  "pulse (the paper's coupling 10 %; the two discretisations' impedance mismatch "
                                  "alone 2.2 %)",
                         .measured = full_state_reflections[1],
                         .expected = 0.05,
                         .compare = Compare::at_most,
                         .tolerance_reason = "regression bound, not a claim of the paper: 1.5 × the measured 3.5 %, "
                                             "the grid's hole at the PD region (table 01) still reflects",
                         .source = kSource,
                         .unit = "",
                         .problem = kProblem});
  test::record_data(kProblem, "05_wave_reflection",
                    {{"kind", "table"},
                     {"title", "Plane pulse through a PD band: reflected and transmitted waves"},
                     {"columns", {"case", "reflected / incident", "transmitted error / incident"}},
                     {"rows", rows},
                     {"caption",
                      "Strip 30w × 16 mm, rollers on the long edges (uniaxial strain), Δx = 1 mm, δ = 3.015Δx, "
                      "cell 2Δx; PD band 5w wide; probes average v_x over the central 6 rows. Reflected: "
                      "largest difference hybrid − all-MPM at the probe before the band; transmitted error: "
                      "the same after it (mostly the phase lead of PD, whose pulse runs 2.4 % faster than the "
                      "continuum's long wave in this strip: its edge layers, 0.6 % in a 48 mm strip; "
                      "docs/models/hybrid.md)."}});
  test::record_data(kProblem, "06_wave_signals",
                    {{"kind", "plot"},
                     {"title", "Plane pulse (w = 8 mm) at the probe before the PD band"},
                     {"xlabel", "t (µs)"},
                     {"ylabel", "v_x / incident peak"},
                     {"xscale", "linear"},
                     {"yscale", "linear"},
                     {"series", series},
                     {"caption",
                      "The incident pulse passes at 3–10 µs; the echoes of the MPM → PD face (≈ 17 µs) and of "
                      "the PD → MPM face (≈ 32 µs) are the hybrid's difference from the all-MPM run."}});
}

}  // namespace
}  // namespace pdmpm
