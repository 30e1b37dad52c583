#pragma once
// A small JSON value for what runs write (metrics.json, element.json). Objects keep insertion
// order; non-finite numbers are written as null (JSON has no NaN), so every file parses.

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace duet {

class Json {
 public:
  using Object = std::vector<std::pair<std::string, Json>>;
  using Array = std::vector<Json>;

  Json() = default;  // null
  Json(std::nullptr_t) {}
  Json(bool b) : value_(b) {}
  Json(int v) : value_(static_cast<double>(v)) {}
  Json(long v) : value_(static_cast<double>(v)) {}
  Json(long long v) : value_(static_cast<double>(v)) {}
  Json(unsigned v) : value_(static_cast<double>(v)) {}
  Json(unsigned long v) : value_(static_cast<double>(v)) {}
  Json(unsigned long long v) : value_(static_cast<double>(v)) {}
  Json(double v) : value_(v) {}
  Json(const char* s) : value_(std::string(s)) {}
  Json(std::string s) : value_(std::move(s)) {}
  Json(std::string_view s) : value_(std::string(s)) {}

  static Json object() {
    Json j;
    j.value_ = Object{};
    return j;
  }
  static Json array() {
    Json j;
    j.value_ = Array{};
    return j;
  }
  static Json array(const std::vector<double>& values);

  /// Object member (appended when missing; a null value becomes an object).
  Json& operator[](std::string_view key);
  /// Object member or nullptr.
  const Json* find(std::string_view key) const;
  /// Append to an array (a null value becomes an array).
  void push_back(Json value);

  bool is_null() const { return std::holds_alternative<std::monostate>(value_); }
  bool is_number() const { return std::holds_alternative<double>(value_); }
  bool is_string() const { return std::holds_alternative<std::string>(value_); }
  bool is_object() const { return std::holds_alternative<Object>(value_); }
  bool is_array() const { return std::holds_alternative<Array>(value_); }
  bool is_bool() const { return std::holds_alternative<bool>(value_); }
  bool boolean() const { return std::get<bool>(value_); }
  double number() const { return std::get<double>(value_); }
  const std::string& string() const { return std::get<std::string>(value_); }
  const Object& members() const { return std::get<Object>(value_); }
  const Array& elements() const { return std::get<Array>(value_); }

  /// Text with `indent` spaces per level (0: one line).
  std::string dump(int indent = 2) const;

 private:
  void dump_to(std::string& out, int indent, int level) const;
  std::variant<std::monostate, bool, double, std::string, Object, Array> value_;
};

/// Parses JSON text (RFC 8259; what dump() writes and more). Throws std::runtime_error naming the
/// offset and what was expected.
Json parse_json(std::string_view text);

/// Parses the file at `path`; throws std::runtime_error naming the path when it cannot be read or
/// parsed.
Json read_json(const std::string& path);

/// Writes `value.dump()` to `path`; throws std::runtime_error when the file cannot be written.
void write_json(const std::string& path, const Json& value);

/// Escape a string for JSON.
std::string json_escape(std::string_view s);

}  // namespace duet
