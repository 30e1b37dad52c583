#include "constitutive/registry.hpp"

#include <cmath>
#include <cstdio>

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

std::vector<std::string> implausible_parameters(
    const std::map<std::string, ParameterValue>& resolved, double density,
    const std::string& context) {
  std::vector<std::string> out;
  auto value = [&](const std::string& name) -> double {
    const auto it = resolved.find(name);
    if (it == resolved.end()) return std::nan("");
    const double* v = std::get_if<double>(&it->second);
    return v ? *v : std::nan("");
  };
  auto say = [&](const std::string& name, double v, const std::string& why) {
    char number[32];
    std::snprintf(number, sizeof number, "%g", v);
    out.push_back(context + "." + name + " = " + number + ": " + why);
  };
  for (const char* name : {"phi", "psi"}) {
    const double v = value(name);
    if (v > 0.0 && v < 1.6) {
      char deg[32];
      std::snprintf(deg, sizeof deg, "%.3g", v * 180.0 / M_PI);
      say(name, v, std::string("looks like radians (") + deg + " deg); angles are in degrees");
    }
  }
  for (const char* name : {"E", "Ei"}) {
    const double v = value(name);
    if (v > 0.0 && v < 1e4)
      say(name, v, "softer than any soil: moduli are in Pa (10 MPa = 1e7), not MPa or kPa");
  }
  for (const char* name : {"c", "cu"}) {
    const double v = value(name);
    if (v > 0.0 && v < 100.0)
      say(name, v, "below 100 Pa: strengths are in Pa (10 kPa = 1e4), not kPa");
  }
  if (density > 0.0 && density < 100.0) {
    char number[32];
    std::snprintf(number, sizeof number, "%g", density);
    out.push_back(context + ".density = " + number +
                  ": below 100 kg/m^3: densities are in kg/m^3 (1.8 t/m^3 = 1800)");
  }
  return out;
}

}  // namespace duet::constitutive
