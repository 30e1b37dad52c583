#pragma once
// Model parameters as the user gave them (scene material table or `duet element --set`), read by a
// model's constructor with range checks and units, so bad input is refused at construction with
// the key, the value, the allowed range and its unit.

#include <map>
#include <set>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "common/parameter_value.hpp"

namespace duet::constitutive {

using duet::ParameterValue;

/// An interval with open or closed ends; infinite ends allowed. A range whose bounds follow other
/// parameters (a dilatancy angle at most phi) carries its `rule` ("[0, phi]"): what `duet models`
/// lists, where the numbers would be those of one example.
struct Range {
  double lo = -1e308;
  double hi = 1e308;
  bool lo_open = false;
  bool hi_open = false;
  std::string rule = {};

  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
  static Range open(double lo, double hi) { return {lo, hi, true, true}; }
  static Range closed_open(double lo, double hi) { return {lo, hi, false, true}; }
  static Range open_closed(double lo, double hi) { return {lo, hi, true, false}; }
  static Range positive() { return {0.0, 1e308, true, false}; }
  static Range non_negative() { return {0.0, 1e308, false, false}; }
  static Range negative() { return {-1e308, 0.0, false, true}; }
  static Range any() { return {}; }

  /// The same bounds with the rule they follow: Range::closed(0, phi).following("[0, phi]").
  Range following(std::string text) const {
    Range r = *this;
    r.rule = std::move(text);
    return r;
  }

  bool contains(double v) const;
  std::string describe() const;  // the numbers: "[0, 0.5)", "> 0", ...
  std::string general() const;   // the rule where there is one, else describe()
  std::string in_full() const;   // "[0, phi] = [0, 30]", or describe(): for messages
};

/// One parameter as a model's constructor read it: what `duet models` lists.
struct ParameterSpec {
  std::string name;
  std::string kind;   // "required", "optional", "choice", "derived"
  std::string range;  // Range::describe(), or the choices "a | b"
  std::string unit;
  std::string fallback;  // the default of an optional parameter or a choice, else ""
  std::string meaning;
};

/// Reads named parameters for one model. `context` prefixes every message ("material.sand").
/// Every value read (default included) is recorded in resolved(); finish() refuses keys that no
/// one read, with a did-you-mean.
class Parameters {
 public:
  Parameters(std::string context, std::map<std::string, ParameterValue> values);

  /// A required number in `range`; `unit` is printed in errors ("Pa", "deg", "-").
  double require(std::string_view name, Range range, std::string_view unit,
                 std::string_view meaning);
  /// An optional number with its default; `fallback_rule` names a default that follows other
  /// parameters ("c cot(phi)") for `duet models`, where the number would be one example's.
  double optional(std::string_view name, double fallback, Range range, std::string_view unit,
                  std::string_view meaning, std::string_view fallback_rule = {});
  /// An optional word from `choices`.
  std::string choice(std::string_view name, const std::vector<std::string>& choices,
                     std::string_view fallback, std::string_view meaning);
  bool has(std::string_view name) const;

  /// Record a derived value (e.g. c1..c4 from Ei, nu, phi, psi) so it appears in resolved().
  void record(std::string_view name, double value);

  /// Throws InputError naming any key that was given but never read.
  void finish() const;

  const std::string& context() const { return context_; }
  const std::map<std::string, ParameterValue>& resolved() const { return resolved_; }
  /// Every parameter read so far, in the order first read (derived values as "derived").
  const std::vector<ParameterSpec>& specs() const { return specs_; }

  /// Message prefix for key `name`: "material.sand.nu".
  std::string key(std::string_view name) const;

 private:
  std::string context_;
  std::map<std::string, ParameterValue> values_;
  std::map<std::string, ParameterValue> resolved_;
  mutable std::set<std::string, std::less<>> read_;
  std::vector<ParameterSpec> specs_;

  void note(ParameterSpec spec);
};

}  // namespace duet::constitutive
