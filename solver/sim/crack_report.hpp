#pragma once
// Crack observables (solver/pd/crack_observables.hpp) as a run reports them:
// history columns and values, and the summary's metrics.crack.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/pd/crack_observables.hpp"

namespace pdmpm::sim {

template <int D>
std::vector<std::string> crack_columns(const pd::CrackObservables<D>& c);
template <int D>
void crack_values(const pd::CrackObservables<D>& c, std::vector<double>& row);
template <int D>
nlohmann::json crack_summary(const pd::CrackObservables<D>& c, const pd::System<D>& sys);

}  // namespace pdmpm::sim
