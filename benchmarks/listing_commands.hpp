#pragma once
// `duet keys [SECTION]`, `duet models [MODEL]` and `duet methods`: what a scene may say, printed
// from the loader's schema (common/scene_keys.hpp), the models' own parameter reading and the
// method registry, so the listings cannot drift from what a run accepts.

#include <CLI/CLI.hpp>
#include <string>

namespace duet {

/// The keys of `section` ("" or "all": every table) as a text table. Throws InputError with a
/// did-you-mean for an unknown section.
std::string keys_listing(const std::string& section);

/// Every model (or one), its forms and parameters: name, kind, range, unit, default, meaning.
std::string models_listing(const std::string& model);

/// The unit of a dotted scene key ("sph.sound_speed" -> "m/s", "material.sand.phi" -> "deg",
/// from the model that reads it); "" when unknown or unitless text.
std::string scene_key_unit(const std::string& dotted);

/// Every registered method with its summary, kind and option tables.
std::string methods_listing();

void add_listing_commands(CLI::App& app, int& exit_code);

}  // namespace duet
