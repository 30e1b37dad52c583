#include "benchmarks/run_summary.hpp"

#include <cmath>
#include <limits>

namespace duet {

const Accuracy* RunSummary::worst_accuracy() const {
  const Accuracy* worst = nullptr;
  for (const auto& [name, a] : accuracy) {
    if (worst == nullptr || std::isnan(worst->rel_error) || a.rel_error > worst->rel_error) {
      worst = &a;
    }
  }
  return worst;
}

double RunSummary::max_rel_error() const {
  const Accuracy* worst = worst_accuracy();
  return worst ? worst->rel_error : std::numeric_limits<double>::quiet_NaN();
}

namespace {

double number_or_nan(const Json* j) {
  return j && j->is_number() ? j->number() : std::numeric_limits<double>::quiet_NaN();
}

std::string string_or_empty(const Json* j) {
  return j && j->is_string() ? j->string() : "";
}

}  // namespace

RunSummary summary_from_metrics(const Json& metrics, const std::string& out_dir) {
  RunSummary s;
  s.out_dir = out_dir;
  s.scene = string_or_empty(metrics.find("scene"));
  s.method = string_or_empty(metrics.find("method"));
  s.spacing = number_or_nan(metrics.find("spacing"));
  s.particles = static_cast<long>(number_or_nan(metrics.find("particles")));
  s.steps = static_cast<long>(number_or_nan(metrics.find("steps")));
  s.wall_seconds = number_or_nan(metrics.find("wall_seconds"));
  s.status = string_or_empty(metrics.find("status"));
  if (const Json* failure = metrics.find("failure"); failure && failure->is_object()) {
    s.failure_reason = string_or_empty(failure->find("reason"));
    s.failure_time = number_or_nan(failure->find("time"));
  }
  if (const Json* measures = metrics.find("measures"); measures && measures->is_object()) {
    for (const auto& [name, value] : measures->members()) {
      s.measures[name] = value.is_number() ? value.number() : std::nan("");
    }
  }
  if (const Json* accuracy = metrics.find("accuracy"); accuracy && accuracy->is_object()) {
    for (const auto& [name, a] : accuracy->members()) {
      Accuracy entry;
      entry.value = number_or_nan(a.find("value"));
      entry.reference = number_or_nan(a.find("reference"));
      entry.rel_error = number_or_nan(a.find("rel_error"));
      entry.source = string_or_empty(a.find("source"));
      entry.signed_error = number_or_nan(a.find("signed_error"));
      entry.worst_at = number_or_nan(a.find("worst_at"));
      s.accuracy[name] = entry;
    }
  }
  if (const Json* warnings = metrics.find("warnings"); warnings && warnings->is_array()) {
    for (const Json& w : warnings->elements()) {
      if (w.is_string()) s.warnings.push_back(w.string());
    }
  }
  if (const Json* timing = metrics.find("timing"); timing && timing->is_object()) {
    for (const auto& [name, value] : timing->members()) {
      if (value.is_number()) s.timing[name] = value.number();
    }
  }
  return s;
}

std::vector<TargetChoice> choose_for_target(const std::vector<RunSummary>& runs, double target) {
  std::vector<TargetChoice> choices;
  for (const auto& run : runs) {
    TargetChoice* choice = nullptr;
    for (auto& c : choices) {
      if (c.method == run.method) choice = &c;
    }
    if (!choice) {
      choices.push_back({run.method, std::nullopt});
      choice = &choices.back();
    }
    const double error = run.max_rel_error();
    // A failed run, or one with no scored measure, never meets a target.
    if (!run.completed() || std::isnan(error) || !(error < target)) continue;
    if (!choice->run || run.spacing > choice->run->spacing) choice->run = run;
  }
  return choices;
}

}  // namespace duet
