#pragma once
// Scene loading for the program and the tests: the common loader with every material checked
// against the constitutive registry (unknown model, missing or out-of-range parameter), so bad
// input is refused before any work with the file and line of the offending key.

#include <string>
#include <vector>

#include "common/scene_loader.hpp"

namespace duet {

/// The MaterialCheck that builds each material's model through constitutive::make_model and,
/// unless `force`, refuses a value in a wrong unit beyond doubt (constitutive::UnitDoubt::refused:
/// E = 20 meant in MPa), naming the key; `duet run`, `check` and `compare` pass --force here.
MaterialCheck model_material_check(bool force = false);

/// The override `--spacing DP` stands for ("spacing=DP"); throws InputError naming the option
/// unless DP is a positive finite number (the loader would name `--set spacing=` instead).
std::string spacing_override(double spacing);

/// One line per measure taken at a time (at = "time") after the scene's end time, which a run
/// never reaches: its value is null and nothing is scored (`--set time.end_time` shortened).
std::vector<std::string> measures_after_the_end(const Scene& scene);

/// Loads with model_material_check(force); the values in a doubtful unit that it lets through
/// are said on stderr as warnings.
Scene load_scene_checked(const std::string& path, const std::vector<std::string>& overrides = {},
                         bool force = false);

Scene load_scene_checked_from_string(const std::string& toml_text, const std::string& path,
                                     const std::vector<std::string>& overrides = {},
                                     bool force = false);

}  // namespace duet
