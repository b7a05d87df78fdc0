#pragma once
// Probes ([[probe]] in a scene): the particle nearest a point, whose u and v go
// into history.csv.
#include <string>
#include <vector>

#include "solver/core/types.hpp"
#include "solver/dist/communicator.hpp"
#include "solver/dist/decomposition.hpp"
#include "solver/io/scene.hpp"
#include "solver/sim/run_metrics.hpp"

namespace pdmpm::sim {

struct Probe {
  std::string name;
  Index particle = -1;  // its index in the store; -1 where another process owns it
  int owner = 0;        // the process that owns it (a distributed run)
};

// Throws InputError(probe[k].point) if no real particle lies within √D Δx of a point.
// Distributed (`comm`, this process owning `own` of a body of `n_body` particles): the
// nearest particle of every process's, the lowest global index on a tie, as in one process.
template <int D>
std::vector<Probe> locate_probes(const io::Scene& s, const std::vector<Vec<D>>& x0, Index n_real,
                                 const dist::Communicator* comm = nullptr, dist::OwnedRange own = {}, Index n_body = 0);

// history.csv columns of the probes: probe_<name>_u<x…>, then _v<x…>, per probe.
template <int D>
void add_probe_columns(const std::vector<Probe>& probes, std::vector<std::string>& columns) {
  for (const auto& pr : probes)
    for (const char* q : {"u", "v"})
      for (int a = 0; a < D; ++a) columns.push_back("probe_" + pr.name + "_" + q + axis_name(a));
}

// Their values, in the same order. Distributed (`comm`), the process that owns a probe's
// particle sends its u and v to every process.
template <int D>
void add_probe_values(const std::vector<Probe>& probes, const std::vector<Vec<D>>& u, const std::vector<Vec<D>>& v,
                      std::vector<double>& row, const dist::Communicator* comm = nullptr) {
  for (const auto& pr : probes) {
    std::vector<double> values(2 * D, 0.0);
    if (pr.particle >= 0)
      for (int a = 0; a < D; ++a) values[a] = u[pr.particle][a], values[D + a] = v[pr.particle][a];
    if (comm) comm->broadcast(values, pr.owner);
    row.insert(row.end(), values.begin(), values.end());
  }
}

}  // namespace pdmpm::sim
