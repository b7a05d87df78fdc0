#include "solver/sim/pd_setup.hpp"

#include <limits>
#include <cmath>
#include <stdexcept>

#include "solver/bc/symmetry.hpp"
#include "solver/core/error.hpp"
#include "solver/core/particle_builder.hpp"
#include "solver/pd/constants.hpp"
#include "solver/pd/precrack.hpp"
#include "solver/sim/geometry_from_scene.hpp"
#include "solver/sim/initial_from_scene.hpp"

namespace pdmpm::sim {
namespace {

template <int D>
void add_constraint(const io::Scene& s, const io::BoundarySpec& b, std::vector<Index> particles, PdSetup<D>& out) {
  bc::Constraint<D> c;
  c.name = b.name;
  c.particles = std::move(particles);
  switch (b.kind) {
    case io::BoundaryKind::fixed:
      c.kind = bc::ConstraintKind::fixed;
      break;
    case io::BoundaryKind::displacement:
      c.kind = bc::ConstraintKind::displacement;
      break;
    case io::BoundaryKind::velocity:
      c.kind = bc::ConstraintKind::velocity;
      break;
    case io::BoundaryKind::analytic:
      c.kind = bc::ConstraintKind::analytic;
      break;
    case io::BoundaryKind::traction:
      break;
  }
  for (int a = 0; a < D; ++a) {
    const bool fully = b.kind == io::BoundaryKind::fixed || b.kind == io::BoundaryKind::analytic;
    c.active[a] = fully || b.value[a] != "free";
    if (!fully && c.active[a]) c.value[a] = bc::Expression::parse(b.value[a]);
  }
  if (b.kind == io::BoundaryKind::analytic)
    c.field = bc::make_analytic_field<D>(b.callback, b.parameters, s.material, s.setting);
  out.boundaries.constraints.push_back(std::move(c));
}

// What a distributed run does not take yet (docs/models/distributed.md), refused by key.
void check_distributable(const io::Scene& s) {
  const auto refuse = [&](const std::string& key, const std::string& what) {
    throw InputError(s.file, key, what + " is not available in a distributed run yet (run it as one process)");
  };
  if (!pd::model_info(s.model).distributed)
    refuse("model.type", "model \"" + s.model + "\" (its forces reach beyond a horizon's halo)");
  // A distributed contact list holds the processes' own particles, not their mirrors.
  if (!s.symmetries.empty() && s.contact.enabled)
    refuse(s.symmetries.front().key, "a symmetry plane with short-range contact");
}

std::vector<bc::SymmetryPlane> symmetry_planes(const io::Scene& s) {
  std::vector<bc::SymmetryPlane> planes;
  for (const auto& sym : s.symmetries) planes.push_back({sym.key, sym.axis, sym.position});
  return planes;
}

double family_reach(const io::Scene& s) { return pd::family_ratio(s.partial_volume, s.delta, s.spacing) * s.spacing; }

// The planes against the whole body's sites: their bounds over every process's own.
template <int D>
void check_symmetry_planes(const io::Scene& s, const core::Particles<D>& p, const dist::Communicator* comm) {
  if (s.symmetries.empty()) return;
  auto [lowest, highest] = bc::real_site_bounds(p);
  if (comm)
    for (int a = 0; a < D; ++a) {
      lowest[a] = static_cast<std::int32_t>(comm->min(lowest[a]));
      highest[a] = static_cast<std::int32_t>(comm->max(highest[a]));
    }
  bc::check_symmetry_planes<D>(p.lattice, lowest, highest, symmetry_planes(s), family_reach(s), s.file);
}

// A halo too thin would leave bonds out of families without a trace: the bonds of every
// process's own particles to real particles and the halo (not to mirrors) must be those
// their sites have in the whole body. A failure is a bug, reported by every process alike.
template <int D>
void check_families_whole(const pd::System<D>& sys, const dist::Ownership& ownership, const dist::Communicator& comm) {
  const Index held_ghosts = sys.particles.n_real + static_cast<Index>(ownership.halo.size());
  std::int64_t held = 0;
  for (BondIndex b = 0; b < sys.families.n_bonds(); ++b) held += sys.families.neighbor[b] < held_ghosts;
  const std::int64_t missing = comm.sum(ownership.whole_body_bonds - held);
  if (missing != 0)
    throw RunError("the processes' families hold " + std::to_string(missing) +
                   " bonds fewer than the whole body's (a halo too thin: a bug, please report it)");
}

// The scene's model settings on a system (its particles aside).
template <int D>
void set_model_settings(pd::System<D>& sys, const io::Scene& s) {
  sys.setting = s.setting;
  sys.material = s.material;
  sys.delta = s.delta;
  sys.measure = D == 3 ? 1.0 : s.measure;
  sys.influence = s.influence;
  sys.partial_volume = s.partial_volume;
  sys.continuum_weighted_volume = s.continuum_weighted_volume;
  if (pd::model_info(s.model).plastic) {
    sys.hardening = s.hardening;
    sys.ductile_failure = s.failure;
  }
  if (s.model == "hpd" && s.hpd.law == pd::HpdLaw::j2) sys.hardening = s.hardening;
  sys.isotropic_deviatoric = s.isotropic_deviatoric;
  sys.yield_on_live_bonds = s.yield_on_live_bonds;
  sys.hpd = s.hpd;
}

}  // namespace

template <int D>
PdSetup<D> build_pd(const io::Scene& s, const dist::Communicator* comm) {
  PdSetup<D> out;
  auto& sys = out.system;
  const bool distributed = comm && comm->size() > 1;
  // Counts over the whole body, for the checks that a region or pre-crack acts somewhere.
  const auto everywhere = [&](std::int64_t local) { return distributed ? comm->sum(local) : local; };
  // Probes and J-integral rings are placed in the whole body; symmetry planes checked against it.
  if (distributed) {
    check_distributable(s);
    // Every process keeps the whole body as site keys and makes particles for its own
    // sites and their halo only (docs/models/distributed.md).
    const auto body = body_sites_of<D>(s);
    out.ownership.emplace();
    sys.particles =
        dist::distribute<D>(*comm, body, pd::family_ratio(s.partial_volume, s.delta, s.spacing), *out.ownership);
    const auto& p = sys.particles;
    out.probes = locate_probes<D>(s, p.x0, p.n_real, comm, out.ownership->own, body.size());
    out.j_integrals = j_integral_outputs<D>(s, p.x0, p.n_real, comm);
    check_symmetry_planes<D>(s, p, comm);
    out.symmetry_ghosts = bc::mirror_count<D>(body, symmetry_planes(s), family_reach(s));
    // Crack tracking follows connected components over the whole body: every process keeps
    // the whole body's families, their flags gathered at each history sample (PdRun).
    if (s.crack.enabled) out.crack_body.emplace().particles = body.particles(0, body.size());
  } else {
    sys.particles = fill_body<D>(s);
    const auto& p = sys.particles;
    out.probes = locate_probes<D>(s, p.x0, p.n_real);
    out.j_integrals = j_integral_outputs<D>(s, p.x0, p.n_real);
    check_symmetry_planes<D>(s, p, nullptr);
  }

  set_model_settings(sys, s);

  // The mirrors of the symmetry planes: a distributed process makes those of its own
  // particles and halo (bc/symmetry.hpp).
  bc::add_symmetry_ghosts<D>(sys.particles, symmetry_planes(s), family_reach(s));
  if (!distributed) out.symmetry_ghosts = sys.particles.n_ghost();
  sys.connect();
  if (out.ownership) {
    check_families_whole<D>(sys, *out.ownership, *comm);
    out.ownership->exchange->index_bond_sides(sys.families.offsets, sys.families.neighbor);
  }

  for (const auto& pc : s.precracks) {
    pd::CrackSurface<D> crack;
    for (const auto& pt : pc.points) crack.points.push_back(to_vec<D>(pt));
    const auto cut = pd::cut_bonds<D>(sys, crack);
    if (everywhere(cut) == 0) throw InputError(s.file, pc.key, "this pre-crack cuts no bond: it lies outside the body");
    out.precrack_cut += cut;
  }

  out.model = pd::make_model<D>(s.model);
  try {
    out.model->initialise(sys);
  } catch (const std::invalid_argument& e) {  // a stencil the model cannot take (lps_plastic's isotropy weights)
    throw InputError(s.file, "model.isotropy",
                     std::string(e.what()) + "; use isotropy = \"lattice\" or another horizon ratio");
  }
  out.damage = s.damage;
  out.break_after_force = s.break_after_force;
  // With the ductile criterion alone no bond breaks by stretch (s₀ = ∞).
  if (s.damage)
    out.critical_stretch = s.critical_stretch ? *s.critical_stretch
        : s.fracture_energy
        ? pd::critical_stretch(s.influence, s.setting, s.material, *s.fracture_energy, s.delta, sys.measure)
        : std::numeric_limits<double>::infinity();

  for (const auto& b : s.boundaries) {
    auto selected = select_particles<D>(sys.particles.x0, sys.particles.n_real, make_geometry<D>(b.region), s.spacing);
    if (everywhere(static_cast<std::int64_t>(selected.size())) == 0)
      throw InputError(s.file, b.key + ".region",
                       "selects no particle (particles sit on lattice sites; check the region against the body)");
    if (b.kind == io::BoundaryKind::traction) {
      bc::Traction<D> t;
      t.name = b.name;
      t.particles = std::move(selected);
      for (int a = 0; a < D; ++a) {
        if (b.value[a] == "free")
          throw InputError(s.file, b.key + ".value", "a traction component cannot be \"free\" (use 0)");
        t.value[a] = bc::Expression::parse(b.value[a]);
      }
      t.layer = b.layer > 0.0 ? b.layer : s.spacing;
      out.boundaries.tractions.push_back(std::move(t));
    } else {
      add_constraint<D>(s, b, std::move(selected), out);
    }
  }
  out.boundaries.finalise(sys.particles.n_real);
  // Before the run's first force evaluation, so a displacement is strained from t = 0.
  out.initial = make_initial_conditions<D>(s, sys.particles, distributed ? comm : nullptr);
  bc::apply_initial_conditions<D>(out.initial, sys.particles);

  if (!s.body_force.empty()) {
    out.has_body_force = true;
    for (int a = 0; a < D; ++a) out.body_force[a] = bc::Expression::parse(s.body_force[a]);
  }
  if (s.indenter) {
    bc::Indenter<D> ind;
    ind.center0 = to_vec<D>(s.indenter->center);
    ind.velocity = to_vec<D>(s.indenter->velocity);
    ind.radius = s.indenter->radius;
    ind.stiffness = s.indenter->stiffness;
    ind.force_density = s.indenter->force_density;
    out.indenter = ind;
  }
  if (s.contact.enabled) {
    const double c = pd::pmb_micromodulus(pd::Influence::constant, s.setting, s.material, s.delta, sys.measure);
    out.contact.emplace(pd::ContactParameters{s.contact.stiffness_factor, s.contact.distance_factor,
                                              s.contact.max_distance, s.contact.bonded_pairs},
                        c);
  }
  if (out.crack_body) {
    auto& whole = *out.crack_body;
    set_model_settings(whole, s);
    bc::add_symmetry_ghosts<D>(whole.particles, symmetry_planes(s), family_reach(s));
    whole.connect();
  }
  if (s.crack.enabled) {
    out.crack =
        pd::CrackSettings{s.crack.threshold, s.crack.path_threshold, s.crack.min_piece_fraction, s.crack.speed_window};
    const auto& body = out.crack_system().particles;  // the whole body's particles
    out.crack_exclude.assign(static_cast<std::size_t>(body.n_real), 0);
    if (!s.crack.exclude.empty()) {
      const auto selected = select_particles<D>(body.x0, body.n_real, make_geometry<D>(s.crack.exclude), s.spacing);
      if (selected.empty())
        throw InputError(s.file, "crack.exclude", "selects no particle (check the region against the body)");
      for (Index i : selected) out.crack_exclude[i] = 1;
    }
    for (const auto& o : s.observes) {
      pd::NamedLocation<D> loc;
      loc.name = o.name;
      loc.point = to_vec<D>(o.point);
      loc.radius = o.radius > 0.0 ? o.radius : s.delta;
      for (Index i = 0; i < body.n_real; ++i)
        if ((body.x0[i] - loc.point).norm() <= loc.radius * (1.0 + 1e-12)) loc.particles.push_back(i);
      if (loc.particles.empty())
        throw InputError(s.file, o.key + ".point",
                         "no particle lies within the radius of this point (is it inside the body?)");
      out.locations.push_back(std::move(loc));
    }
  }
  return out;
}

template PdSetup<1> build_pd<1>(const io::Scene&, const dist::Communicator*);
template PdSetup<2> build_pd<2>(const io::Scene&, const dist::Communicator*);
template PdSetup<3> build_pd<3>(const io::Scene&, const dist::Communicator*);

}  // namespace pdmpm::sim
