#include "common/scene_schema.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/enum_names.hpp"
#include "common/input_error.hpp"
#include "common/suggest.hpp"

namespace duet {

namespace {

std::string format_number(double v) {
  std::ostringstream out;
  out.precision(12);
  out << v;
  return out.str();
}

toml::array to_array(const Vec2& v) {
  return toml::array{v.x(), v.y()};
}

}  // namespace

std::string SceneSource::where(const std::string& key, const toml::node* node) const {
  for (const auto& [overridden, text] : overrides) {
    // The key itself, or a key inside an overridden table.
    if (key == overridden || key.starts_with(overridden + ".")) {
      return "--set " + overridden + "=" + text;
    }
  }
  if (node && node->source().begin.line > 0) {
    return file + ":" + std::to_string(node->source().begin.line);
  }
  return file;
}

NumberCheck positive(std::string_view what_and_unit) {
  std::string what(what_and_unit);
  return [what](double v) { return v > 0.0 ? std::string() : what + " > 0"; };
}

NumberCheck non_negative(std::string_view what_and_unit) {
  std::string what(what_and_unit);
  return [what](double v) { return v >= 0.0 ? std::string() : what + " >= 0"; };
}

NumberCheck in_closed(double lo, double hi, std::string_view what_and_unit) {
  std::string what(what_and_unit);
  return [=](double v) {
    return v >= lo && v <= hi ? std::string()
                              : what + " in [" + format_number(lo) + ", " + format_number(hi) + "]";
  };
}

NumberCheck any_number() {
  return [](double) { return std::string(); };
}

std::string describe_type(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::table:
      return "a table";
    default:
      return "a date or time";
  }
}

toml::table& resolved_child(toml::table& parent, std::string_view key) {
  if (auto* existing = parent.get_as<toml::table>(key)) return *existing;
  return *parent.insert_or_assign(key, toml::table{}).first->second.as_table();
}

SectionReader::SectionReader(const toml::table* table, std::string path,
                             std::vector<std::string> keys, const SceneSource& source,
                             toml::table& resolved)
    : table_(table),
      path_(std::move(path)),
      keys_(std::move(keys)),
      source_(source),
      resolved_(resolved) {
  // Unknown keys first: a misspelt key is the likeliest cause of a "missing key" that follows.
  if (!table_ || keys_.empty()) return;
  for (const auto& [k, value] : *table_) {
    const std::string key(k.str());
    if (std::find(keys_.begin(), keys_.end(), key) == keys_.end()) {
      fail(key, "unknown key" + did_you_mean(key, keys_), "one of " + join(keys_));
    }
  }
}

std::string SectionReader::key_path(std::string_view key) const {
  if (key.empty()) return path_;
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

std::string SectionReader::where(std::string_view key) const {
  const toml::node* n = key.empty() ? static_cast<const toml::node*>(table_) : node(key);
  if (!n) n = table_;  // a missing key: the table's header line
  return source_.where(key_path(key), n);
}

void SectionReader::fail(std::string_view key, const std::string& problem,
                         const std::string& expected) const {
  std::string message = where(key) + ": " + key_path(key) + ": " + problem;
  if (!expected.empty()) message += "; expected " + expected;
  throw InputError(message);
}

bool SectionReader::has(std::string_view key) const {
  return node(key) != nullptr;
}

const toml::node* SectionReader::node(std::string_view key) const {
  return table_ ? table_->get(key) : nullptr;
}

const toml::node& SectionReader::require(std::string_view key) const {
  read_.emplace_back(key);
  const toml::node* n = node(key);
  if (!n) fail(key, "missing key", "a value for it");
  return *n;
}

double SectionReader::as_number(std::string_view key, const toml::node& n) const {
  if (auto v = n.value_exact<double>()) return *v;
  if (auto i = n.value_exact<std::int64_t>()) return static_cast<double>(*i);
  fail(key, "wrong type: " + describe_type(n), "a number");
}

Vec2 SectionReader::as_vec2(std::string_view key, const toml::node& n) const {
  const toml::array* a = n.as_array();
  if (!a || a->size() != 2) fail(key, "wrong type: " + describe_type(n), "[x, y]");
  const Vec2 v(as_number(key, *a->get(0)), as_number(key, *a->get(1)));
  // nan and inf are TOML numbers; a point or a vector of them is no geometry (the fuzzer's nan
  // in a wall reached the SPH cell list as an internal error, exit 1)
  if (!v.allFinite()) {
    fail(key, "[" + format_number(v.x()) + ", " + format_number(v.y()) + "]",
         "finite numbers in [x, y]");
  }
  return v;
}

double SectionReader::number(std::string_view key, const NumberCheck& check) {
  const toml::node& n = require(key);
  const double v = as_number(key, n);
  if (!std::isfinite(v)) fail(key, "value " + format_number(v), "a finite number");
  if (std::string expected = check(v); !expected.empty())
    fail(key, "is " + format_number(v), expected);
  resolved_.insert_or_assign(key, v);
  return v;
}

double SectionReader::number(std::string_view key, double fallback, const NumberCheck& check) {
  if (has(key)) return number(key, check);
  read_.emplace_back(key);
  resolved_.insert_or_assign(key, fallback);
  return fallback;
}

int SectionReader::integer(std::string_view key, int fallback, int min_value) {
  read_.emplace_back(key);
  int v = fallback;
  if (const toml::node* n = node(key)) {
    auto i = n->value_exact<std::int64_t>();
    if (!i) fail(key, "wrong type: " + describe_type(*n), "an integer");
    if (*i < min_value || *i > 1000000000) {
      fail(key, "is " + std::to_string(*i), "an integer >= " + std::to_string(min_value));
    }
    v = static_cast<int>(*i);
  }
  resolved_.insert_or_assign(key, v);
  return v;
}

bool SectionReader::boolean(std::string_view key, bool fallback) {
  read_.emplace_back(key);
  bool v = fallback;
  if (const toml::node* n = node(key)) {
    auto b = n->value_exact<bool>();
    if (!b) fail(key, "wrong type: " + describe_type(*n), "true or false");
    v = *b;
  }
  resolved_.insert_or_assign(key, v);
  return v;
}

std::string SectionReader::string(std::string_view key) {
  const toml::node& n = require(key);
  auto s = n.value_exact<std::string>();
  if (!s) fail(key, "wrong type: " + describe_type(n), "a string");
  resolved_.insert_or_assign(key, *s);
  return *s;
}

std::string SectionReader::string(std::string_view key, std::string fallback) {
  if (has(key)) return string(key);
  read_.emplace_back(key);
  resolved_.insert_or_assign(key, fallback);
  return fallback;
}

std::string SectionReader::choice(std::string_view key, const std::vector<std::string>& choices,
                                  std::optional<std::string> fallback) {
  const std::string v = (fallback && !has(key)) ? string(key, *fallback) : string(key);
  if (std::find(choices.begin(), choices.end(), v) == choices.end()) {
    fail(key, "\"" + v + "\" is not a known choice" + did_you_mean(v, choices),
         "one of " + join(choices));
  }
  return v;
}

Vec2 SectionReader::vec2(std::string_view key) {
  const Vec2 v = as_vec2(key, require(key));
  resolved_.insert_or_assign(key, to_array(v));
  return v;
}

Vec2 SectionReader::vec2(std::string_view key, const Vec2& fallback) {
  if (has(key)) return vec2(key);
  read_.emplace_back(key);
  resolved_.insert_or_assign(key, to_array(fallback));
  return fallback;
}

std::vector<Vec2> SectionReader::points(std::string_view key, std::size_t min_points) {
  const toml::node& n = require(key);
  const toml::array* a = n.as_array();
  if (!a) fail(key, "wrong type: " + describe_type(n), "a list of [x, y] points");
  std::vector<Vec2> out;
  toml::array resolved;
  for (const toml::node& p : *a) {
    out.push_back(as_vec2(key, p));
    resolved.push_back(to_array(out.back()));
  }
  if (out.size() < min_points) {
    fail(key, std::to_string(out.size()) + " points",
         "at least " + std::to_string(min_points) + " [x, y] points");
  }
  resolved_.insert_or_assign(key, std::move(resolved));
  return out;
}

Schedule SectionReader::schedule(std::string_view key, int width) {
  read_.emplace_back(key);
  Schedule out;
  toml::array resolved;
  if (const toml::node* n = node(key)) {
    const std::string shape = width == 3 ? "[[t, x, y], ...]" : "[[t, v], ...]";
    const toml::array* a = n->as_array();
    if (!a) fail(key, "wrong type: " + describe_type(*n), "a schedule " + shape);
    for (const toml::node& row : *a) {
      const toml::array* r = row.as_array();
      if (!r || r->size() != static_cast<std::size_t>(width)) {
        fail(key, "a knot is " + describe_type(row) + " of the wrong size", "a schedule " + shape);
      }
      Knot k;
      k.time = as_number(key, *r->get(0));
      k.value.x() = as_number(key, *r->get(1));
      k.value.y() = width == 3 ? as_number(key, *r->get(2)) : 0.0;
      if (!out.empty() && k.time < out.back().time) {
        fail(key,
             "time " + format_number(k.time) + " comes after " + format_number(out.back().time),
             "knot times in non-decreasing order (s)");
      }
      out.push_back(k);
      toml::array knot{k.time, k.value.x()};
      if (width == 3) knot.push_back(k.value.y());
      resolved.push_back(std::move(knot));
    }
  }
  resolved_.insert_or_assign(key, std::move(resolved));
  return out;
}

const toml::table* SectionReader::table(std::string_view key) const {
  const toml::node* n = node(key);
  if (!n) return nullptr;
  if (!n->is_table()) fail(key, "wrong type: " + describe_type(*n), "a table");
  return n->as_table();
}

void SectionReader::finish(const std::vector<std::string>& not_mine) const {
  if (!table_) return;
  for (const auto& [k, value] : *table_) {
    const std::string key(k.str());
    const bool read = std::find(read_.begin(), read_.end(), key) != read_.end() ||
                      std::find(not_mine.begin(), not_mine.end(), key) != not_mine.end();
    if (!read) fail(key, "does not apply with the other settings of this table", "");
  }
}

}  // namespace duet

namespace duet {

const char* to_string(WallCondition c) {
  return name_of(c, kWallConditionNames);
}
const char* to_string(Surface s) {
  return name_of(s, kSurfaceNames);
}
const char* to_string(InitialStressKind k) {
  return name_of(k, kInitialStressKindNames);
}
const char* to_string(MeasureKind k) {
  return name_of(k, kMeasureKindNames);
}
const char* to_string(MeasureAt a) {
  return name_of(a, kMeasureAtNames);
}
const char* to_string(SphKernel k) {
  return name_of(k, kSphKernelNames);
}
const char* to_string(SphWallStress w) {
  return name_of(w, kSphWallStressNames);
}
const char* to_string(SphIntegrator i) {
  return name_of(i, kSphIntegratorNames);
}
const char* to_string(Remesh r) {
  return name_of(r, kRemeshNames);
}

}  // namespace duet
