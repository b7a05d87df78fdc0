#pragma once
// Runs the same PD problem in LAMMPS' PERI package (Parks et al. 2008; the
// Debian package `lammps`, command `lmp`) next to pdmpm: a validated 3D scene
// and the particles pdmpm built from it become a LAMMPS data file (same
// particles, volumes and density, atom id = pdmpm index + 1) and an input
// script (same horizon, micromodulus or moduli, critical stretch, lattice
// constant, indenter, supports, time step and number of steps); `lmp` runs it
// and its dump is read back in pdmpm's particle order.
//
// What LAMMPS does (read in src/PERI: pair_peri_pmb.cpp, pair_peri_lps.cpp,
// fix_peri_neigh.cpp, compute_damage_atom.cpp; src/set.cpp, fix_nve.cpp,
// fix_indent.cpp), and how the translation keeps the two codes on one model:
//  - family: partners with |ξ| ≤ δ at the start; partial volume
//    (δ + lc/2 − |ξ|)/lc for | |ξ| − δ | ≤ lc/2, lc = the lattice constant: pdmpm's
//    "seed001" rule, so scenes must use it; `lattice sc Δx` sets lc.
//  - PERI atoms carry force densities: their per-atom "mass" is the density
//    (set/read_data), so f/m = acceleration. fix indent's K(r − R)² is thus a
//    force density: pdmpm's indenter law "force_density" maps to K directly,
//    law "force" to K = k / V.
//  - peri/pmb: f = c s V_j β ŷ with c from pair_coeff (constant ω only);
//    peri/lps: 3D LPS with ω = 1/|ξ| (pdmpm influence "inverse_distance").
//  - critical stretch: s₀ = s00 − α·(min bond stretch of the previous step); the
//    translation sets α = 0 (pdmpm's fixed s₀). A bond breaks after its force
//    has been applied in that step (pdmpm: before).
//  - LAMMPS builds the bond families (fix PERI_NEIGH setup) only after the force
//    evaluation of a run's set-up, so that evaluation leaves each atom's s₀ at an
//    uninitialised value (s0_new is never written) and bonds break at random in
//    the first step: seen with peri/lps (damage with s₀₀ = 1e100; displacements
//    1 % off by step 10). The input therefore starts with `run 0`, whose set-up
//    builds the families; the real run's set-up then sets s₀ = s₀₀ − α s.
//  - short-range contact (15 c/δ)(r − d) with d = min(0.9|ξ|, 1.35 lc) acts on
//    every pair closer than d, bonded or not, always: pdmpm matches it with
//    [model.contact] bonded_pairs = true (defaults otherwise).
//  - integrator: fix nve, velocity Verlet, the same as pdmpm's.
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "solver/io/scene.hpp"
#include "solver/sim/pd_setup.hpp"

namespace pdmpm::test::lammps {

// The command that runs LAMMPS: $PDMPM_LAMMPS, else "lmp".
std::string executable();
// True if the command is found on PATH (or is an executable path).
bool available();

struct Options {
  std::filesystem::path work_dir;  // input, data, dump and log are written here
  std::int64_t steps = 0;
  double dt = 0.0;
  std::int64_t dump_every = 0;     // 0: the first and last step only
  int threads = 1;                 // OMP_NUM_THREADS for lmp
};

struct Input {
  std::string script;  // in.pdmpm
  std::string data;    // data.pdmpm
};

// Builds the LAMMPS input for a scene and the setup pdmpm built from it. Throws
// std::invalid_argument naming the scene feature LAMMPS cannot reproduce.
Input make_input(const io::Scene& scene, const sim::PdSetup<3>& setup, const Options& options);

struct Frame {
  std::int64_t step = 0;
  std::vector<std::array<double, 3>> x, v;  // by pdmpm particle index
  std::vector<double> damage;               // compute damage/atom
};

struct Result {
  std::vector<Frame> frames;
  double loop_seconds = 0.0;  // LAMMPS' own "Loop time" (the time steps only)
  double wall_seconds = 0.0;  // the whole lmp process, set-up included
  // The log's "MPI task timing breakdown": average seconds per section (Pair, Neigh,
  // Comm, Output, Modify, Other) of the time-step loop. Pair is the force computation.
  std::map<std::string, double> sections;
  double memory_mbytes = 0.0;  // "Per MPI rank memory allocation" (LAMMPS' own estimate, max)
  std::int64_t bonds = 0;     // "total # of bonds" LAMMPS reports (bond sides)
  std::string version;        // from the log's first line, e.g. "7 Jan 2022"
  std::string log;            // log.pdmpm
};

// Writes the input, runs lmp in options.work_dir and reads the dump back.
// Throws std::runtime_error when lmp fails (its log's tail in the message).
Result run(const io::Scene& scene, const sim::PdSetup<3>& setup, const Options& options);

// Reads a LAMMPS text dump with columns id x y z vx vy vz c_damage (any order).
std::vector<Frame> read_dump(const std::filesystem::path& path, std::size_t particles);

// Average seconds per section of the last "MPI task timing breakdown" in a log.
std::map<std::string, double> timing_breakdown(const std::string& log);

// Broken bond sides implied by a damage field when all volumes are equal:
// φ_i = (broken sides of i)/(family size of i), so Σ φ_i n_i (rounded).
std::int64_t broken_sides_from_damage(const std::vector<double>& damage, const core::Families<3>& families);

}  // namespace pdmpm::test::lammps
