#include "constitutive/registry.hpp"

#include "common/input_error.hpp"
#include "common/suggest.hpp"
#include "constitutive/drucker_prager.hpp"
#include "constitutive/hypoplastic.hpp"
#include "constitutive/linear_elastic.hpp"
#include "constitutive/mohr_coulomb.hpp"
#include "constitutive/simhypo_sand.hpp"
#include "constitutive/tresca.hpp"

namespace duet::constitutive {

void ModelRegistry::add(ModelInfo info) {
  models_.push_back(std::move(info));
}

const ModelInfo& ModelRegistry::find(const std::string& name, const std::string& context) const {
  for (const auto& m : models_) {
    if (m.name == name) return m;
  }
  throw InputError(context + " = \"" + name + "\": unknown model" + did_you_mean(name, names()) +
                   "; known models: " + join(names()));
}

std::vector<std::string> ModelRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& m : models_) out.push_back(m.name);
  return out;
}

void register_builtin_models(ModelRegistry& registry) {
  // One line per model file (each file defines its own register_* function).
  register_linear_elastic(registry);
  register_hypoplastic(registry);
  register_drucker_prager(registry);
  register_tresca(registry);
  register_mohr_coulomb(registry);
  register_simhypo_sand(registry);
}

const ModelRegistry& builtin_models() {
  static const ModelRegistry registry = [] {
    ModelRegistry r;
    register_builtin_models(r);
    return r;
  }();
  return registry;
}

std::unique_ptr<Model> make_model(const std::string& name,
                                  std::map<std::string, ParameterValue> values,
                                  const std::string& context,
                                  std::map<std::string, ParameterValue>* resolved) {
  const ModelInfo& info = builtin_models().find(name, context + ".model");
  Parameters parameters(context, std::move(values));
  auto model = info.make(parameters);
  parameters.finish();
  if (resolved) *resolved = parameters.resolved();
  return model;
}

}  // namespace duet::constitutive
