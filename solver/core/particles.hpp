#pragma once
// Structure-of-arrays particle store. Real particles come first, [0, n_real);
// ghosts follow: mirror ghosts (symmetry planes) copy their owner's reflected
// state, remote ghosts (a distributed run's halo, solver/dist/) receive the state
// of a particle another process owns.
// A particle's kind says which solver integrates it, so a particle can later move
// between MPM and PD without being copied. `removed` is for good: a particle the
// hybrid took out of the body at ductile failure (no solver integrates it, no
// bond reaches it; it stays in the store so indices never move).
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "solver/core/lattice.hpp"
#include "solver/core/state_archive.hpp"
#include "solver/core/types.hpp"

namespace pdmpm::core {

// The other processes of a distributed run as a particle store sees them
// (solver/dist/halo_exchange.hpp): they fill its remote ghosts and join its sums.
class OtherProcesses {
 public:
  virtual ~OtherProcesses() = default;
  // The remote ghosts' entries of a per-particle array (`width` doubles per particle).
  virtual void fill(double* data, int width) const = 0;
  // `n` sums over the particles of every process in their global order: add_own adds
  // this process's terms to `partial`, which arrives holding the processes' before it;
  // `partial` returns the totals, the same on every process.
  virtual void ordered_sum(double* partial, int n, const std::function<void(double*)>& add_own) const = 0;
  // The largest of every process's `local` (exact in any order).
  virtual double max(double local) const = 0;
  // The global index of this process's first own particle (own particles are contiguous).
  virtual Index first_global() const = 0;
  // Per-bond-side state (lps_plastic's plastic extension): for every bond side i→j of this
  // store whose j is a remote ghost, `reverse[i→j]` receives the value `sides` holds at j→i
  // on j's process (and this process's `sides[i→j]` goes to it). Needs the families
  // (dist::HaloExchange::index_bond_sides).
  virtual void fill_reverse_sides(const double* sides, double* reverse) const = 0;
  // The number of processes, this process's rank, and remote ghost g's (store index
  // n_real + g) global index and owner.
  virtual int processes() const = 0;
  virtual int rank() const = 0;
  virtual Index ghost_global(Index g) const = 0;
  virtual int ghost_owner_rank(Index g) const = 0;
  // Values of any length to other processes (`to[q]` to process q, one entry per process):
  // returns what each process sent this one, by rank.
  virtual std::vector<std::vector<double>> send_to(const std::vector<std::vector<double>>& to) const = 0;
};

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

  // Ghost g (index n_real + g) mirrors ghost_owner[g] with per-axis signs ghost_sign[g];
  // a remote ghost has owner kRemoteOwner and takes its values from `remote`.
  static constexpr Index kRemoteOwner = -1;
  std::vector<Index> ghost_owner;
  std::vector<Vec<D>> ghost_sign;
  std::shared_ptr<const OtherProcesses> remote;

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
    // Remote ghosts first: a mirror may mirror one.
    if (remote) {
      remote->fill(u.data()->data(), D);
      remote->fill(v.data()->data(), D);
    }
    const Index ng = n_ghost();
    for (Index g = 0; g < ng; ++g) {
      const Index o = ghost_owner[g], i = n_real + g;
      if (o == kRemoteOwner) continue;
      u[i] = u[o].cwiseProduct(ghost_sign[g]);
      v[i] = v[o].cwiseProduct(ghost_sign[g]);
    }
  }

  // A per-particle scalar (an orientation-free quantity: dilatation, weighted volume)
  // in the ghosts' entries: their owner's value.
  void fill_ghosts(std::vector<double>& a) const {
    if (remote) remote->fill(a.data(), 1);  // first: a mirror may mirror a remote ghost
    const Index ng = n_ghost();
    for (Index g = 0; g < ng; ++g)
      if (ghost_owner[g] != kRemoteOwner) a[n_real + g] = a[ghost_owner[g]];
  }

  // N sums over particles from `start`, taken in the global particle order: add_own(s)
  // adds this store's terms to s[0..N); with other processes the sums continue theirs
  // in rank order, so a distributed total is the one-process total to the bit.
  template <int N, class Fn>
  std::array<double, N> sum_in_order(Fn&& add_own, std::array<double, N> start = {}) const {
    auto s = start;
    if (remote)
      remote->ordered_sum(s.data(), N, [&](double* partial) { add_own(partial); });
    else
      add_own(s.data());
    return s;
  }

  // The largest of `local` over the processes of a run.
  double max_everywhere(double local) const { return remote ? remote->max(local) : local; }
  // A real particle's or remote ghost's index in the whole body (a one-process run: its
  // index here; a distributed run's mirror ghosts have none).
  Index global_index(Index i) const {
    if (!remote) return i;
    return i < n_real ? remote->first_global() + i : remote->ghost_global(i - n_real);
  }

  // The particle whose state a particle carries: itself, a mirror ghost's owner, or
  // itself for a remote ghost (its entries are the remote owner's, received).
  Index source(Index i) const {
    if (i < n_real) return i;
    const Index o = ghost_owner[i - n_real];
    return o == kRemoteOwner ? i : o;
  }
};

}  // namespace pdmpm::core
