#pragma once
// Typed reading of one TOML table of a scene file against its list of keys: every value is
// type-checked, every key the table holds must be one of its schema's keys (unknown keys are
// refused with a did-you-mean), and every value read, default included, is copied to the
// resolved table (Scene::resolved_toml). Errors are InputError "FILE:LINE: key: problem;
// expected ...", with "--set key=value" in place of FILE:LINE for a value given on the command
// line.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "common/scene.hpp"
#include "common/tensor.hpp"

namespace duet {

/// Where values came from: the file, and the keys overridden by --set (dotted key -> raw text).
struct SceneSource {
  std::string file;
  std::map<std::string, std::string> overrides;

  /// "FILE:LINE" for a node of the file, "--set key=value" for an overridden key (or one below
  /// an overridden table), "FILE" when no line is known.
  std::string where(const std::string& key, const toml::node* node) const;
};

/// A check on a number: returns "" when fine, else what was expected ("a length > 0 (m)").
using NumberCheck = std::function<std::string(double)>;
NumberCheck positive(std::string_view what_and_unit);
NumberCheck non_negative(std::string_view what_and_unit);
NumberCheck in_closed(double lo, double hi, std::string_view what_and_unit);
NumberCheck any_number();

class SectionReader {
 public:
  /// `table` may be null (the section is absent: every key takes its default). `path` is the
  /// dotted key of the table ("" for the root), `keys` its schema, `resolved` the output table
  /// that receives what was read. Refuses keys not in `keys` at once (did-you-mean); an empty
  /// `keys` is an open table (a material's model parameters).
  SectionReader(const toml::table* table, std::string path, std::vector<std::string> keys,
                const SceneSource& source, toml::table& resolved);

  bool has(std::string_view key) const;
  const toml::node* node(std::string_view key) const;

  double number(std::string_view key, const NumberCheck& check);  // required
  double number(std::string_view key, double fallback, const NumberCheck& check);
  int integer(std::string_view key, int fallback, int min_value);
  bool boolean(std::string_view key, bool fallback);
  std::string string(std::string_view key);  // required
  std::string string(std::string_view key, std::string fallback);
  /// One of `choices` (required when fallback is nullopt).
  std::string choice(std::string_view key, const std::vector<std::string>& choices,
                     std::optional<std::string> fallback);
  Vec2 vec2(std::string_view key);  // required [x, y]
  Vec2 vec2(std::string_view key, const Vec2& fallback);
  /// A required list of [x, y] points, at least `min_points`.
  std::vector<Vec2> points(std::string_view key, std::size_t min_points);
  /// An optional schedule [[t, a, b], ...] (`width` 3) or [[t, a], ...] (`width` 2, b = 0), times
  /// non-decreasing. Empty when absent.
  Schedule schedule(std::string_view key, int width);

  /// A sub-table (null when absent); a non-table value is a type error.
  const toml::table* table(std::string_view key) const;
  /// Refuses keys of the schema that the chosen settings did not read ("does not apply", e.g.
  /// `vertices` on a rectangle), except those in `not_mine` (sub-tables read by another reader).
  void finish(const std::vector<std::string>& not_mine = {}) const;

  /// Throws InputError "WHERE: path.key: problem; expected ...".
  [[noreturn]] void fail(std::string_view key, const std::string& problem,
                         const std::string& expected) const;
  /// Location of a key (or of the table itself for "").
  std::string where(std::string_view key) const;
  std::string key_path(std::string_view key) const;
  const std::string& path() const { return path_; }
  toml::table& resolved() { return resolved_; }

 private:
  const toml::node& require(std::string_view key) const;
  double as_number(std::string_view key, const toml::node& node) const;
  Vec2 as_vec2(std::string_view key, const toml::node& node) const;

  const toml::table* table_;
  std::string path_;
  std::vector<std::string> keys_;
  const SceneSource& source_;
  toml::table& resolved_;
  mutable std::vector<std::string> read_;
};

/// "a string", "an integer", "an array", ... for messages.
std::string describe_type(const toml::node& node);

/// The resolved sub-table `key` of `parent`, created when absent.
toml::table& resolved_child(toml::table& parent, std::string_view key);

}  // namespace duet
