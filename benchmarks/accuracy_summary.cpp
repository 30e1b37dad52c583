#include "benchmarks/accuracy_summary.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "benchmarks/plotting.hpp"
#include "benchmarks/reports.hpp"
#include "benchmarks/run_grid.hpp"
#include "common/input_error.hpp"

namespace duet {

namespace {

std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g %%", 100.0 * fraction);
  return text;
}

std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", s);
  return text;
}

std::string spacing_text(double dp) {
  char text[32];
  std::snprintf(text, sizeof text, "%g m", dp);
  return text;
}

/// A failure reason short enough for a table cell.
std::string short_reason(const std::string& reason) {
  std::string s = reason.size() > 90 ? reason.substr(0, 87) + "..." : reason;
  for (char& c : s) {
    if (c == '|' || c == '\n') c = ' ';
  }
  return s;
}

std::vector<std::string> methods_in_order(const std::vector<RunSummary>& runs) {
  std::vector<std::string> methods;
  for (const RunSummary& r : runs) {
    bool seen = false;
    for (const std::string& m : methods) seen = seen || m == r.method;
    if (!seen) methods.push_back(r.method);
  }
  return methods;
}

/// " (warned: N)" for a run that doubts its own result (metrics.json's warnings), else "".
std::string warned(const RunSummary& run) {
  return run.warnings.empty() ? "" : " (warned: " + std::to_string(run.warnings.size()) + ")";
}

/// The row of one method on one benchmark.
std::string method_row(const std::string& scene, const std::string& method,
                       const std::vector<RunSummary>& runs, const TargetChoice& choice) {
  long tried = 0, completed = 0;
  const RunSummary* best = nullptr;
  const RunSummary* first_failure = nullptr;
  bool scored = false;
  for (const RunSummary& r : runs) {
    if (r.method != method) continue;
    ++tried;
    if (!r.completed()) {
      if (!first_failure) first_failure = &r;
      continue;
    }
    ++completed;
    const double error = r.max_rel_error();
    if (std::isnan(error)) continue;
    scored = true;
    if (!best || error < best->max_rel_error()) best = &r;
  }
  std::ostringstream row;
  row << "| " << scene << " | " << method << " | " << completed << " of " << tried << " | ";
  if (choice.run) {
    row << spacing_text(choice.run->spacing) << " | " << seconds(choice.run->wall_seconds) << " | "
        << percent(choice.run->max_rel_error()) << warned(*choice.run) << " | ";
  } else {
    row << "none | | | ";
  }
  if (best) {
    row << percent(best->max_rel_error()) << " (dp " << spacing_text(best->spacing) << ", "
        << seconds(best->wall_seconds) << " s" << warned(*best) << ")";
  } else if (completed > 0 && !scored) {
    row << "no scored measure";
  } else if (first_failure) {
    row << "none completed: " << short_reason(first_failure->failure_reason);
  }
  if (first_failure && completed > 0) {
    row << "; failed at dp " << spacing_text(first_failure->spacing) << ": "
        << short_reason(first_failure->failure_reason);
  }
  row << " |\n";
  return row.str();
}

}  // namespace

std::string summary_markdown(const std::vector<BenchmarkRuns>& benchmarks, double target) {
  std::ostringstream md;
  const std::string within = "within " + percent(target);
  md << "Target: every scored error below " << percent(target)
     << ". Per benchmark and method: the coarsest spacing that meets it and its wall time, the "
        "smallest error any completed run reached, and the first failure; \"warned: N\" marks a "
        "run whose metrics.json holds N warnings about its own result.\n\n";
  md << "| benchmark | method | runs completed | coarsest spacing " << within
     << " | wall (s) | error | best error reached |\n";
  md << "|---|---|---|---|---|---|---|\n";
  for (const BenchmarkRuns& b : benchmarks) {
    const std::vector<TargetChoice> choices = choose_for_target(b.runs, target);
    for (const std::string& method : methods_in_order(b.runs)) {
      TargetChoice choice{method, std::nullopt};
      for (const TargetChoice& c : choices) {
        if (c.method == method) choice = c;
      }
      md << method_row(b.scene, method, b.runs, choice);
    }
  }

  md << "\nCheapest " << within << ":\n\n";
  md << "| benchmark | cheapest method | wall (s) | next cheapest | times cheaper |\n";
  md << "|---|---|---|---|---|\n";
  for (const BenchmarkRuns& b : benchmarks) {
    std::vector<TargetChoice> met;
    for (const TargetChoice& c : choose_for_target(b.runs, target)) {
      if (c.run) met.push_back(c);
    }
    if (met.empty()) {
      md << "| " << b.scene << " | no method meets the target | | | |\n";
      continue;
    }
    std::size_t first = 0;
    for (std::size_t k = 1; k < met.size(); ++k) {
      if (met[k].run->wall_seconds < met[first].run->wall_seconds) first = k;
    }
    const RunSummary& cheapest = *met[first].run;
    md << "| " << b.scene << " | " << cheapest.method << " (dp " << spacing_text(cheapest.spacing)
       << ") | " << seconds(cheapest.wall_seconds) << " | ";
    const RunSummary* next = nullptr;
    for (std::size_t k = 0; k < met.size(); ++k) {
      if (k != first && (!next || met[k].run->wall_seconds < next->wall_seconds)) {
        next = &*met[k].run;
      }
    }
    if (next) {
      md << next->method << ", " << seconds(next->wall_seconds) << " s | "
         << seconds(next->wall_seconds / cheapest.wall_seconds) << " |\n";
    } else {
      md << "the only one | |\n";
    }
  }
  return md.str();
}

std::string write_accuracy_summary(const std::vector<std::string>& grid_dirs, double target,
                                   const std::string& out_dir) {
  std::vector<BenchmarkRuns> benchmarks;
  std::vector<RunSummary> all;
  for (const std::string& dir : grid_dirs) {
    const Grid grid = read_grid(dir);
    if (grid.kind != "compare") {
      throw InputError(dir + ": a " + grid.kind +
                       " grid; duet summary takes the folders of duet compare");
    }
    // Grids of one scene (a coarse and a finer one) are one benchmark; a method and spacing run
    // in both counts once, as the later folder has it.
    BenchmarkRuns* b = nullptr;
    for (BenchmarkRuns& known : benchmarks) {
      if (known.scene == grid.scene_name) b = &known;
    }
    if (!b) {
      benchmarks.push_back({grid.scene_name, dir, {}});
      b = &benchmarks.back();
    }
    for (RunSummary& run : collect_runs(grid, dir)) {
      std::erase_if(b->runs, [&](const RunSummary& r) {
        return r.method == run.method && r.spacing == run.spacing;
      });
      b->runs.push_back(std::move(run));
    }
  }
  for (const BenchmarkRuns& b : benchmarks) all.insert(all.end(), b.runs.begin(), b.runs.end());
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  if (error) throw InputError(out_dir + ": cannot create the folder (" + error.message() + ")");
  const std::string md = summary_markdown(benchmarks, target);
  {
    std::ofstream file(out_dir + "/summary.md");
    if (!file) throw std::runtime_error("cannot write " + out_dir + "/summary.md");
    file << "# Accuracy against cost: every benchmark\n\n" << md;
  }
  write_compare_csv(out_dir + "/summary.csv", all);
  draw_chart("summary.py",
             {out_dir + "/summary.csv", out_dir + "/summary.png", format_number(target)});
  return md;
}

}  // namespace duet
