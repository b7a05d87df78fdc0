#include "solver/sim/initial_from_scene.hpp"

#include "solver/core/error.hpp"
#include "solver/sim/geometry_from_scene.hpp"

namespace pdmpm::sim {
namespace {

// Per component: the expression, or nothing for "free" or a key the table left out.
template <int D>
std::array<std::optional<bc::Expression>, D> components(const std::vector<std::string>& text) {
  std::array<std::optional<bc::Expression>, D> e;
  if (text.empty()) return e;
  for (int a = 0; a < D; ++a)
    if (text[a] != "free") e[a] = bc::Expression::parse(text[a]);
  return e;
}

}  // namespace

template <int D>
std::vector<bc::InitialCondition<D>> make_initial_conditions(const io::Scene& s, const core::Particles<D>& p,
                                                             const dist::Communicator* comm) {
  std::vector<bc::InitialCondition<D>> out;
  for (const auto& spec : s.initials) {
    bc::InitialCondition<D> c;
    if (spec.region.empty()) {
      for (Index i = 0; i < p.n_real; ++i) c.particles.push_back(i);
    } else {
      c.particles = select_particles<D>(p.x0, p.n_real, make_geometry<D>(spec.region), s.spacing);
      const auto selected = static_cast<std::int64_t>(c.particles.size());
      if ((comm ? comm->sum(selected) : selected) == 0)
        throw InputError(s.file, spec.key + ".region",
                         "selects no particle (particles sit on lattice sites; check the region against the body)");
    }
    c.velocity = components<D>(spec.velocity);
    c.displacement = components<D>(spec.displacement);
    out.push_back(std::move(c));
  }
  return out;
}

template std::vector<bc::InitialCondition<1>> make_initial_conditions<1>(const io::Scene&, const core::Particles<1>&,
                                                                         const dist::Communicator*);
template std::vector<bc::InitialCondition<2>> make_initial_conditions<2>(const io::Scene&, const core::Particles<2>&,
                                                                         const dist::Communicator*);
template std::vector<bc::InitialCondition<3>> make_initial_conditions<3>(const io::Scene&, const core::Particles<3>&,
                                                                         const dist::Communicator*);

}  // namespace pdmpm::sim
