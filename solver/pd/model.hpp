#pragma once
// A peridynamic force model: the same verbs for every model, chosen by name
// from a scene. Adding a model = one class + one line in the model table
// (model.cpp), and every verification test that loops over the table covers it;
// tests ask the table for a model's properties, never for its name.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "solver/pd/stress.hpp"
#include "solver/pd/system.hpp"

namespace pdmpm::pd {

struct ForceRequest {
  bool break_bonds = false;       // apply the critical-stretch rule this evaluation
  double critical_stretch = 0.0;  // s₀
  // false: a bond with s ≥ s₀ breaks before it acts (pdmpm's rule); true: it acts
  // once more in this evaluation and breaks if s > s₀ (LAMMPS' PERI rule).
  bool break_after_force = false;
  std::vector<double>* energy = nullptr;  // if set: strain energy density W_i of each real particle
};

template <int D>
class Model {
 public:
  virtual ~Model() = default;
  virtual std::string name() const = 0;
  // Precompute what depends on the reference configuration and live bonds.
  virtual void initialise(const System<D>& sys) = 0;
  // The live bonds of these real particles changed (particle kinds changed):
  // recompute what initialise derived from them, for them only.
  virtual void refresh(const System<D>& sys, const std::vector<Index>& changed) { (void)sys, (void)changed; }
  // Internal force density of every real particle into sys.particles.f.
  // Returns the number of bonds broken by this call (counted once per bond side).
  virtual std::int64_t compute_forces(System<D>& sys, const ForceRequest& req) = 0;
  // Dilatation θ_i of each real particle (the model's own measure; PMB uses the LPS one).
  virtual void dilatation(const System<D>& sys, std::vector<double>& theta) const;
  // Row sum Σ_j V_j C_ij of the bond stiffness of particle i (Silling & Askari 2005);
  // negative if the model has no such bound.
  virtual double stiffness_row_sum(const System<D>& sys, Index i) const {
    (void)sys;
    (void)i;
    return -1.0;
  }
  // Model state beyond the bond flags (plastic models), trial/committed like them:
  // accept() commits what the last evaluation wrote, reject() returns to the last commit.
  virtual void accept() {}
  virtual void reject() {}
  // Everything beyond the reference configuration a resumed run needs (core/state_archive.hpp).
  virtual void checkpoint(core::StateArchive& a) { (void)a; }
  // Plastic models: equivalent plastic strain per real particle and the plastic work
  // so far (J); nullptr and 0 for elastic ones.
  virtual const std::vector<double>* eq_plastic_strain() const { return nullptr; }
  virtual double plastic_work() const { return 0.0; }
  // The model's own stress of particle i from its force state (3D tensor, with σ_zz of the
  // 2D settings), for models whose stress is not Hooke's law of the strain (plastic ones);
  // the others leave it to the deformation-gradient stress of pd/stress.hpp.
  virtual bool has_own_stress() const { return false; }
  virtual Tensor6 own_stress(const System<D>& sys, Index i) const;
  // Out-of-plane strain ε_zz per real particle where the model carries it (plastic plane
  // stress); nullptr: the fields take the elastic one, −ν/(1−ν) θ.
  virtual const std::vector<double>* out_of_plane_strain() const { return nullptr; }
};

// One row of the model table: what a scene, a run and a test need to know of a
// model without knowing the model.
struct ModelInfo {
  std::string name;
  // Forces involve the dilatation of every neighbour, so an affine field is
  // force-free only 2δ (not δ) from a boundary.
  bool state_based = false;
  // A pair potential fixes Poisson's ratio by the setting (Cauchy relation).
  bool pair_potential = false;
  bool plastic = false;
  // Symmetry planes (ghost particles) work: false where a ghost's missing family matters
  // (plastic state on bond sides, sub-horizons built from both ends' families).
  bool symmetry_planes = true;
  // Runs over several processes (solver/dist/): false where a force reads state beyond the
  // halo of one horizon (HPD's sub-horizons reach two).
  bool distributed = true;
  std::function<std::unique_ptr<Model<1>>()> make1;
  std::function<std::unique_ptr<Model<2>>()> make2;
  std::function<std::unique_ptr<Model<3>>()> make3;

  // The ν the model requires in a setting, if it fixes one: ¼ in 3D and plane
  // strain, ⅓ in plane stress for a pair potential; none in a 1D bar.
  std::optional<double> fixed_poisson(core::Setting s) const;
  // Admissible Poisson's ratio interval [lo, hi] in a setting.
  std::pair<double, double> poisson_range(core::Setting s) const;
  template <int D>
  std::unique_ptr<Model<D>> make() const;
};

// Every registered model, in a fixed order.
const std::vector<ModelInfo>& model_table();
// The row of a model by name; nullptr if unknown.
const ModelInfo* find_model(std::string_view name);
// The row of a model the caller knows exists (throws std::invalid_argument otherwise).
const ModelInfo& model_info(std::string_view name);
std::vector<std::string> model_names();
// A new model by name (nullptr if unknown).
template <int D>
std::unique_ptr<Model<D>> make_model(const std::string& name);

}  // namespace pdmpm::pd
