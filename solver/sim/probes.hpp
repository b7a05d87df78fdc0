#pragma once
// Probes ([[probe]] in a scene): the particle nearest a point, whose u and v go
// into history.csv.
#include <string>
#include <vector>

#include "solver/core/types.hpp"
#include "solver/io/scene.hpp"

namespace pdmpm::sim {

struct Probe {
  std::string name;
  Index particle = -1;
};

// Throws InputError(probe[k].point) if no real particle lies within √D Δx of a point.
template <int D>
std::vector<Probe> locate_probes(const io::Scene& s, const std::vector<Vec<D>>& x0, Index n_real);

}  // namespace pdmpm::sim
