#include "constitutive/scene_models.hpp"

#include <stdexcept>
#include <string>

#include "common/strength_reduction.hpp"
#include "constitutive/registry.hpp"

namespace duet::constitutive {

bool cannot_soften(const Scene& scene) {
  if (scene.strength_reduction.factor != 1.0) return false;
  for (const Material& m : scene.materials) {
    if (builtin_models().find(m.model).softens) return false;
  }
  return true;
}

Models make_scene_models(const Scene& scene, double factor) {
  Models models;
  for (const Material& m : scene.materials) {
    models.push_back(make_model(m.model, parameters_at(scene, m, factor), "material." + m.name));
  }
  return models;
}

void replace_models(Models& models, Models replacement, const char* solver) {
  if (replacement.size() != models.size()) {
    throw std::invalid_argument(std::string(solver) +
                                ": use_models with another number of materials");
  }
  for (std::size_t m = 0; m < models.size(); ++m) {
    if (replacement[m]->internal_variables().size() != models[m]->internal_variables().size()) {
      throw std::invalid_argument(std::string(solver) +
                                  ": use_models with other internal variables");
    }
  }
  models = std::move(replacement);
}

StrengthInRun::StrengthInRun(const Scene& scene) : factor_(loading_strength_factor(scene)) {}

bool StrengthInRun::changes_at(const Scene& scene, double time) {
  const double f = strength_factor_at(scene, time);
  if (f == factor_) return false;
  factor_ = f;
  return true;
}

}  // namespace duet::constitutive
