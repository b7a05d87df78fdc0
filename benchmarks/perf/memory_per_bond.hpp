#pragma once
// Resident memory per bond side: the growth of this process' peak resident set
// (VmHWM, reset first) while it builds the 10⁷-bond problem (perf_problem.hpp,
// refine 3 whatever the other parts use) and evaluates its first forces,
// divided by the bond sides — families, per-bond state and every per-particle
// array a run holds, spread over the bonds. Next to it, the account from the data
// layout (what the arrays should take).
#include <nlohmann/json.hpp>
#include <string>

namespace pdmpm::perf {

// model: "pmb" or "lps"; `gate`: record the ≤ 16 bytes target (PMB). Returns the raw results.
nlohmann::json memory_per_bond(const std::string& model, bool gate);

}  // namespace pdmpm::perf
