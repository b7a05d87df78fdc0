#pragma once
// The report's "performance" section from the driver's raw results: headline
// table, bond evaluations per second (pdmpm vs LAMMPS, with intervals), thread
// scaling, a roofline in bond units, memory per bond, the byte account, the run's
// context — as evidence items under <results>/data/performance/.
#include <nlohmann/json.hpp>

namespace pdmpm::perf {

struct Collected {
  nlohmann::json memory = nlohmann::json::array();  // memory_per_bond() per model
  nlohmann::json kernels;                            // kernel_scaling()
  nlohmann::json lammps = nlohmann::json::array();   // lammps_side_by_side() per model
  nlohmann::json context;
};

// Writes what the collected parts allow (a part not run leaves its items out).
void record_evidence(const Collected& c);

}  // namespace pdmpm::perf
