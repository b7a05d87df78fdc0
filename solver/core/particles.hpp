#pragma once
// Structure-of-arrays particle store. Real particles come first, [0, n_real);
// mirror ghosts (symmetry planes) follow and copy their owner's reflected state.
// A particle's kind says which solver integrates it, so a particle can later move
// between MPM and PD without being copied. `removed` is for good: a particle the
// hybrid took out of the body at ductile failure (no solver integrates it, no
// bond reaches it; it stays in the store so indices never move).
#include <cstdint>
#include <vector>

#include "solver/core/lattice.hpp"
#include "solver/core/state_archive.hpp"
#include "solver/core/types.hpp"

namespace pdmpm::core {

enum class ParticleKind : std::uint8_t { pd = 0, mpm = 1, transition = 2, removed = 3 };

template <int D>
struct Particles {
  Lattice<D> lattice;
  std::vector<IVec<D>> site;   // integer lattice coordinates
  std::vector<Vec<D>> x0;      // reference position
  std::vector<Vec<D>> u;       // displacement
  std::vector<Vec<D>> v;       // velocity
  std::vector<Vec<D>> f;       // internal force density (N/m^3), real particles only
  std::vector<Vec<D>> b;       // external force density (N/m^3), real particles only
  std::vector<double> volume;  // V_i
  std::vector<ParticleKind> kind;
  Index n_real = 0;

  // Ghost g (index n_real + g) mirrors ghost_owner[g] with per-axis signs ghost_sign[g].
  std::vector<Index> ghost_owner;
  std::vector<Vec<D>> ghost_sign;

  Index size() const { return static_cast<Index>(site.size()); }
  Index n_ghost() const { return size() - n_real; }
  Vec<D> position(Index i) const { return x0[i] + u[i]; }

  // Append one particle at a lattice site (fields zero).
  void push_back(const IVec<D>& s, double vol) {
    site.push_back(s);
    x0.push_back(lattice.position(s));
    u.push_back(Vec<D>::Zero());
    v.push_back(Vec<D>::Zero());
    f.push_back(Vec<D>::Zero());
    b.push_back(Vec<D>::Zero());
    volume.push_back(vol);
    kind.push_back(ParticleKind::pd);
  }

  // What changes in a run (core/state_archive.hpp); the lattice, sites and ghost
  // mirrors are the scene's and are rebuilt from it.
  void checkpoint(StateArchive& a) {
    a.expect("particles/count", size());
    a.expect("particles/real", n_real);
    a.sync("particles/u", u);
    a.sync("particles/v", v);
    a.sync("particles/f", f);
    a.sync("particles/b", b);
    a.sync("particles/volume", volume);
    a.sync("particles/kind", kind);
  }

  // Copy each owner's displacement and velocity, reflected, into its ghosts.
  void update_ghosts() {
    const Index ng = n_ghost();
    for (Index g = 0; g < ng; ++g) {
      const Index o = ghost_owner[g], i = n_real + g;
      u[i] = u[o].cwiseProduct(ghost_sign[g]);
      v[i] = v[o].cwiseProduct(ghost_sign[g]);
    }
  }
};

}  // namespace pdmpm::core
