#include "benchmarks/perf/memory_per_bond.hpp"

#include <fmt/format.h>

#include "benchmarks/perf/memory_status.hpp"
#include "benchmarks/perf/perf_output.hpp"
#include "benchmarks/perf/perf_problem.hpp"
#include "solver/time/velocity_verlet.hpp"
#include "solver/sim/pd_setup.hpp"

namespace pdmpm::perf {

nlohmann::json memory_per_bond(const std::string& model, bool gate) {
  constexpr int refine = 3;
  fmt::print("Memory per bond: {} (refine {})\n", model, refine);
  const io::Scene scene = perf_scene(model, refine);
  const MemoryStatus before = memory_status();
  const bool reset = reset_peak();
  MemoryStatus after;
  double sides = 0.0, particles = 0.0, layout_bond = 0.0, layout_particle = 0.0;
  {
    auto setup = sim::build_pd<3>(scene);
    auto state = sim::make_simulation(setup);
    time::VelocityVerlet<3> stepper(state, perf_dt(refine));
    stepper.start();
    after = memory_status();
    const auto& sys = setup.system;
    sides = static_cast<double>(sys.families.n_bonds());
    particles = static_cast<double>(sys.particles.size());
    // The layout: per bond side a neighbour (int32), a stencil index (uint16) and a
    // broken flag (uint8); per particle the CSR offset (int64) and the particle arrays
    // (site, x0, u, v, f, b, volume, kind) plus what the integrator keeps (u_old, b_old)
    // and, for LPS, m, θ, Aθ/m, 1/m and B/m.
    layout_bond = sizeof(Index) + sizeof(std::uint16_t) + sizeof(std::uint8_t);
    layout_particle = sizeof(BondIndex) + sizeof(IVec<3>) + 7 * sizeof(Vec<3>) + sizeof(double) + 1 +
        (model == "lps" ? 5 * sizeof(double) : 0);
  }
  const double peak = (after.peak_bytes - before.resident_bytes) / sides;
  const double resident = (after.resident_bytes - before.resident_bytes) / sides;
  const double layout = layout_bond + layout_particle * particles / sides;
  fmt::print("  {:.4g} bond sides: peak {:.2f} B/bond, resident {:.2f} B/bond, layout account {:.2f} B/bond\n", sides,
             peak, resident, layout);
  if (gate)
    target(
        {.id = "performance.memory_per_bond",
         .claim = fmt::format("building and starting the {:.3g}-bond-side 3D {} problem shall raise the process' peak "
                              "resident memory by at most 16 bytes per bond side (families, per-bond state and all "
                              "per-particle arrays of a run)",
                              sides, model == "pmb" ? "PMB" : "LPS"),
         .measured = peak,
         .expected = 16.0,
         .tolerance = 0.0,
         .compare = test::Compare::at_most,
         .tolerance_reason = reset
             ? "a target (issue 6); VmHWM was reset before the build, so the number is the build's own peak"
             : "a target (issue 6); VmHWM could not be reset (/proc/self/clear_refs refused): the peak may "
               "include earlier allocations and overstate the cost",
         .source = "[pdmpm] docs/design.md (performance targets); /proc/self/status VmHWM, VmRSS",
         .unit = "B",
         .problem = problem});
  return {{"model", model},
          {"refine", refine},
          {"bond_sides", sides},
          {"particles", particles},
          {"baseline_resident_bytes", before.resident_bytes},
          {"peak_reset", reset},
          {"peak_bytes_per_bond", peak},
          {"resident_bytes_per_bond", resident},
          {"layout_bytes_per_bond", layout},
          {"layout", {{"per_bond_side", layout_bond}, {"per_particle", layout_particle}}}};
}

}  // namespace pdmpm::perf
