#include "benchmarks/perf/perf_evidence.hpp"

#include <fmt/format.h>

#include <cmath>

#include "benchmarks/perf/perf_output.hpp"

namespace pdmpm::perf {
namespace {

using nlohmann::json;

std::string upper(const std::string& m) { return m == "pmb" ? "PMB" : m == "lps" ? "LPS" : m; }

std::string ci(const json& r) {
  return fmt::format("{:.3g} [{:.3g}, {:.3g}]", r["value"].get<double>(), r["ci95"][0].get<double>(),
                     r["ci95"][1].get<double>());
}

// Bond evaluations per second with the interval of evals / median(t) (stats.hpp).
Ratio rate(const json& run, const char* code, const char* key) {
  return ratio_of_medians({run["bond_evaluations_per_rep"].get<double>()}, run[code][key].get<std::vector<double>>());
}

void lammps_items(const json& lammps) {
  json rows = json::array();
  json ours = {{"label", "pdmpm (bond kernel + contact)"}, {"style", "points"}};
  json theirs = {{"label", "LAMMPS (Pair)"}, {"style", "points"}};
  json values = json::array(), labels = json::array();
  double x = 1.0;
  for (const auto& run : lammps) {
    if (run.contains("skipped")) continue;
    const std::string m = run["model"];
    const Ratio a = rate(run, "pdmpm", "force_s"), b = rate(run, "lammps", "pair_s");
    for (auto [s, r, dx] : {std::tuple{&ours, a, -0.08}, std::tuple{&theirs, b, 0.08}}) {
      (*s)["x"].push_back(x + dx);
      (*s)["y"].push_back(r.value);
      (*s)["ylo"].push_back(r.lo);
      (*s)["yhi"].push_back(r.hi);
    }
    values.push_back(x);
    labels.push_back(upper(m) + " (" + run["lammps_style"].get<std::string>() + ")");
    x += 1.0;
    const auto& per = run["bond_evals_per_s_per_core"];
    rows.push_back({upper(m), run["particles"], run["bond_sides"], run["steps"], run["reps"], per["pdmpm"],
                    per["pdmpm_kernel_only"], per["lammps"], ci(run["speedup_force_vs_pair"]),
                    ci(run["speedup_steps_vs_loop"]), run["max_rel_displacement_difference"]});
  }
  if (rows.empty()) return;
  std::string notes;
  for (const auto& run : lammps) {
    if (run.contains("skipped")) continue;
    const double contact = median(run["pdmpm"]["contact_s"].get<std::vector<double>>());
    const double force = median(run["pdmpm"]["force_s"].get<std::vector<double>>());
    notes += fmt::format("<li>{}: pdmpm's short-range contact takes {:.0f} % of its force time; its bond kernels alone do "
                         "{} times LAMMPS' Pair rate (interval in brackets).</li>",
                         upper(run["model"]), 100.0 * contact / force, ci(run["speedup_kernel_vs_pair"]));
  }
  test::record_data(problem, "01a_lammps_parts",
                    {{"kind", "text"},
                     {"title", "Where pdmpm's force time goes"},
                     {"html", "<ul>" + notes + "</ul><p>The contact loop (solver/pd/contact.cpp) rebuilds a cell list "
                              "of the deformed positions every step and takes two square roots per candidate pair; "
                              "LAMMPS' contact loop reads a neighbour list it rebuilds only when atoms have moved "
                              "half a skin. Both are in the compared time, as both codes evaluate the same "
                              "contact rule.</p>"}});
  test::record_data(problem, "01_lammps_table",
                    {{"kind", "table"},
                     {"title", "pdmpm vs LAMMPS PERI, one core each, same problem"},
                     {"columns", {"model", "particles", "bond sides", "steps", "reps", "pdmpm bond evals/s",
                                  "pdmpm kernel only", "LAMMPS bond evals/s (Pair)", "speed-up [95 % CI]",
                                  "whole steps speed-up [95 % CI]", "max |Δu| / max |u|"}},
                     {"rows", rows},
                     {"caption", "Bond evaluations = bond sides × steps (LPS: both passes count as one evaluation). "
                                 "pdmpm: the model's bond kernels plus short-range contact; LAMMPS: its Pair time, "
                                 "which holds its bond forces and its short-range contact loop. Whole steps: pdmpm's "
                                 "time-step loop against LAMMPS' Loop time less Output. Medians of interleaved "
                                 "repetitions in one process run; intervals: bootstrap of the ratio of medians."}});
  test::record_data(problem, "02_lammps_rates",
                    {{"kind", "plot"},
                     {"title", "Bond evaluations per second per core: pdmpm vs LAMMPS"},
                     {"ylabel", "bond evaluations / s (one core)"},
                     {"yscale", "log"},
                     {"xticks", {{"values", values}, {"labels", labels}}},
                     {"series", {ours, theirs}},
                     {"caption", "Medians with bootstrap 95 % intervals (bars)."}});
}

void kernel_items(const json& k) {
  if (k.is_null()) return;
  const std::string n = std::to_string(k["threads"].get<int>());
  json series = json::array();
  json rows = json::array();
  series.push_back({{"label", "ideal"}, {"x", {1, k["threads"]}}, {"y", {1, k["threads"]}}, {"style", "dashed"}});
  double shift = -0.02;  // keeps the models' interval bars apart
  for (const auto& [model, m] : k["models"].items()) {
    const auto& s = m["speedup_threads"];
    series.push_back({{"label", upper(model) + " force kernel"},
                      {"x", {1.0, k["threads"].get<double>() + shift}},
                      {"y", {1.0, s["value"]}},
                      {"ylo", {1.0, s["ci95"][0]}},
                      {"yhi", {1.0, s["ci95"][1]}},
                      {"style", "line"}});
    shift = -shift;
  }
  test::record_data(problem, "03_thread_scaling",
                    {{"kind", "plot"},
                     {"title", "Thread scaling of the force kernels"},
                     {"xlabel", "OpenMP threads"},
                     {"ylabel", "speed-up over 1 thread"},
                     {"xticks", {{"values", {1, k["threads"]}}, {"labels", {"1", n}}}},
                     {"series", series},
                     {"caption", fmt::format("Ratio of medians of interleaved repetitions on the {:.3g}-bond-side "
                                             "problem (bars: bootstrap 95 %); target ≥ 1.8 on 2 threads.",
                                             k["models"]["pmb"]["bond_sides"].get<double>())}});

  // Roofline in bond units: x = bond sides per byte moved, y = bond sides per second.
  const double bw1 = k["triad_best_bytes_per_s"]["1"], bwn = k["triad_best_bytes_per_s"][n];
  series = json::array();
  const std::vector<double> xs = {0.02, 0.05, 0.1, 0.2, 0.5, 1.0};
  json roof1 = {{"label", "memory roof, 1 thread (triad)"}, {"style", "line"}};
  json roofn = {{"label", "memory roof, " + n + " threads (triad)"}, {"style", "line"}};
  for (double x : xs) {
    roof1["x"].push_back(x), roof1["y"].push_back(bw1 * x);
    roofn["x"].push_back(x), roofn["y"].push_back(bwn * x);
  }
  series.push_back(roof1);
  series.push_back(roofn);
  for (const auto& [model, m] : k["models"].items()) {
    const double x = 1.0 / m["bytes_per_bond_side"].get<double>();
    series.push_back({{"label", upper(model) + " measured (1, " + n + " threads)"},
                      {"x", {x, x}},
                      {"y", {m["bond_sides_per_s"]["1"], m["bond_sides_per_s"][n]}},
                      {"style", "points"}});
    series.push_back({{"label", upper(model) + " in cache, 1 thread (ceiling)"},
                      {"x", {xs.front(), xs.back()}},
                      {"y", {m["in_cache_bond_sides_per_s"]["1"], m["in_cache_bond_sides_per_s"]["1"]}},
                      {"style", "dashed"}});
    rows.push_back({upper(model), m["bytes_per_bond_side"], m["bond_sides_per_s"]["1"], m["bond_sides_per_s"][n],
                    m["bandwidth_bound_bond_sides_per_s"]["1"], m["bandwidth_bound_bond_sides_per_s"][n],
                    m["bandwidth_fraction"]["1"], m["bandwidth_fraction"][n], m["in_cache_bond_sides_per_s"]["1"],
                    m["cycles_per_bond_side_1_thread"], ci(m["speedup_threads"])});
  }
  test::record_data(problem, "04_roofline",
                    {{"kind", "plot"},
                     {"title", "Roofline in bond units"},
                     {"xlabel", "bond sides per byte moved (1 / bytes per bond side)"},
                     {"ylabel", "bond sides / s"},
                     {"xscale", "log"},
                     {"yscale", "log"},
                     {"series", series},
                     {"caption", fmt::format("Memory roofs: triad bandwidth × bond sides per byte. Points: the force "
                                             "kernels on the {:.3g}-bond-side problem at their byte account (table "
                                             "below). Dashed: the same kernel on the {:.3g}-bond-side problem (refine 1), "
                                             "held in cache — the rate memory is not in the way of.",
                                             k["models"]["pmb"]["bond_sides"].get<double>(),
                                             k["models"]["pmb"]["in_cache_bond_sides"].get<double>())}});
  test::record_data(problem, "05_roofline_table",
                    {{"kind", "table"},
                     {"title", "Force kernels: rates, bandwidth bound and thread scaling (" + k["simd"].get<std::string>() +
                                   " kernels)"},
                     {"columns", {"model", "bytes / bond side", "bond sides/s, 1 thread", "bond sides/s, " + n + " threads",
                                  "memory bound, 1 thread", "memory bound, " + n + " threads",
                                  "bandwidth fraction, 1 thread", "bandwidth fraction, " + n + " threads",
                                  "in cache, 1 thread", "cycles / bond side", "speed-up " + n + " threads [95 % CI]"}},
                     {"rows", rows},
                     {"caption", fmt::format("Triad (best of {} passes): {:.3g} GB/s on 1 thread, {:.3g} GB/s on {}. "
                                             "Cycles at the nominal clock ({:.0f} MHz).",
                                             k["reps"].get<int>(), bw1 / 1e9, bwn / 1e9, n, k["cpu_mhz"].get<double>())}});
  json account = json::array();
  for (const auto& [model, m] : k["models"].items())
    for (const auto& item : m["byte_account"]) account.push_back({upper(model), item[0], item[1]});
  test::record_data(problem, "06_byte_account",
                    {{"kind", "table"},
                     {"title", "Bytes moved per bond side, from the data layout"},
                     {"columns", {"model", "item", "bytes / bond side"}},
                     {"rows", account},
                     {"caption", "Streamed arrays only (benchmarks/perf/bytes_per_bond.hpp): gathered neighbour data "
                                 "is reused from cache (lattice order) and not counted, which makes the memory bound "
                                 "an upper bound on the rate memory allows."}});
  const auto& pmb = k["models"]["pmb"];
  const double in_cache = pmb["in_cache_bond_sides_per_s"]["1"], from_mem = pmb["bond_sides_per_s"]["1"];
  test::record_data(problem, "07_bandwidth_account",
                    {{"kind", "text"},
                     {"title", "What limits the PMB kernel"},
                     {"html", fmt::format(
                                  "<p>On {} threads the PMB kernel moves {:.0f} % of the triad bandwidth by the byte "
                                  "account. On one thread it does {:.3g} bond sides/s from memory and {:.3g} on a "
                                  "problem that fits in cache (×{:.2f}): {} About {:.0f} cycles per bond side go to "
                                  "the scalar gather of each neighbour's index, displacement, volume and broken flag "
                                  "into vector lanes, and to one square root and one division per bond — the "
                                  "instruction stream, not the {:.1f} bytes per bond side, sets the pace.</p>",
                                  n, 100.0 * pmb["bandwidth_fraction"][n].get<double>(), from_mem, in_cache,
                                  in_cache / from_mem,
                                  in_cache < 1.3 * from_mem
                                      ? "keeping every array in cache hardly helps, so memory bandwidth is not the limit."
                                      : "cache residency helps noticeably, so memory traffic is part of the limit.",
                                  pmb["cycles_per_bond_side_1_thread"].get<double>(),
                                  pmb["bytes_per_bond_side"].get<double>())}});
}

void memory_items(const json& memory, const json& lammps) {
  if (memory.empty()) return;
  json rows = json::array();
  for (const auto& m : memory)
    rows.push_back({upper(m["model"]), m["bond_sides"], m["particles"], m["peak_bytes_per_bond"],
                    m["resident_bytes_per_bond"], m["layout_bytes_per_bond"], nullptr});
  for (const auto& run : lammps)
    if (!run.contains("skipped") && run["lammps"]["memory_mbytes_estimate"].get<double>() > 0)
      rows.push_back({"LAMMPS " + run["lammps_style"].get<std::string>(), run["bond_sides"], run["particles"], nullptr,
                      nullptr, nullptr,
                      run["lammps"]["memory_mbytes_estimate"].get<double>() * 1048576.0 / run["bond_sides"].get<double>()});
  test::record_data(problem, "08_memory",
                    {{"kind", "table"},
                     {"title", "Memory per bond side"},
                     {"columns", {"code", "bond sides", "particles", "peak RSS growth / bond side [B]",
                                  "RSS growth / bond side [B]", "layout account [B]", "LAMMPS' own estimate [B]"}},
                     {"rows", rows},
                     {"caption", "pdmpm: growth of VmHWM (reset first) and VmRSS while building the problem and "
                                 "evaluating its first forces, over the bond sides. LAMMPS: its log's \"Per MPI rank "
                                 "memory allocation\" (its arrays, not measured residency) over its bond sides."}});
}

void context_item(const json& c) {
  json rows = json::array();
  for (const char* key : {"cpu", "cores", "compiler", "flags", "simd", "git_sha", "tree", "date", "load_average_start",
                          "load_average_end"})
    if (c.contains(key)) rows.push_back({key, c[key].is_string() ? c[key].get<std::string>() : c[key].dump()});
  rows.push_back({"options", c["options"].dump()});
  test::record_data(problem, "09_context",
                    {{"kind", "table"},
                     {"title", "Where and how these numbers were measured"},
                     {"columns", {"item", "value"}},
                     {"rows", rows},
                     {"caption", "A load average above 0 at the start means other work shared the cores: the ratios "
                                 "are measured interleaved, but a shared memory bus and cores still bend them. "
                                 "Re-measure with ci/bench.sh on a quiet machine."}});
}

}  // namespace

void record_evidence(const Collected& c) {
  lammps_items(c.lammps);
  kernel_items(c.kernels);
  memory_items(c.memory, c.lammps);
  context_item(c.context);
}

}  // namespace pdmpm::perf
