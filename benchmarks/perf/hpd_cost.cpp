#include "benchmarks/perf/hpd_cost.hpp"

#include <fmt/format.h>
#include <omp.h>

#include "benchmarks/bench_bodies.hpp"
#include "benchmarks/perf/force_call_time.hpp"
#include "benchmarks/perf/perf_output.hpp"
#include "benchmarks/perf/stats.hpp"
#include "solver/pd/hpd.hpp"
#include "solver/pd/lps.hpp"

namespace pdmpm::perf {

nlohmann::json hpd_cost(const Options& o) {
  // 8³ sites per refine step, at most 16³: the nD law stores ~0.4 MB of sub-horizon per particle
  // at δ = 3.015Δx (16³ = 4096 particles, ~1.7 GB); the other drivers' 60³ would not fit.
  const int n = std::min(8 * o.refine, 16);
  fmt::print("HPD cost: hpd (linear_elastic, axial_1d) against lps on a {}³ cube, 1 thread, {} repetitions\n", n,
             o.reps);
  const int before = omp_get_max_threads();
  omp_set_num_threads(1);
  auto sys = bench::lattice_body<3>(n);  // ν = ¼: PMB's, so axial_1d accepts it too
  bench::deform(sys);                    // strains ~1e-4
  auto axial_sys = sys;
  sys.hpd.law = pd::HpdLaw::linear_elastic;
  axial_sys.hpd.law = pd::HpdLaw::axial_1d;
  pd::Lps<3> lps;
  pd::Hpd<3> nd, axial;
  lps.initialise(sys);
  nd.initialise(sys);
  axial.initialise(axial_sys);
  std::vector<double> t_lps, t_nd, t_axial;
  for (int r = 0; r < o.reps; ++r) {
    t_lps.push_back(seconds_per_force_call(lps, sys, o.kernel_calls));
    t_nd.push_back(seconds_per_force_call(nd, sys, o.kernel_calls));
    t_axial.push_back(seconds_per_force_call(axial, axial_sys, o.kernel_calls));
    fmt::print("  rep {}: lps {:.3g} s, hpd linear_elastic {:.3g} s, hpd axial_1d {:.3g} s\n", r + 1, t_lps.back(),
               t_nd.back(), t_axial.back());
  }
  omp_set_num_threads(before);
  const Ratio r_nd = ratio_of_medians(t_nd, t_lps), r_axial = ratio_of_medians(t_axial, t_lps);
  const double sides = static_cast<double>(sys.families.n_bonds());
  const double slots = static_cast<double>(nd.sub_horizon().point.size());
  fmt::print(
      "  per bond side against lps ({:.3g} bond sides, {:.3g} sub-horizon slots): linear_elastic {:.3g}× "
      "[{:.3g}, {:.3g}], axial_1d {:.3g}× [{:.3g}, {:.3g}]\n",
      sides, slots, r_nd.value, r_nd.lo, r_nd.hi, r_axial.value, r_axial.lo, r_axial.hi);
  return {{"bond_sides", sides},
          {"sub_horizon_slots", slots},
          {"particles", sys.n_real()},
          {"seconds_per_evaluation", {{"lps", t_lps}, {"hpd_linear_elastic", t_nd}, {"hpd_axial_1d", t_axial}}},
          {"ratio_linear_elastic", to_json(r_nd)},
          {"ratio_axial_1d", to_json(r_axial)}};
}

}  // namespace pdmpm::perf
