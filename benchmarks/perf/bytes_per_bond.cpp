#include "benchmarks/perf/bytes_per_bond.hpp"

namespace pdmpm::perf {

ByteAccount bytes_per_bond(const pd::System<3>& sys, const std::string& model) {
  const auto& fam = sys.families;
  const double sides = static_cast<double>(fam.n_bonds());
  BondIndex partial = 0;  // bond sides in families that are not the whole stencil
  for (Index i = 0; i < fam.n_owners(); ++i)
    if (fam.end(i) - fam.begin(i) != fam.stencil.size()) partial += fam.end(i) - fam.begin(i);
  const double passes = model == "lps" ? 2.0 : 1.0;
  const double per_particle_share = static_cast<double>(fam.n_owners()) / sides;
  ByteAccount a;
  a.items = {
      {"neighbour index (int32)", passes * sizeof(Index)},
      {"broken flag (uint8)", passes * sizeof(std::uint8_t)},
      {"stencil index (uint16), partial families only", passes * sizeof(std::uint16_t) * static_cast<double>(partial) / sides},
      {"per particle: offset, u_i, V_i (each pass)", passes * (sizeof(BondIndex) + 3 * sizeof(double) + sizeof(double)) * per_particle_share},
      {"per particle: f_i written", 3 * sizeof(double) * per_particle_share},
  };
  if (model == "lps")  // pass 1 reads m, writes θ; pass 2 reads α = Aθ/m, B/m, θ
    a.items.push_back({"per particle: m, θ, α, B/m", 5 * sizeof(double) * per_particle_share});
  for (const auto& [name, bytes] : a.items) a.total += bytes;
  return a;
}

}  // namespace pdmpm::perf
