#pragma once
// A validated scene: everything a run needs, read from a TOML file by
// parse_scene(). Vectors have exactly `dimension` components. The README's
// "Scene reference" documents every key.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "solver/hybrid/settings.hpp"
#include "solver/mpm/settings.hpp"
#include "solver/pd/hpd_options.hpp"
#include "solver/pd/influence.hpp"
#include "solver/core/material.hpp"
#include "solver/pd/partial_volume.hpp"

namespace pdmpm::io {

struct ShapeSpec {
  std::string key;   // key path, for messages
  std::string type;  // box | ball | cylinder
  bool subtract = false;
  std::vector<double> min, max, center;
  double radius = 0.0, height = 0.0;
  int axis = 2;
};

enum class BoundaryKind { fixed, displacement, velocity, traction, analytic };
constexpr std::array<EnumName<BoundaryKind>, 5> names(BoundaryKind) {
  return {{{BoundaryKind::fixed, "fixed"},
           {BoundaryKind::displacement, "displacement"},
           {BoundaryKind::velocity, "velocity"},
           {BoundaryKind::traction, "traction"},
           {BoundaryKind::analytic, "analytic"}}};
}

struct BoundarySpec {
  std::string key, name;
  BoundaryKind kind = BoundaryKind::fixed;
  std::vector<ShapeSpec> region;
  std::vector<std::string> value;  // per component; "free" leaves it unconstrained
  double layer = 0.0;              // traction: loaded layer thickness (0 → Δx)
  std::string callback;            // analytic
  bool moving = false;             // velocity, MPM grid: the node box travels with the grip
  std::map<std::string, double> parameters;
};

// [[initial]]: velocity and/or displacement at t = 0 of the particles in a region.
struct InitialSpec {
  std::string key;
  std::vector<ShapeSpec> region;                    // empty: the whole body
  std::vector<std::string> velocity, displacement;  // per component ("free" leaves it alone); empty: not given
};

struct SymmetrySpec {
  std::string key;
  int axis = 0;
  double position = 0.0;
};

struct PrecrackSpec {
  std::string key;
  std::vector<std::vector<double>> points;  // 2D: from, to; 3D: three corners
};

struct IndenterSpec {
  std::vector<double> center, velocity;
  double radius = 0.0, stiffness = 0.0;
  bool force_density = false;  // k (R − r)² is a force density (N/m³, LAMMPS' fix indent on PERI atoms), not a force
};

struct ProbeSpec {
  std::string name;
  std::vector<double> point;
};

// [[j_integral]]: J of a crack tip (domain form, solver/core/j_integral.hpp) in history.csv as
// column j_<name> (J/m²); 2D scenes. The tip and the ring are fixed in the reference configuration.
struct JIntegralSpec {
  std::string key;  // "j_integral[k]"
  std::string name;
  std::vector<double> tip;                  // (m)
  std::vector<double> direction{1.0, 0.0};  // the crack's growth, normalised when read
  double r_inner = 0.0, r_outer = 0.0;      // the ring (m), 0 ≤ r_inner < r_outer
};

struct ContactSpec {
  bool enabled = false;
  double stiffness_factor = 15.0;  // c_s = 15 c (Deryugin et al. 2023 eq 6.3)
  double distance_factor = 0.9;    // d = min(0.9 |ξ|, 1.35 Δx) (Deryugin et al. 2023 eq 6.4)
  double max_distance = 1.35;      // in units of Δx
  bool bonded_pairs = false;       // also between bonded particles (LAMMPS peri/pmb's rule)
};

// Crack observables (solver/pd/crack_observables.hpp): enabled by a [crack] table
// or any [[observe]] location.
struct CrackSpec {
  bool enabled = false;
  double threshold = 0.5;
  double path_threshold = 0.35;
  double min_piece_fraction = 0.01;
  double speed_window = 0.0;       // s; 0 → ten history intervals
  std::vector<ShapeSpec> exclude;  // regions where no crack is detected
};

struct ObserveSpec {
  std::string key, name;
  std::vector<double> point;
  double radius = 0.0;  // 0 → δ
};

// verlet: dynamic (velocity Verlet); adr: quasi-static (adaptive dynamic relaxation).
enum class Integrator { verlet, adr };
constexpr std::array<EnumName<Integrator>, 2> names(Integrator) {
  return {{{Integrator::verlet, "verlet"}, {Integrator::adr, "adr"}}};
}
enum class StableStepEstimate { silling_askari, lanczos };
constexpr std::array<EnumName<StableStepEstimate>, 2> names(StableStepEstimate) {
  return {{{StableStepEstimate::silling_askari, "silling_askari"}, {StableStepEstimate::lanczos, "lanczos"}}};
}
// model.break_timing: before_force (default: a bond at s ≥ s₀ breaks before it acts) or
// after_force (it acts once more and breaks if s > s₀, as in LAMMPS).
enum class BreakTiming { before_force, after_force };
constexpr std::array<EnumName<BreakTiming>, 2> names(BreakTiming) {
  return {{{BreakTiming::before_force, "before_force"}, {BreakTiming::after_force, "after_force"}}};
}
// model.weighted_volume (state-based models): discrete (default: the sum over each
// family) or continuum (the integral over a full horizon, Gu & Zhou 2017 eq 15).
enum class WeightedVolume { discrete, continuum };
constexpr std::array<EnumName<WeightedVolume>, 2> names(WeightedVolume) {
  return {{{WeightedVolume::discrete, "discrete"}, {WeightedVolume::continuum, "continuum"}}};
}

// model.isotropy (plastic models): corrected (default: the deviatoric bond weight
// c(n) = 1 + κ g(n) makes the lattice's fourth moment isotropic) or lattice (plain sums).
enum class Isotropy { corrected, lattice };
constexpr std::array<EnumName<Isotropy>, 2> names(Isotropy) {
  return {{{Isotropy::corrected, "corrected"}, {Isotropy::lattice, "lattice"}}};
}

// model.damaged_yield (plastic models): where a particle with broken bonds reads its
// equivalent stress — reference_family (default: the live bonds' norm over the reference
// family's weighted volume, as LPS) or live_bonds (over the live bonds' weighted volume).
enum class DamagedYield { reference_family, live_bonds };
constexpr std::array<EnumName<DamagedYield>, 2> names(DamagedYield) {
  return {{{DamagedYield::reference_family, "reference_family"}, {DamagedYield::live_bonds, "live_bonds"}}};
}

struct TimeSpec {
  Integrator integrator = Integrator::verlet;
  std::optional<double> end_time;
  std::optional<std::int64_t> steps;
  std::optional<double> dt;
  double safety_factor = 0.8;
  StableStepEstimate estimate = StableStepEstimate::silling_askari;
  double tolerance = 1e-6;          // adr: residual relative to the load scale
  std::int64_t max_steps = 200000;  // adr, per load step
  std::int64_t load_steps = 1;      // adr: t in expressions runs 1/N, 2/N, …, 1
  double energy_growth_limit = 10;  // instability: E > limit × (E₀ + |work in|)
};

struct OutputSpec {
  std::optional<std::int64_t> frames, every;
  std::vector<double> frame_times;  // frames at the steps nearest these times (plus first and last)
  std::optional<std::int64_t> history_every;
  std::vector<std::string> fields;
};

// Material point method options (model type "mpm"): the [mpm] table, and the
// constitutive keys of [material]. Plain copies of mpm::Settings fields.
struct MpmSpec {
  mpm::ShapeFunction shape = mpm::ShapeFunction::gimp;
  mpm::GimpDomain gimp_domain = mpm::GimpDomain::fixed;
  mpm::UpdateScheme scheme = mpm::UpdateScheme::musl;
  double flip = 1.0;
  double cell_size = 0.0, cell_factor = 2.0;
  int padding_cells = 3;
  std::vector<double> domain_min, domain_max;  // the grid's node box; empty: particle bounds ± padding_cells
  double damping_viscous = 0.0, damping_local = 0.0;
  mpm::Nonlocal nonlocal;
  mpm::MaterialModel constitutive = mpm::MaterialModel::linear_elastic;
};

// Which method integrates the body. `pd` and `mpm` follow from [model] type;
// `hybrid` (the adaptive SBPD–MPM coupling) from a [hybrid] table, with the PD
// model in [model] and the grid options in [mpm].
enum class Method { pd, mpm, hybrid };

struct Scene {
  std::string file, id, description;
  std::string text;  // the TOML it was parsed from (a checkpoint keeps it)
  int dimension = 3;
  core::Setting setting = core::Setting::solid3d;
  double spacing = 0.0, delta = 0.0, measure = 1.0;
  std::optional<std::vector<double>> lattice_origin;
  pd::PartialVolume partial_volume = pd::PartialVolume::seed001;
  std::vector<ShapeSpec> shapes;

  core::Elastic material;
  core::J2Hardening hardening;   // [material] yield_stress, tangent_modulus (plastic laws)
  core::DuctileFailure failure;  // [material.failure] (plastic laws)
  std::optional<double> critical_stretch, fracture_energy;
  Method method = Method::pd;
  std::string model = "pmb";  // the PD model's name (model table), or "mpm"
  pd::Influence influence = pd::Influence::constant;
  bool damage = false;
  bool break_after_force = false;          // model.break_timing = "after_force" (LAMMPS' rule)
  bool continuum_weighted_volume = false;  // model.weighted_volume = "continuum" (lps)
  bool isotropic_deviatoric = false;       // model.isotropy = "corrected" (plastic PD models)
  bool yield_on_live_bonds = false;        // model.damaged_yield = "live_bonds" (plastic PD models)
  pd::HpdOptions hpd;                      // material.constitutive, model.overlap_min_points (hpd)
  ContactSpec contact;
  std::optional<MpmSpec> mpm;              // set when model = "mpm", and for a hybrid scene
  std::optional<hybrid::Settings> hybrid;  // the [hybrid] table (method hybrid)
  std::vector<ShapeSpec> initial_pd;       // [hybrid] initial_pd: regions whose particles start PD

  TimeSpec time;
  std::vector<BoundarySpec> boundaries;
  std::vector<InitialSpec> initials;  // in file order: a later table overwrites an earlier one
  std::vector<SymmetrySpec> symmetries;
  std::vector<PrecrackSpec> precracks;
  std::vector<std::string> body_force;  // force density expressions, empty = none
  std::optional<IndenterSpec> indenter;
  std::vector<ProbeSpec> probes;
  std::vector<JIntegralSpec> j_integrals;
  CrackSpec crack;
  std::vector<ObserveSpec> observes;
  OutputSpec output;
};

// Field names `output.fields` may list for this scene's method and model.
std::vector<std::string> output_field_names(const Scene& s);
const std::vector<std::string>& mpm_field_names();

class TomlReader;

// PD parts of a scene (scene_pd.cpp): the PD model's keys of [model].
void read_pd_model(const TomlReader& model, Scene& s);
// The hpd model's sub-horizons on this horizon (needs [discretization]): fails on
// `horizon_key` of `discretization` if an interior bond has too few overlap points.
void check_hpd_horizon(const TomlReader& discretization, const Scene& s, const std::string& horizon_key);

// MPM parts of a scene (scene_mpm.cpp): the constitutive keys of [material]
// (read from the material table's own reader) and the [mpm] table.
void read_mpm_material(const TomlReader& material, Scene& s);
// [material] yield_stress and tangent_modulus (0 ≤ E_t < E), for every plastic law.
void read_hardening(const TomlReader& material, Scene& s);
// [material.failure]: the ductile criterion ε_f = d₀ exp(cη) (d0 > 0, c, rule), MPM's and plastic PD's.
void read_ductile_failure(const TomlReader& material, Scene& s);
void read_mpm_options(const TomlReader& table, Scene& s);
// Rejects the PD-only parts of a scene (pre-cracks, indenter, crack observables,
// displacement/analytic boundaries, non-box regions) for model type "mpm".
void check_mpm_scene(const Scene& s);

// Rejects, for the MPM grid, boundaries other than fixed/velocity/traction on boxes
// (`who`: "the mpm model", "the hybrid").
void check_grid_boundaries(const Scene& s, const std::string& who);

// Hybrid parts of a scene (scene_hybrid.cpp). start_hybrid_model: after the PD
// model is read, accepts lps_plastic or lps and sets the matching MPM law;
// read_hybrid_material: [material] constitutive, if given, must be that law;
// read_hybrid: the [hybrid] table (needs the dimension); check_hybrid_scene:
// refuses symmetry planes, indenter, contact, crack observables, and boundaries
// the grid cannot take.
void start_hybrid_model(const TomlReader& model, Scene& s);
void read_hybrid_material(const TomlReader& material, Scene& s);
void read_hybrid(const TomlReader& table, Scene& s);
ShapeSpec read_shape(const TomlReader& r, int dim);  // one region shape (scene_parser.cpp)
void check_hybrid_scene(const Scene& s);

// Reads and validates a scene file; throws InputError on any problem.
Scene parse_scene(const std::string& path);
Scene parse_scene_text(const std::string& text, const std::string& file_label);

}  // namespace pdmpm::io
