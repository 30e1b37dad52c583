#pragma once
// Accuracy against cost over every benchmark (issue 16, `duet summary`): the compare grids of
// several scenes side by side. Per benchmark and method, the coarsest spacing whose scored errors
// are all below the target and what it cost (choose_for_target), else the best error reached;
// which method gets there cheapest and by what factor.

#include <string>
#include <vector>

#include "benchmarks/run_summary.hpp"

namespace duet {

/// One benchmark's compare grid, collected from its runs' metrics.json.
struct BenchmarkRuns {
  std::string scene;
  std::string grid_dir;
  std::vector<RunSummary> runs;
};

/// The summary table (Markdown): per benchmark a row per method, then the cheapest method that
/// meets `target`.
std::string summary_markdown(const std::vector<BenchmarkRuns>& benchmarks, double target);

/// Collects the compare grids in `grid_dirs` (InputError naming a folder that holds no compare
/// grid; grids of one scene make one benchmark, a method and spacing in two of them counted once,
/// from the later folder) and writes into `out_dir` summary.md, summary.csv (every run of every
/// grid, the columns of compare.csv) and summary.png (benchmarks/plot/summary.py: one small
/// error-against-cost chart per benchmark). Returns the Markdown.
std::string write_accuracy_summary(const std::vector<std::string>& grid_dirs, double target,
                                   const std::string& out_dir);

}  // namespace duet
