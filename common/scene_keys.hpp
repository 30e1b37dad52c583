#pragma once
// The scene schema as data: every key of every table of a scene file with its type, unit,
// default and meaning. The loader (scene_loader.cpp) takes the keys each table accepts from this
// list, so `duet keys` cannot list a key the loader refuses, nor miss one it accepts; a test
// (tests/benchmarks/listing_commands_test.cpp) checks every literal default against what the loader
// fills in.

#include <string>
#include <string_view>
#include <vector>

namespace duet {

struct SceneKey {
  std::string section;  // dotted table: "" (top level), "sph", "spfem.implicit", "wall.<name>"
  std::string key;
  std::string type;  // "number", "integer", "boolean", "string", "[x, y]", "table", ...
  std::string unit;  // "m", "s", "-", "" where none
  // A TOML literal ("1.5", "\"every-step\"", "true") the loader fills in when the key is absent;
  // "required"; or a description in parentheses ("(end_time / 50)") for a computed default.
  std::string fallback;
  std::string meaning;  // one line
};

/// Every key, in the order `duet keys` prints them.
const std::vector<SceneKey>& scene_keys();

/// The keys of one table ("" for the top level), in schema order.
std::vector<std::string> scene_keys_of(std::string_view section);

/// The tables, in schema order ("" first).
std::vector<std::string> scene_sections();

/// True when `fallback` is a TOML literal (not "required", not a computed "(...)" default).
bool is_literal_default(const SceneKey& key);

}  // namespace duet
