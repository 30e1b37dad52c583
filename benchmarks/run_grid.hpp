#pragma once
// A grid of runs (the cells of `duet stability`, the method x spacing runs of `duet compare`)
// described once, in GRID_DIR/grid.json, so that the same grid can be run three ways and give the
// same tables: in this process one cell after another, as child processes over the cores
// (--jobs N), or elsewhere from one self-contained `duet run` command per cell (--emit-jobs FILE,
// for GNU parallel or a Slurm array). `duet collect GRID_DIR` then builds the tables and the chart
// (stability.csv / .png, or compare.csv / .md / .png) from the cells' metrics.json; a cell with no
// metrics.json yet is listed as "not run".

#include <string>
#include <utility>
#include <vector>

#include "benchmarks/run_summary.hpp"

namespace duet {

struct GridCell {
  std::vector<std::pair<std::string, std::string>> settings;  // what varies: key, value as given
  std::string method;
  std::vector<std::string> overrides;  // the --set of this cell (the grid's own --set first)
  std::string dir;                     // the run's folder, relative to the grid's folder
};

struct Grid {
  std::string kind;        // "stability" | "compare"
  std::string scene_file;  // absolute
  std::string scene_name;
  std::string title;    // of the chart
  double target = 0.0;  // compare: --target
  bool force = false;   // --force: every run takes it (values in a doubtful unit run as given)
  std::vector<GridCell> cells;
};

/// GRID_DIR/grid.json.
void write_grid(const std::string& grid_dir, const Grid& grid);
/// Throws InputError naming the folder when it holds no readable grid.json.
Grid read_grid(const std::string& grid_dir);

/// The self-contained command that runs `cell`: the absolute path of this duet program, the
/// scene, the method, every --set, --out GRID_DIR/<dir> (absolute), --quiet --no-plots, and
/// --force when the grid was given it.
std::string job_command(const Grid& grid, const GridCell& cell, const std::string& grid_dir);
/// One job_command per line into `path`.
void write_job_file(const std::string& path, const Grid& grid, const std::string& grid_dir);

/// Runs every cell: in this process one after another (jobs <= 1), or as up to `jobs` child
/// processes at once, each with OMP_NUM_THREADS=1 unless the caller set it, its terminal output
/// in <cell>/run.log. Stops starting cells after an interrupt (and passes SIGTERM on to running
/// children).
void run_grid(const Grid& grid, const std::string& grid_dir, int jobs);

/// The cells' summaries from their metrics.json (status "not run" where there is none).
std::vector<RunSummary> collect_runs(const Grid& grid, const std::string& grid_dir);

/// Writes the tables and the chart of the grid's kind from collect_runs; returns the Markdown
/// table for the terminal (compare) or a one-line count (stability).
std::string write_grid_reports(const Grid& grid, const std::string& grid_dir);

}  // namespace duet
