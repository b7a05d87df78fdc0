#pragma once
// The bond loops of PMB and LPS, written for SIMD.
//
// Every particle sums its family in a canonical order: bond b of the family
// (counted from the family's start) goes to lane b mod 8, each lane accumulates
// its bonds in increasing order, and the eight lane sums are combined in a fixed
// tree. The result therefore does not depend on the SIMD width the compiler
// picks (SSE2, AVX2, AVX-512 — the same source is compiled once per instruction
// set and chosen at run time) nor on the number of threads: every build on every
// x86-64 machine gives bitwise identical forces. Broken bonds and padding lanes
// are masked with selects, never multiplied by 0, so a degenerate bond cannot
// turn into NaN.
#include <cstdint>

#include "solver/core/index.hpp"

namespace pdmpm::pd::kernels {

inline constexpr int lanes = 8;

// The bond flag (pd/bond_state.hpp) of a bond that counts in its owner's state but
// exchanges no force: lps_plastic's first pass takes it, every force pass skips it.
inline constexpr std::uint8_t kStateOnlyFlag = 8;

// Per-stencil-offset data, structure of arrays, each padded with `lanes` zeros
// so a block starting at any stencil row can be loaded whole; and the same as
// rows, for blocks whose offsets are scattered.
struct BondShapeTable {
  const double* xi[3];   // reference bond vector components
  const double* length;  // |ξ|
  const double* weight;  // ω β
  const double* rows;    // 4 per offset: ξ (D components), |ξ|, zeros; `lanes` zero rows of padding
};

// Bond arrays (neighbor, shape, broken) are padded with `lanes` entries past the
// last bond (core::Families, pd::System), so a block may read 8 entries anywhere.
struct FamilyView {
  Index n_owners;      // particles visited
  const Index* owner;  // their indices, increasing (nullptr: 0 … n_owners − 1)
  Index n_sites;       // particles a neighbour index may name (real + ghosts): the extent of u
  const BondIndex* offsets;
  const Index* neighbor;
  const std::uint16_t* shape;
  std::uint8_t* broken;   // per-bond flags (pd/bond_state.hpp): live when 0; a new break sets 1
  bool state_only_bonds;  // some flag is kStateOnlyFlag alone (a hybrid's full-state transition particles)

  Index particle(Index k) const { return owner ? owner[k] : k; }
};

struct PmbArgs {
  FamilyView fam;
  BondShapeTable table;
  const double* u;       // displacements, D per particle (real + ghosts)
  const double* volume;  // per particle
  bool uniform_volume;   // every volume equals volume[0] (lattice bodies): not gathered per bond
  double* f;             // force density out, D per real particle
  double* energy;        // W_i out (nullptr: not computed)
  double c;              // micromodulus
  bool breaking;
  double s0;
  bool after_force;  // break after acting, at s > s₀ (LAMMPS) instead of before, at s ≥ s₀
};

struct LpsArgs {
  FamilyView fam;
  BondShapeTable table;
  const double* u;
  const double* volume;
  bool uniform_volume;       // as in PmbArgs
  const double* m;           // weighted volume, real + ghosts
  double* theta;             // dilatation, real + ghosts (pass 1 writes real ones)
  const double* alpha_beta;  // (A θ / m, B / m) per particle, interleaved (pass 2 reads, real + ghosts; 0 where m = 0)
  double* f;
  double* energy;
  double A, B, kappa, gamma;
  int d;  // dimension in θ = (d/m) Σ ω β |ξ| e V
  bool breaking;
  double s0;
  bool after_force;  // as in PmbArgs: pass 1 keeps such bonds, pass 2 breaks them
};

// lps_plastic's bond loops (solver/pd/lps_plastic.hpp). The first is LPS's
// dilatation pass that also measures θ_c with the deviatoric weights c ωβ and, in a
// second sweep over the same family (in cache), the trial deviatoric extension
// ε = e − γθ_c|ξ| − p_n of every bond of the state (live, or kStateOnlyFlag: such a
// bond counts in θ, θ_c and the norm but never breaks) and Σ c ωβ V ε²; it then hands the
// particle, with its family's ε, to the model's return mapping, which scales the
// elastic deviator by r. The second sums the pair forces (t_ij + t_ji) β V_j y/|y| with
// t_ij/ω = μ_i |ξ| + c s_i ε_ij, μ = (mean term)/m and s = r B/m_d per particle. It forms
// both sides' ε itself, ε_ij from p_ij and ε_ji = e − γθ_c,j|ξ| − p_ji from a copy of p_ji
// kept at the bond (the model updates it where particles flowed), so no pass reads or
// writes another particle's bonds and no ε is stored: every bond value is read in
// family order.
struct LpsPlasticArgs {
  LpsArgs lps;                      // LPS's fields (γ too): pass 1 writes lps.theta; the force pass lps.f, lps.energy
  const double* shell;              // c per stencil offset, padded with `lanes` entries
  const double* inv_md;             // 1/m_d per particle (0 where m_d = 0)
  const double* plastic_extension;  // committed p per bond side, padded
  const double* reverse_plastic;    // committed p_ji of each bond side i→j (a copy at the bond), padded
  double* theta_c;                  // θ_c = (d/m_d) Σ c ωβ |ξ| e V per real particle (pass 1 out)
  double* norm2;                    // Σ c ωβ V ε² per real particle (pass 1 out)
  // The model's return mapping of particle i, called by pass 1 when θ, θ_c and the norm are
  // known, with eps[b − begin] = ε of each bond side b of i's state in its family [begin, end).
  void (*return_map)(void* model, Index i, const double* eps);
  void* model;
  const double* particle_rows;      // (μ, s, γθ_c, 0) per particle (force pass)
  const double* volumetric_energy;  // per particle: W_i's volumetric part (force pass, with energy)
  const double* scale;              // r per particle (force pass, with energy)
  double B;                         // deviatoric modulus of t (15G, 8G, E)
};

// Each returns the number of bond sides broken by the call.
template <int D>
std::int64_t pmb_forces(const PmbArgs& a);
template <int D>
std::int64_t lps_dilatation(const LpsArgs& a);
template <int D>
std::int64_t lps_forces(const LpsArgs& a);
template <int D>
std::int64_t lps_plastic_extension(const LpsPlasticArgs& a);
template <int D>
std::int64_t lps_plastic_forces(const LpsPlasticArgs& a);

// Which instruction set the dispatcher chose: "avx512", "avx2" or "sse2".
// PDMPM_SIMD=sse2|avx2|avx512 in the environment forces a (supported) choice.
const char* simd_level();

}  // namespace pdmpm::pd::kernels
