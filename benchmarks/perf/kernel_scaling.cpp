#include "benchmarks/perf/kernel_scaling.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <fstream>

#include "benchmarks/bench_bodies.hpp"
#include "benchmarks/perf/bytes_per_bond.hpp"
#include "benchmarks/perf/perf_output.hpp"
#include "benchmarks/perf/perf_problem.hpp"
#include "benchmarks/perf/triad.hpp"
#include "solver/pd/kernels/bond_kernels.hpp"
#include "solver/sim/pd_setup.hpp"

namespace pdmpm::perf {
namespace {

using nlohmann::json;

struct Body {
  std::string model;
  sim::PdSetup<3> setup;
  double sides = 0.0;
};

Body make_body(const std::string& model, int refine) {
  Body b{model, sim::build_pd<3>(perf_scene(model, refine)), 0.0};
  bench::deform(b.setup.system);  // every bond stretched a little, as in a run
  b.sides = static_cast<double>(b.setup.system.families.n_bonds());
  return b;
}

// Seconds per force evaluation, averaged over `calls` after one warm-up call.
double seconds_per_call(Body& b, int threads, int calls) {
  omp_set_num_threads(threads);
  pd::ForceRequest req;
  b.setup.model->compute_forces(b.setup.system, req);
  const double t0 = omp_get_wtime();
  for (int k = 0; k < calls; ++k) b.setup.model->compute_forces(b.setup.system, req);
  return (omp_get_wtime() - t0) / calls;
}

double cpu_mhz() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("cpu MHz", 0) == 0) return std::stod(line.substr(line.find(':') + 1));
  return 0.0;
}

}  // namespace

json kernel_scaling(const Options& o) {
  const int threads = std::min(2, omp_get_num_procs());
  fmt::print("Force kernels: thread scaling 1 → {} and roofline (refine {}, {} repetitions, simd {})\n", threads,
             o.refine, o.reps, pd::kernels::simd_level());
  const int before = omp_get_max_threads();
  std::vector<Body> big, small;
  for (const char* m : {"pmb", "lps"}) {
    big.push_back(make_body(m, o.refine));
    small.push_back(make_body(m, 1));
  }
  // Enough calls on the small body that one sample takes about as long as one on the big one.
  const int small_calls = o.kernel_calls * std::max(1, static_cast<int>(big[0].sides / small[0].sides));
  Triad triad;
  std::vector<double> bw1, bw2;
  std::vector<std::vector<double>> t1(2), t2(2), c1(2), c2(2);
  for (int r = 0; r < o.reps; ++r) {
    bw1.push_back(triad.bytes_per_second(1));
    bw2.push_back(triad.bytes_per_second(threads));
    for (std::size_t m = 0; m < big.size(); ++m) {
      t1[m].push_back(seconds_per_call(big[m], 1, o.kernel_calls));
      t2[m].push_back(seconds_per_call(big[m], threads, o.kernel_calls));
      c1[m].push_back(seconds_per_call(small[m], 1, small_calls));
      c2[m].push_back(seconds_per_call(small[m], threads, small_calls));
    }
    fmt::print("  rep {}: triad {:.1f} / {:.1f} GB/s, PMB {:.3g} / {:.3g} s, LPS {:.3g} / {:.3g} s (1 / {} threads)\n",
               r + 1, bw1.back() / 1e9, bw2.back() / 1e9, t1[0].back(), t2[0].back(), t1[1].back(), t2[1].back(),
               threads);
  }
  omp_set_num_threads(before);

  // STREAM reports the best pass: the bandwidth the machine can deliver.
  const double bw_1 = *std::max_element(bw1.begin(), bw1.end());
  const double bw_n = *std::max_element(bw2.begin(), bw2.end());
  const double mhz = cpu_mhz();
  // The machine's own 1 → n scaling of memory traffic: a kernel that streams
  // from memory or the shared last-level cache cannot be expected to beat it by much.
  const Ratio triad_scaling = ratio_of_medians(bw2, bw1);
  json out = {{"threads", threads},
              {"reps", o.reps},
              {"kernel_calls", o.kernel_calls},
              {"simd", pd::kernels::simd_level()},
              {"cpu_mhz", mhz},
              {"triad_bytes_per_s", {{"1", bw1}, {std::to_string(threads), bw2}}},
              {"triad_best_bytes_per_s", {{"1", bw_1}, {std::to_string(threads), bw_n}}},
              {"triad_speedup_threads", to_json(triad_scaling)},
              {"models", json::object()}};
  for (std::size_t m = 0; m < big.size(); ++m) {
    const std::string& model = big[m].model;
    const ByteAccount bytes = bytes_per_bond(big[m].setup.system, model);
    const double sides = big[m].sides;
    const Ratio scaling = ratio_of_medians(t1[m], t2[m]);
    const double rate1 = sides / median(t1[m]), rate_n = sides / median(t2[m]);
    const double cache1 = small[m].sides / median(c1[m]), cache_n = small[m].sides / median(c2[m]);
    const double frac1 = rate1 * bytes.total / bw_1, frac_n = rate_n * bytes.total / bw_n;
    json account = json::array();
    for (const auto& [name, b] : bytes.items) account.push_back({name, b});
    out["models"][model] = {{"bond_sides", sides},
                            {"particles", big[m].setup.system.n_real()},
                            {"seconds_per_evaluation", {{"1", t1[m]}, {std::to_string(threads), t2[m]}}},
                            {"in_cache_seconds_per_evaluation", {{"1", c1[m]}, {std::to_string(threads), c2[m]}}},
                            {"in_cache_bond_sides", small[m].sides},
                            {"speedup_threads", to_json(scaling)},
                            {"bond_sides_per_s", {{"1", rate1}, {std::to_string(threads), rate_n}}},
                            {"in_cache_bond_sides_per_s", {{"1", cache1}, {std::to_string(threads), cache_n}}},
                            {"bytes_per_bond_side", bytes.total},
                            {"byte_account", account},
                            {"bandwidth_fraction", {{"1", frac1}, {std::to_string(threads), frac_n}}},
                            {"bandwidth_bound_bond_sides_per_s",
                             {{"1", bw_1 / bytes.total}, {std::to_string(threads), bw_n / bytes.total}}},
                            {"cycles_per_bond_side_1_thread", mhz > 0 ? mhz * 1e6 / rate1 : 0.0}};
    const std::string name = model == "pmb" ? "PMB" : "LPS";
    target({.id = "performance.threads_" + model,
            .claim = fmt::format(
                "the {} force kernel shall run at least 1.8× faster on 2 threads than on 1 ({:.3g} bond sides)", name,
                sides),
            .measured = scaling.value,
            .expected = 1.8,
            .tolerance = 0.0,
            .compare = test::Compare::at_least,
            .tolerance_reason = fmt::format(
                "a target (issue 6). Ratio of medians of {} interleaved repetitions; bootstrap 95 % interval "
                "[{:.3g}, {:.3g}]. Gather-only loops need no atomics; the two cores share the last-level cache "
                "and the memory bus: the triad in the same run scales {:.2f}× (interval [{:.3g}, {:.3g}]); "
                "in-cache problem {:.2f}×",
                o.reps, scaling.lo, scaling.hi, triad_scaling.value, triad_scaling.lo, triad_scaling.hi,
                median(c1[m]) / median(c2[m])),
            .source = "[pdmpm] docs/design.md (performance targets)",
            .unit = "×",
            .problem = problem});
    if (model == "pmb")
      target({.id = "performance.bandwidth_fraction_pmb",
              .claim = fmt::format(
                  "the PMB force kernel on {} threads shall move at least 50 % of the memory bandwidth a triad "
                  "reaches on as many threads, counting {:.2f} bytes per bond side from the data layout",
                  threads, bytes.total),
              .measured = frac_n,
              .expected = 0.5,
              .tolerance = 0.0,
              .compare = test::Compare::at_least,
              .tolerance_reason = fmt::format(
                  "a target (issue 6), with a written account when missed: the same kernel on a problem that "
                  "fits in the last-level cache runs at {:.3g} bond sides/s on 1 thread against {:.3g} from "
                  "memory (×{:.2f}); {:.1f} cycles per bond side at the nominal clock",
                  cache1, rate1, cache1 / rate1, mhz > 0 ? mhz * 1e6 / rate1 : 0.0),
              .source = "[pdmpm] docs/design.md (performance targets); STREAM triad [mccalpin1995]",
              .unit = "",
              .problem = problem});
  }
  return out;
}

}  // namespace pdmpm::perf
