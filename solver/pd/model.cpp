#include "solver/pd/model.hpp"

#include <stdexcept>

#include "solver/pd/hpd.hpp"
#include "solver/pd/lps.hpp"
#include "solver/pd/lps_plastic.hpp"
#include "solver/pd/pmb.hpp"
#include "solver/pd/weighted_volume.hpp"

namespace pdmpm::pd {

template <int D>
void Model<D>::dilatation(const System<D>& sys, std::vector<double>& theta) const {
  theta.assign(sys.particles.n_real, 0.0);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < sys.particles.n_real; ++i) theta[i] = dilatation_of(sys, i, weighted_volume(sys, i));
}

template <int D>
Tensor6 Model<D>::own_stress(const System<D>&, Index) const {
  throw std::logic_error("model " + name() + " has no stress of its own");
}

namespace {

template <template <int> class M>
ModelInfo row(std::string name, bool state_based, bool pair_potential, bool plastic, bool symmetry_planes,
              bool distributed) {
  return {std::move(name),
          state_based,
          pair_potential,
          plastic,
          symmetry_planes,
          distributed,
          [] { return std::make_unique<M<1>>(); },
          [] { return std::make_unique<M<2>>(); },
          [] { return std::make_unique<M<3>>(); }};
}

}  // namespace

const std::vector<ModelInfo>& model_table() {
  // name, state-based, pair potential, plastic, symmetry planes, distributed
  static const std::vector<ModelInfo> table = {
      row<Pmb>("pmb", false, true, false, true, true),
      row<Lps>("lps", true, false, false, true, true),
      row<LpsPlastic>("lps_plastic", true, false, true, false, true),
      row<Hpd>("hpd", true, false, false, false, true),
  };
  return table;
}

std::optional<double> ModelInfo::fixed_poisson(core::Setting s) const {
  if (!pair_potential || s == core::Setting::bar1d) return std::nullopt;  // ν plays no role in a bar
  return s == core::Setting::plane_stress ? 1.0 / 3.0 : 0.25;
}

std::pair<double, double> ModelInfo::poisson_range(core::Setting s) const {
  if (const auto nu = fixed_poisson(s)) return {*nu, *nu};
  // ν = ½ is excluded: K = E / (3(1 − 2ν)) must stay finite (and κ₂ in plane stress).
  return pair_potential ? std::pair{0.0, 0.5} : std::pair{-1.0, 0.5};
}

template <int D>
std::unique_ptr<Model<D>> ModelInfo::make() const {
  if constexpr (D == 1) return make1();
  if constexpr (D == 2) return make2();
  if constexpr (D == 3) return make3();
}

const ModelInfo* find_model(std::string_view name) {
  for (const auto& m : model_table())
    if (m.name == name) return &m;
  return nullptr;
}

const ModelInfo& model_info(std::string_view name) {
  if (const auto* m = find_model(name)) return *m;
  throw std::invalid_argument("no peridynamic model named \"" + std::string(name) + "\"");
}

std::vector<std::string> model_names() {
  std::vector<std::string> names;
  for (const auto& m : model_table()) names.push_back(m.name);
  return names;
}

template <int D>
std::unique_ptr<Model<D>> make_model(const std::string& name) {
  const auto* m = find_model(name);
  return m ? m->make<D>() : nullptr;
}

template class Model<1>;
template class Model<2>;
template class Model<3>;
template std::unique_ptr<Model<1>> ModelInfo::make<1>() const;
template std::unique_ptr<Model<2>> ModelInfo::make<2>() const;
template std::unique_ptr<Model<3>> ModelInfo::make<3>() const;
template std::unique_ptr<Model<1>> make_model<1>(const std::string&);
template std::unique_ptr<Model<2>> make_model<2>(const std::string&);
template std::unique_ptr<Model<3>> make_model<3>(const std::string&);

}  // namespace pdmpm::pd
