#pragma once
// compare.csv / compare.md and stability.csv: the tables users and scripts read.

#include <string>
#include <vector>

#include "benchmarks/run_summary.hpp"

namespace duet {

/// One row per run, every field of metrics.json flattened; columns are the union over the runs
/// (a run that lacks a field leaves it empty). Failed runs appear with their reason.
void write_compare_csv(const std::string& path, const std::vector<RunSummary>& runs);

/// The same as a Markdown table (a warned run's status says "(warned: N)", its warnings listed
/// under the table), plus the --target choice per method when target > 0.
void write_compare_markdown(const std::string& path, const std::vector<RunSummary>& runs,
                            double target);

/// Markdown text of the comparison (also printed by `duet compare`); `duet run`, which has said its
/// warnings on the terminal already, leaves out their list (list_warnings false).
std::string compare_markdown(const std::vector<RunSummary>& runs, double target,
                             bool list_warnings = true);

/// A varied key and the value it took in one stability run.
struct StabilityCell {
  std::vector<std::pair<std::string, std::string>> settings;  // key, value as given
  RunSummary run;
};

void write_stability_csv(const std::string& path, const std::vector<StabilityCell>& cells);

/// CSV field quoting (commas, quotes, newlines).
std::string csv_field(const std::string& text);

/// Number formatted for tables: shortest round-trip text, "" for NaN.
std::string format_number(double value);

}  // namespace duet
