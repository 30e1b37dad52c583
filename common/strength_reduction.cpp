#include "common/strength_reduction.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <variant>

namespace duet {

bool reduce_strength(std::map<std::string, ParameterValue>& parameters, double factor,
                     const std::string& rule) {
  auto* phi = parameters.count("phi") ? std::get_if<double>(&parameters["phi"]) : nullptr;
  auto* c = parameters.count("c") ? std::get_if<double>(&parameters["c"]) : nullptr;
  if (!phi && !c) return false;
  if (factor == 1.0) return true;
  if (c) *c /= factor;  // Peng 2015 eq 39
  if (phi) {
    const double deg = std::numbers::pi / 180.0;
    *phi = rule == "angle" ? *phi / factor  // Peng 2015 eq 40
                           : std::atan(std::tan(*phi * deg) / factor) / deg;
  }
  return true;
}

bool strength_changes_in_run(const Scene& scene) {
  return scene.initial_stress.kind == InitialStressKind::gravity_loading &&
         scene.strength_reduction.stage == "after-loading" &&
         scene.strength_reduction.factor != 1.0;
}

double loading_strength_factor(const Scene& scene) {
  return strength_changes_in_run(scene) ? 1.0 : scene.strength_reduction.factor;
}

double strength_factor_at(const Scene& scene, double time) {
  const double f = scene.strength_reduction.factor;
  if (!strength_changes_in_run(scene)) return f;
  if (time <= 0.0) return 1.0;  // the state gravity loading left, at full strength
  const double ramp = scene.strength_reduction.ramp;
  if (ramp <= 0.0 || time >= ramp) return f;
  return 1.0 + (f - 1.0) * std::clamp(time / ramp, 0.0, 1.0);
}

std::map<std::string, ParameterValue> parameters_at(const Scene& scene, const Material& material,
                                                    double factor) {
  if (factor == scene.strength_reduction.factor) return material.parameters;  // as loaded
  std::map<std::string, ParameterValue> p = material.full_strength;
  reduce_strength(p, factor, scene.strength_reduction.rule);
  return p;
}

}  // namespace duet
