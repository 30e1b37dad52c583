#pragma once
// Models chosen by name. register_builtin_models() is called from one place (no static
// self-registration: the linker drops it from static libraries). Adding a model is one new file
// plus one line in registry.cpp.

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "constitutive/model.hpp"
#include "constitutive/parameters.hpp"

namespace duet::constitutive {

/// Builds a model from its parameters; throws InputError on bad values. Must call
/// parameters.finish() so unknown keys are refused.
using ModelFactory = std::function<std::unique_ptr<Model>(Parameters&)>;

struct ModelInfo {
  std::string name;
  std::string summary;  // one line, for listings
  ModelFactory make;
  std::map<std::string, ParameterValue> example;  // a valid parameter set (the demo uses it)
  // Valid parameter sets of the model's other forms (hypoplastic: c1..c4 in place of Ei nu phi
  // psi), so `duet models` lists every parameter the model reads.
  std::vector<std::map<std::string, ParameterValue>> other_forms = {};
  // Whether its strength can fall with its own state (a dense hypoplastic sand past its peak);
  // false for elasticity and perfect plasticity, whose load on a driven body does not fall (the
  // run's load-drop warning, benchmarks/run_warnings.hpp). True unless a model says otherwise.
  bool softens = true;
};

class ModelRegistry {
 public:
  void add(ModelInfo info);
  /// Throws InputError naming the known models (with a did-you-mean) when `name` is unknown.
  const ModelInfo& find(const std::string& name, const std::string& context = "model") const;
  std::vector<std::string> names() const;
  const std::vector<ModelInfo>& models() const { return models_; }

 private:
  std::vector<ModelInfo> models_;
};

void register_builtin_models(ModelRegistry& registry);

/// The registry with every built-in model.
const ModelRegistry& builtin_models();

/// A legal value that is almost surely in the wrong unit.
struct UnitDoubt {
  std::string message;   // "material.sand.E = 20: ...": the key, the value, what was likely meant
  bool refused = false;  // beyond doubt: refused before work unless the user says it is meant
};

/// Values that are legal but almost surely in the wrong unit, one each (empty when none).
/// Refused (a bare number in MPa or kPa, which no soil has in Pa):
///   a modulus (E, Ei, E_i) below 10 kPa: the softest soils (peat, soft clay) have 100 kPa and
///     more, and a modulus in MPa (up to 10 GPa) written bare lands below it;
///   an undrained strength cu in (0, 100) Pa: a remoulded clay at its liquid limit has 1-2 kPa,
///     and a bare number in kPa up to 100 lands below it;
///   a cohesion c in (0, 1) Pa: a cohesion in MPa written bare (0.01 for 10 kPa).
/// Said only (they can be meant):
///   an angle (phi, psi) in (0, 1.6) looks like radians; a modulus in [10, 100) kPa like kPa;
///   cu in [100, 1000) Pa like kPa (a quick clay's remoulded strength can be that low); c in
///   [1, 100) Pa like kPa (a few Pa of cohesion is a known device in granular-flow runs); a
///   density below 100 kg/m^3 like t/m^3.
/// `context` prefixes each (e.g. "material.sand").
std::vector<UnitDoubt> implausible_parameters(const std::map<std::string, ParameterValue>& resolved,
                                              double density, const std::string& context);

/// Convenience: find by name, build from values, check unknown keys. `context` prefixes messages.
std::unique_ptr<Model> make_model(const std::string& name,
                                  std::map<std::string, ParameterValue> values,
                                  const std::string& context,
                                  std::map<std::string, ParameterValue>* resolved = nullptr);

}  // namespace duet::constitutive
