#include "solver/pd/model.hpp"

#include "solver/pd/lps.hpp"
#include "solver/pd/pmb.hpp"
#include "solver/pd/weighted_volume.hpp"

namespace pdmpm::pd {

template <int D>
void Model<D>::dilatation(const System<D>& sys, std::vector<double>& theta) const {
  theta.assign(sys.particles.n_real, 0.0);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < sys.particles.n_real; ++i) theta[i] = dilatation_of(sys, i, weighted_volume(sys, i));
}

std::vector<std::string> model_names() { return {"pmb", "lps"}; }

template <int D>
std::unique_ptr<Model<D>> make_model(const std::string& name) {
  if (name == "pmb") return std::make_unique<Pmb<D>>();
  if (name == "lps") return std::make_unique<Lps<D>>();
  return nullptr;
}

template class Model<1>;
template class Model<2>;
template class Model<3>;
template std::unique_ptr<Model<1>> make_model<1>(const std::string&);
template std::unique_ptr<Model<2>> make_model<2>(const std::string&);
template std::unique_ptr<Model<3>> make_model<3>(const std::string&);

}  // namespace pdmpm::pd
