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

namespace {

/// The number of a resolved parameter, NaN when absent or a word.
double number_of(const std::map<std::string, ParameterValue>& resolved, const std::string& name) {
  const auto it = resolved.find(name);
  if (it == resolved.end()) return std::nan("");
  const double* v = std::get_if<double>(&it->second);
  return v ? *v : std::nan("");
}

std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

std::vector<UnitDoubt> implausible_parameters(const std::map<std::string, ParameterValue>& resolved,
                                              double density, const std::string& context) {
  std::vector<UnitDoubt> out;
  const auto say = [&](const std::string& name, double v, const std::string& why, bool refused) {
    out.push_back({context + "." + name + " = " + number_text(v) + ": " + why, refused});
  };
  for (const char* name : {"phi", "psi"}) {
    const double v = number_of(resolved, name);
    if (v > 0.0 && v < 1.6) {
      char deg[32];
      std::snprintf(deg, sizeof deg, "%.3g", v * 180.0 / M_PI);
      say(name, v, std::string("looks like radians (") + deg + " deg); angles are in degrees",
          false);
    }
  }
  for (const char* name : {"E", "Ei", "E_i"}) {
    const double v = number_of(resolved, name);
    if (v > 0.0 && v < 1e4) {
      say(name, v,
          "a modulus below 10 kPa, softer than any soil: moduli are in Pa (" + number_text(v) +
              " MPa = " + number_text(v * 1e6) + " Pa), not MPa or kPa",
          true);
    } else if (v >= 1e4 && v < 1e5) {
      say(name, v, "below 100 kPa, softer than the softest soils: moduli are in Pa, not kPa",
          false);
    }
  }
  if (const double v = number_of(resolved, "cu"); v > 0.0 && v < 100.0) {
    say("cu", v,
        "an undrained strength below 100 Pa, a slurry's: strengths are in Pa (" + number_text(v) +
            " kPa = " + number_text(v * 1e3) + " Pa), not kPa",
        true);
  } else if (v >= 100.0 && v < 1e3) {
    say("cu", v, "below 1 kPa: strengths are in Pa (10 kPa = 1e4), not kPa", false);
  }
  if (const double v = number_of(resolved, "c"); v > 0.0 && v < 1.0) {
    say("c", v,
        "a cohesion below 1 Pa: strengths are in Pa (" + number_text(v) +
            " MPa = " + number_text(v * 1e6) + " Pa), not MPa",
        true);
  } else if (v >= 1.0 && v < 100.0) {
    say("c", v, "below 100 Pa: strengths are in Pa (10 kPa = 1e4), not kPa", false);
  }
  if (density > 0.0 && density < 100.0) {
    out.push_back({context + ".density = " + number_text(density) +
                       ": below 100 kg/m^3: densities are in kg/m^3 (1.8 t/m^3 = 1800)",
                   false});
  }
  return out;
}

}  // namespace duet::constitutive
