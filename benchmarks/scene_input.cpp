#include "benchmarks/scene_input.hpp"

#include <cmath>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "benchmarks/reports.hpp"
#include "common/input_error.hpp"
#include "common/lattice.hpp"
#include "constitutive/registry.hpp"

namespace duet {

std::string spacing_override(double spacing) {
  if (!(spacing > 0.0) || !std::isfinite(spacing)) {
    throw InputError("--spacing " + format_number(spacing) +
                     ": expected a particle spacing (m) > 0");
  }
  return "spacing=" + format_number(spacing);
}

MaterialCheck model_material_check(bool force) {
  return [force](const std::string& model, const std::map<std::string, ParameterValue>& parameters,
                 const std::string& context) {
    std::map<std::string, ParameterValue> resolved;
    constitutive::make_model(model, parameters, context, &resolved);
    if (force) return resolved;
    // The loader points the message at the key it starts with ("material.sand.E = 20: ...").
    for (const constitutive::UnitDoubt& d :
         constitutive::implausible_parameters(resolved, 0.0, context)) {
      if (d.refused) {
        throw InputError(d.message + "; expected a value in Pa, or --force if it is meant");
      }
    }
    return resolved;
  };
}

std::vector<std::string> measures_after_the_end(const Scene& scene) {
  std::vector<std::string> out;
  for (const Measure& m : scene.measures) {
    if (m.at == MeasureAt::time && m.time > scene.time.end_time) {
      out.push_back("measure." + m.name + " is taken at t = " + format_number(m.time) +
                    " s, after time.end_time = " + format_number(scene.time.end_time) +
                    " s: a run reads no value for it and scores nothing");
    }
  }
  return out;
}

namespace {

/// Legal values in a likely wrong unit (phi = 0.5, c = 10; with --force also those refused
/// otherwise, E = 20), rectangles the lattice does not fit (common/lattice.hpp) and measures taken
/// after the end time: said on the terminal. Once per message and process: compare and stability
/// load a scene once per run.
void warn_implausible(const Scene& scene) {
  static std::set<std::string> said;
  std::vector<std::string> warnings;
  for (const Material& m : scene.materials) {
    for (const constitutive::UnitDoubt& d :
         constitutive::implausible_parameters(m.resolved, m.density, "material." + m.name)) {
      warnings.push_back(d.message + (d.refused ? " (run as given: --force)" : ""));
    }
  }
  const std::vector<std::string> misfits = lattice_misfits(scene);
  warnings.insert(warnings.end(), misfits.begin(), misfits.end());
  const std::vector<std::string> late = measures_after_the_end(scene);
  warnings.insert(warnings.end(), late.begin(), late.end());
  for (const std::string& w : warnings) {
    const std::string line = "duet: warning: " + scene.path + ": " + w;
    if (said.insert(line).second) std::cerr << line << '\n';
  }
}

}  // namespace

Scene load_scene_checked(const std::string& path, const std::vector<std::string>& overrides,
                         bool force) {
  Scene scene = load_scene(path, overrides, model_material_check(force));
  warn_implausible(scene);
  return scene;
}

Scene load_scene_checked_from_string(const std::string& toml_text, const std::string& path,
                                     const std::vector<std::string>& overrides, bool force) {
  Scene scene = load_scene_from_string(toml_text, path, overrides, model_material_check(force));
  warn_implausible(scene);
  return scene;
}

}  // namespace duet
