#pragma once
// A peridynamic force model: the same verbs for every model, chosen by name
// from a scene. Adding a model = one class + one line in model.cpp, and every
// typed verification test then covers it.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "solver/pd/system.hpp"

namespace pdmpm::pd {

struct ForceRequest {
  bool break_bonds = false;        // apply the critical-stretch rule this evaluation
  double critical_stretch = 0.0;   // s₀
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
  // Admissible Poisson's ratio interval [lo, hi] for this model and setting.
  virtual std::pair<double, double> poisson_range(Setting s) const = 0;
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
  virtual double stiffness_row_sum(const System<D>& sys, Index i) const { (void)sys; (void)i; return -1.0; }
};

template <int D>
using ModelFactory = std::function<std::unique_ptr<Model<D>>()>;

// Names of the registered models and a factory by name (nullptr if unknown).
std::vector<std::string> model_names();
template <int D>
std::unique_ptr<Model<D>> make_model(const std::string& name);

}  // namespace pdmpm::pd
