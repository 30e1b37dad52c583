#include "constitutive/parameters.hpp"

#include <cmath>
#include <sstream>

#include "common/input_error.hpp"
#include "common/suggest.hpp"

namespace duet::constitutive {

namespace {

std::string format_number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

}  // namespace

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  const bool above = lo_open ? v > lo : v >= lo;
  const bool below = hi_open ? v < hi : v <= hi;
  return above && below;
}

std::string Range::describe() const {
  const bool no_lo = lo <= -1e307;
  const bool no_hi = hi >= 1e307;
  if (no_lo && no_hi) return "any finite number";
  if (no_hi) return (lo_open ? "> " : ">= ") + format_number(lo);
  if (no_lo) return (hi_open ? "< " : "<= ") + format_number(hi);
  return std::string(lo_open ? "(" : "[") + format_number(lo) + ", " + format_number(hi) +
         (hi_open ? ")" : "]");
}

std::string Range::general() const {
  return rule.empty() ? describe() : rule;
}

std::string Range::in_full() const {
  return rule.empty() ? describe() : rule + " = " + describe();
}

Parameters::Parameters(std::string context, std::map<std::string, ParameterValue> values)
    : context_(std::move(context)), values_(std::move(values)) {}

std::string Parameters::key(std::string_view name) const {
  return context_.empty() ? std::string(name) : context_ + "." + std::string(name);
}

bool Parameters::has(std::string_view name) const {
  return values_.find(std::string(name)) != values_.end();
}

void Parameters::note(ParameterSpec spec) {
  for (const ParameterSpec& s : specs_) {
    if (s.name == spec.name) return;
  }
  specs_.push_back(std::move(spec));
}

double Parameters::require(std::string_view name, Range range, std::string_view unit,
                           std::string_view meaning) {
  note({std::string(name), "required", range.general(), std::string(unit), "",
        std::string(meaning)});
  const auto it = values_.find(std::string(name));
  if (it == values_.end()) {
    // A misspelt name is the likeliest cause: point at the given key that looks like it.
    std::vector<std::string> unread;
    for (const auto& [given, value] : values_) {
      if (!read_.count(given)) unread.push_back(given);
    }
    const std::string near = closest_match(name, unread);
    const std::string beside =
        near.empty()
            ? ""
            : ", and '" + key(near) + "', which this model does not take, is probably it misspelt";
    throw InputError(key(name) + ": missing" + beside + "; " + std::string(meaning) +
                     " is required (" + range.in_full() + ", unit " + std::string(unit) + ")");
  }
  read_.insert(std::string(name));
  const double* v = std::get_if<double>(&it->second);
  if (!v) {
    throw InputError(key(name) + " = \"" + std::get<std::string>(it->second) + "\": " +
                     std::string(meaning) + " must be a number (" + std::string(unit) + ")");
  }
  if (!range.contains(*v)) {
    throw InputError(key(name) + " = " + format_number(*v) + ": " + std::string(meaning) +
                     " must lie in " + range.in_full() + " (unit " + std::string(unit) + ")");
  }
  resolved_[std::string(name)] = *v;
  return *v;
}

double Parameters::optional(std::string_view name, double fallback, Range range,
                            std::string_view unit, std::string_view meaning,
                            std::string_view fallback_rule) {
  note({std::string(name), "optional", range.general(), std::string(unit),
        fallback_rule.empty() ? format_number(fallback) : std::string(fallback_rule),
        std::string(meaning)});
  if (!has(name)) {
    resolved_[std::string(name)] = fallback;
    return fallback;
  }
  return require(name, range, unit, meaning);
}

std::string Parameters::choice(std::string_view name, const std::vector<std::string>& choices,
                               std::string_view fallback, std::string_view meaning) {
  std::string words;
  for (const auto& c : choices) words += (words.empty() ? "" : " | ") + c;
  note({std::string(name), "choice", words, "", std::string(fallback), std::string(meaning)});
  const auto it = values_.find(std::string(name));
  if (it == values_.end()) {
    resolved_[std::string(name)] = std::string(fallback);
    return std::string(fallback);
  }
  read_.insert(std::string(name));
  const std::string* word = std::get_if<std::string>(&it->second);
  const std::string given = word ? *word : format_number(std::get<double>(it->second));
  for (const auto& c : choices) {
    if (c == given) {
      resolved_[std::string(name)] = c;
      return c;
    }
  }
  throw InputError(key(name) + " = \"" + given + "\": " + std::string(meaning) +
                   " must be one of " + join(choices) + did_you_mean(given, choices));
}

void Parameters::record(std::string_view name, double value) {
  note({std::string(name), "derived", "", "", "",
        "derived from the others (not given in this form)"});
  resolved_[std::string(name)] = value;
}

void Parameters::finish() const {
  std::vector<std::string> known;
  for (const auto& [name, value] : resolved_) known.push_back(name);
  for (const auto& [name, value] : values_) {
    if (read_.count(name)) continue;
    throw InputError(key(name) + ": unknown parameter" + did_you_mean(name, known) +
                     "; this model takes " + join(known));
  }
}

}  // namespace duet::constitutive
