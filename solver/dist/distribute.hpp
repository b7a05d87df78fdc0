#pragma once
// Splits a body between the processes of a run: each makes particles for its own
// sites and its halo only (solver/dist/decomposition.hpp), the halo kept current by
// messages (solver/dist/halo_exchange.hpp). Every process keeps the whole body's sites
// as sorted Morton keys (core/body_sites.hpp, 8 bytes a site); families and bonds are
// built for its own particles alone.
#include <memory>
#include <vector>

#include "solver/core/particles.hpp"
#include "solver/dist/communicator.hpp"
#include "solver/dist/decomposition.hpp"
#include "solver/dist/halo_exchange.hpp"

namespace pdmpm::dist {

// Where a process's particles sit in the whole body.
struct Ownership {
  Index global_count = 0;                  // real particles of the whole body
  OwnedRange own;                          // its own particles' global indices
  std::vector<Index> halo;                 // its remote ghosts' global indices, in store order
  std::int64_t whole_body_bonds = 0;       // its own particles' bonds in the whole body
  std::int64_t values_sent = 0;            // values it sends per exchanged scalar
  int neighbours = 0;                      // processes it exchanges with
  std::shared_ptr<HaloExchange> exchange;  // the store's `remote`
};

// This process's store of `body`, with the halo every bond of a family of
// `family_ratio` lattice spacings needs; the exchange is set as the store's `remote`.
template <int D>
core::Particles<D> distribute(const Communicator& comm, const core::BodySites<D>& body, double family_ratio,
                              Ownership& ownership);

}  // namespace pdmpm::dist
