#pragma once
// Reads a scene file (TOML) into a Scene with every default filled in, applies --set overrides,
// and validates it. Bad input throws InputError "FILE:LINE: key: problem; expected ..." before
// any work (the duet program turns it into exit status 2).
//
// File layout (every table optional unless noted; named tables are [kind.<name>]):
//   name, description, spacing (required, m), gravity = [gx, gy] (m/s^2, default [0, 0]),
//   confined (bool: every body must be enclosed by walls / rigid bodies)
//   [time] end_time (required, s), output_interval (s, default end_time / 50)
//   [domain] min, max ([x, y], m; default the bounding box of everything), padding (m)
//   [initial_stress] kind = none | isotropic | geostatic | gravity-loading, pressure, K0,
//     damping, time
//   [material.<name>] model, density (kg/m^3), then the model's parameters
//   [body.<name>] material, shape = rectangle (min, max) | polygon (vertices), initial_velocity
//   [wall.<name>] points, condition = no-slip | free-slip, velocity = [[t, vx, vy], ...] or
//     centre + radial_velocity = [[t, v_r], ...]
//   [rigid_body.<name>] vertices, velocity, surface = rough | smooth | friction, friction
//   [load.<name>] body, min, max (the box of particles that share it), force = [[t, fx, fy], ...]
//   [strength_reduction] factor (c and phi reduced, Peng 2015 eqs 39-40), rule = tangent | angle
//   [measure.<name>] kind = front | height | reaction | wall_stress | max_displacement |
//     displacement | period | safety_factor | expansion, target, component = x | y | magnitude,
//     at = end | max | series | time (with time = ...), min_thickness | min_depth, column_width,
//     divide_by, scale
//   [reference.<measure name>] value, source (required), tolerance
//   [sph], [spfem], [spfem.implicit]: method options (common/scene.hpp has the defaults)

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "common/scene.hpp"

namespace duet {

/// Checks a material's model and parameters and returns the parameters as the model resolved them
/// (defaults and derived values included); throws InputError "<context>.<key> = value: ...".
/// common/ knows no soil model, so the layer that does provides it (benchmarks/scene_input.hpp
/// passes the constitutive registry); without one, model names and parameters are not checked.
using MaterialCheck = std::function<std::map<std::string, ParameterValue>(
    const std::string& model, const std::map<std::string, ParameterValue>& parameters,
    const std::string& context)>;

/// Loads, overrides and validates. `overrides` are "dotted.key=value" strings (from --set); the
/// value is read as TOML (number, bool, quoted string, array), a bare word as a string, and is
/// type-checked like the file. `--spacing DP` is the override "spacing=DP".
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {},
                 const MaterialCheck& check = {});

/// The same from TOML text (`path` is only used in messages and for the default name).
Scene load_scene_from_string(const std::string& toml_text, const std::string& path,
                             const std::vector<std::string>& overrides = {},
                             const MaterialCheck& check = {});

}  // namespace duet
