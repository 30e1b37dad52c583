#include "constitutive/scene_models.hpp"

#include "common/strength_reduction.hpp"
#include "constitutive/registry.hpp"

namespace duet::constitutive {

Models make_scene_models(const Scene& scene, double factor) {
  Models models;
  for (const Material& m : scene.materials) {
    models.push_back(make_model(m.model, parameters_at(scene, m, factor), "material." + m.name));
  }
  return models;
}

StrengthInRun::StrengthInRun(const Scene& scene) : factor_(loading_strength_factor(scene)) {}

bool StrengthInRun::changes_at(const Scene& scene, double time) {
  const double f = strength_factor_at(scene, time);
  if (f == factor_) return false;
  factor_ = f;
  return true;
}

}  // namespace duet::constitutive
