#pragma once
// What one run produced, as the comparison and stability reports read it (the fields of
// metrics.json that compare.csv flattens).

#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/json.hpp"

namespace duet {

struct Accuracy {
  double value = 0.0;
  double reference = 0.0;
  double rel_error = 0.0;  // |value - reference| / |reference|; a curve's largest over its window
  std::string source;
  // (value - reference) / |reference| where rel_error is: over (+) or under (-) the reference;
  // NaN in a metrics.json written before it was recorded
  double signed_error = std::numeric_limits<double>::quiet_NaN();
  double worst_at = std::numeric_limits<double>::quiet_NaN();  // a curve's: where (its abscissa)
};

struct RunSummary {
  std::string scene;
  std::string method;
  double spacing = 0.0;
  long particles = 0;
  long steps = 0;
  double wall_seconds = 0.0;
  std::string status;  // "completed" | "failed"
  std::string failure_reason;
  double failure_time = 0.0;
  std::map<std::string, double> measures;
  std::map<std::string, Accuracy> accuracy;
  std::map<std::string, double> timing;
  std::vector<std::string> warnings;  // metrics.json's: what the run doubts about itself
  std::string out_dir;

  bool completed() const { return status == "completed"; }
  /// The scored measure with the largest relative error (the first of equals), or none.
  const Accuracy* worst_accuracy() const;
  /// Its relative error (NaN when none is scored).
  double max_rel_error() const;
};

/// Builds the summary from a metrics.json object.
RunSummary summary_from_metrics(const Json& metrics, const std::string& out_dir);

/// Per method: the coarsest spacing whose scored errors are all below `target`, and its cost.
struct TargetChoice {
  std::string method;
  std::optional<RunSummary> run;  // empty when no spacing meets the target
};
std::vector<TargetChoice> choose_for_target(const std::vector<RunSummary>& runs, double target);

}  // namespace duet
