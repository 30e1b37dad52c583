#include "benchmarks/scene_input.hpp"

#include "constitutive/registry.hpp"

namespace duet {

MaterialCheck model_material_check() {
  return [](const std::string& model, const std::map<std::string, ParameterValue>& parameters,
            const std::string& context) {
    std::map<std::string, ParameterValue> resolved;
    constitutive::make_model(model, parameters, context, &resolved);
    return resolved;
  };
}

Scene load_scene_checked(const std::string& path, const std::vector<std::string>& overrides) {
  return load_scene(path, overrides, model_material_check());
}

Scene load_scene_checked_from_string(const std::string& toml_text, const std::string& path,
                                     const std::vector<std::string>& overrides) {
  return load_scene_from_string(toml_text, path, overrides, model_material_check());
}

}  // namespace duet
