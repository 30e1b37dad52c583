#include "benchmarks/commands.hpp"

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>
#include <utility>

#include "benchmarks/accuracy_summary.hpp"
#include "benchmarks/driver.hpp"
#include "benchmarks/element_demo.hpp"
#include "benchmarks/listing_commands.hpp"
#include "benchmarks/methods.hpp"
#include "benchmarks/plotting.hpp"
#include "benchmarks/reports.hpp"
#include "benchmarks/run_grid.hpp"
#include "benchmarks/scene_input.hpp"
#include "common/h5_writer.hpp"
#include "common/input_error.hpp"
#include "common/interrupt.hpp"
#include "common/json.hpp"
#include "common/suggest.hpp"

namespace duet {

namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  for (char c : text) {
    if (c == separator) {
      parts.push_back(part);
      part.clear();
    } else {
      part += c;
    }
  }
  parts.push_back(part);
  return parts;
}

std::vector<double> parse_spacings(const std::string& text) {
  std::vector<double> spacings;
  for (const auto& word : split(text, ',')) {
    try {
      std::size_t used = 0;
      const double v = std::stod(word, &used);
      if (used != word.size() || !(v > 0.0)) throw std::invalid_argument(word);
      spacings.push_back(v);
    } catch (const std::exception&) {
      throw InputError("--spacings " + text + ": '" + word +
                       "' is not a positive number (particle spacing, m)");
    }
  }
  return spacings;
}

std::vector<std::string> with_spacing(std::vector<std::string> overrides, double spacing) {
  overrides.push_back(spacing_override(spacing));
  return overrides;
}

struct RunArgs {
  std::string scene;
  std::string method;
  double spacing = 0.0;
  std::vector<std::string> sets;
  std::string out;
  bool quiet = false;
  bool force = false;
  bool no_plots = false;
  std::string field = "von_mises";
  std::string resume;
};

/// The scene and method a run recorded (`duet run --resume DIR`), refused with the reason when
/// DIR holds no run that can go on.
std::pair<Scene, const MethodInfo*> recorded_run(const std::string& dir) {
  const std::string h5 = dir + "/run.h5";
  if (!std::filesystem::exists(h5)) {
    throw InputError("--resume " + dir + ": no run.h5 there; expected the folder of a duet run");
  }
  const std::string metrics = dir + "/metrics.json";
  if (std::filesystem::exists(metrics)) {
    const Json m = read_json(metrics);
    const Json* status = m.find("status");
    const Json* end = m.find("end_time");
    if (status && status->is_string() && status->string() == "completed") {
      throw InputError("--resume " + dir + ": the run completed" +
                       (end && end->is_number() ? " (t = " + format_number(end->number()) + " s)"
                                                : std::string()) +
                       "; nothing to go on with");
    }
  }
  RunMetadata meta;
  try {
    meta = read_metadata(h5);
  } catch (const std::runtime_error& e) {
    throw InputError("--resume " + dir + ": " + e.what());
  }
  // The run was accepted when it started (with --force, if it needed it): not refused again.
  Scene scene =
      load_scene_checked_from_string(meta.scene_toml, h5 + ":/meta/scene_toml", {}, /*force=*/true);
  return {std::move(scene), &builtin_methods().find(meta.method)};
}

/// Draws a run's charts and lists them; a chart that cannot be drawn is reported, never fatal.
void draw_run_charts(const std::string& run_dir, const std::string& field) {
  std::string why;
  const std::vector<std::string> files = plot_run(run_dir, field, &why);
  if (files.empty() && !why.empty()) std::cerr << "duet: charts skipped: " << why << '\n';
  for (const std::string& f : files) std::cout << "chart: " << f << '\n';
}

/// 0 completed, 3 failed, 128 + signal interrupted.
int run_exit_status(const RunSummary& summary) {
  if (summary.completed()) return 0;
  if (summary.status == "interrupted") return interrupted_exit_status(pending_interrupt());
  return 3;
}

}  // namespace

void add_run_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand("run", "run one scene through one method");
  cmd->footer(
      "Scene keys: duet keys [SECTION]; soil models and their parameters: duet models [MODEL]; "
      "methods and their options: duet methods. Validate without running: duet check SCENE.");
  cmd->add_option("scene", args->scene, "scene file (TOML)");
  cmd->add_option("--method", args->method, "sph | espfem | ispfem");
  cmd->add_option("--resume", args->resume,
                  "continue the interrupted or killed run in this folder from its last frame "
                  "(no scene, method or --set: those the run recorded)");
  cmd->add_option("--spacing", args->spacing, "particle spacing dp (m), overrides the scene's");
  cmd->add_option("--set", args->sets, "override a scene key: dotted.key=value (repeatable)");
  cmd->add_option("--out", args->out, "output folder (default runs/<scene>-<method>-dp<spacing>)");
  cmd->add_flag("--quiet", args->quiet, "no progress display");
  cmd->add_flag("--force", args->force,
                "run even when the estimated memory exceeds the machine's, or a modulus or "
                "strength looks like MPa or kPa written in Pa (refused otherwise)");
  cmd->add_flag("--no-plots", args->no_plots, "do not draw the run's charts at the end");
  cmd->add_option("--field", args->field,
                  "field the particle snapshots are coloured by (default von_mises)");
  cmd->callback([args, cmd, &exit_code] {
    RunOptions options;
    options.show_progress = !args->quiet;
    std::optional<Scene> loaded;
    const MethodInfo* chosen = nullptr;
    if (!args->resume.empty()) {
      if (!args->scene.empty() || !args->method.empty() || !args->sets.empty() ||
          cmd->count("--spacing") > 0 || !args->out.empty()) {
        throw InputError(
            "--resume " + args->resume +
            ": takes no scene, --method, --spacing, --set or --out; the run goes on in its folder "
            "with the scene and method it recorded");
      }
      auto [scene, method] = recorded_run(args->resume);
      loaded.emplace(std::move(scene));
      chosen = method;
      options.out_dir = args->resume;
      options.resume = true;
    } else {
      if (args->scene.empty() || args->method.empty()) {
        throw InputError("run: expected a scene file and --method (or --resume DIR)");
      }
      std::vector<std::string> overrides = args->sets;
      if (cmd->count("--spacing") > 0) overrides.push_back(spacing_override(args->spacing));
      loaded.emplace(load_scene_checked(args->scene, overrides, args->force));
      chosen = &builtin_methods().find(args->method);
      options.out_dir = args->out.empty() ? default_run_dir(*loaded, chosen->name) : args->out;
    }
    const Scene& scene = *loaded;
    const MethodInfo& method = *chosen;
    refuse_if_too_large(scene, method, args->force);
    prepare_output_folder(options.out_dir);
    const RunSummary summary = run_scene(scene, method, options);
    std::cout << compare_markdown({summary}, 0.0, false) << "results: " << options.out_dir << '\n';
    exit_code = run_exit_status(summary);
    if (!args->no_plots && !pending_interrupt()) draw_run_charts(options.out_dir, args->field);
  });
}

void add_plot_command(CLI::App& app, int& exit_code) {
  auto dir = std::make_shared<std::string>();
  auto field = std::make_shared<std::string>("von_mises");
  CLI::App* cmd = app.add_subcommand(
      "plot",
      "draw a run's charts beside it: every measure against time, the curves its measures imply "
      "(load-settlement, pressure-expansion, run-out and height), particle snapshots");
  cmd->add_option("run_dir", *dir, "folder of a duet run (metrics.json, run.h5)")->required();
  cmd->add_option("--field", *field,
                  "field the snapshots are coloured by: von_mises (default), pressure, "
                  "equivalent_strain, density, body, material or an internal variable");
  cmd->callback([dir, field, &exit_code] {
    std::string why;
    const std::vector<std::string> files = plot_run(*dir, *field, &why);
    if (files.empty()) {
      std::cerr << "duet: plot " << *dir << ": " << (why.empty() ? "nothing to draw" : why) << '\n';
      exit_code = 1;
      return;
    }
    for (const std::string& f : files) std::cout << f << '\n';
    exit_code = 0;
  });
}

namespace {

struct CompareArgs {
  std::string scene;
  std::string methods;
  std::string spacings;
  double target = 0.0;
  std::vector<std::string> sets;
  std::string out;
  std::string emit_jobs;
  int jobs = 1;
  bool force = false;
};

}  // namespace

void add_compare_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand("compare", "run a scene through several methods and spacings");
  cmd->add_option("scene", args->scene, "scene file (TOML)")->required();
  cmd->add_option("--methods", args->methods, "comma-separated (default: every registered one)");
  cmd->add_option("--spacings", args->spacings, "comma-separated spacings (default: the scene's)");
  cmd->add_option("--target", args->target,
                  "report per method the coarsest spacing whose errors are all below this");
  cmd->add_option("--set", args->sets, "override a scene key: dotted.key=value (repeatable)");
  cmd->add_option("--out", args->out, "output folder (default runs/compare-<scene>)");
  cmd->add_option("--emit-jobs", args->emit_jobs,
                  "write one self-contained duet run command per run into this file and run "
                  "nothing (GNU parallel, a Slurm array); then duet collect OUT");
  cmd->add_option("--jobs", args->jobs,
                  "runs at once as child processes (default 1: wall times are the measured cost, "
                  "and runs side by side slow each other)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--force", args->force,
                "run even when a run's estimated memory exceeds the machine's, or a modulus or "
                "strength looks like MPa or kPa written in Pa (refused otherwise)");
  cmd->callback([args, &exit_code] {
    // Everything is checked before any run starts.
    const Scene base = load_scene_checked(args->scene, args->sets, args->force);
    const std::vector<double> spacings =
        args->spacings.empty() ? std::vector<double>{base.spacing} : parse_spacings(args->spacings);
    std::vector<std::string> method_names =
        args->methods.empty() ? builtin_methods().names() : split(args->methods, ',');
    if (method_names.empty()) builtin_methods().find("sph");  // throws: nothing registered
    std::vector<const MethodInfo*> methods;
    for (const auto& name : method_names) methods.push_back(&builtin_methods().find(name));
    std::vector<Scene> scenes;
    for (double dp : spacings)
      scenes.push_back(load_scene_checked(args->scene, with_spacing(args->sets, dp), args->force));
    if (args->target < 0.0)
      throw InputError("--target must be positive (relative error, e.g. 0.05)");
    for (const MethodInfo* method : methods) {
      for (const Scene& scene : scenes) refuse_if_too_large(scene, *method, args->force);
    }

    const std::string out = args->out.empty() ? "runs/compare-" + base.name : args->out;
    prepare_output_folder(out);
    Grid grid;
    grid.kind = "compare";
    grid.scene_file = std::filesystem::absolute(args->scene).lexically_normal().string();
    grid.scene_name = base.name;
    grid.title = base.name;
    grid.target = args->target;
    grid.force = args->force;
    for (const MethodInfo* method : methods) {
      for (const Scene& scene : scenes) {
        GridCell cell;
        cell.method = method->name;
        cell.settings = {{"method", method->name}, {"spacing", format_number(scene.spacing)}};
        cell.overrides = with_spacing(args->sets, scene.spacing);
        cell.dir = method->name + "-dp" + format_number(scene.spacing);
        grid.cells.push_back(std::move(cell));
      }
    }
    write_grid(out, grid);
    if (!args->emit_jobs.empty()) {
      write_job_file(args->emit_jobs, grid, out);
      std::cout << grid.cells.size() << " runs written to " << args->emit_jobs
                << " (one duet run per line); when they have run: duet collect " << out << '\n';
      exit_code = 0;
      return;
    }
    run_grid(grid, out, args->jobs);
    std::cout << write_grid_reports(grid, out) << "results: " << out << '\n';
    exit_code = pending_interrupt() ? interrupted_exit_status(pending_interrupt()) : 0;
  });
}

namespace {

struct StabilityArgs {
  std::string scene;
  std::string method;
  std::vector<std::string> vary;
  std::vector<std::string> sets;
  std::string out;
  std::string emit_jobs;
  int jobs = 0;  // 0: one per core
  bool force = false;
};

/// Cartesian product of the varied keys' values.
std::vector<std::vector<std::pair<std::string, std::string>>> grid_of(
    const std::vector<std::string>& vary) {
  std::vector<std::vector<std::pair<std::string, std::string>>> grid{{}};
  for (const auto& spec : vary) {
    const auto eq = spec.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == spec.size()) {
      throw InputError("--vary " + spec + ": expected key=v1,v2,... (e.g. sph.cfl=0.05,0.1,0.2)");
    }
    const std::string key = spec.substr(0, eq);
    std::vector<std::vector<std::pair<std::string, std::string>>> next;
    for (const auto& cell : grid) {
      for (const auto& value : split(spec.substr(eq + 1), ',')) {
        auto extended = cell;
        extended.emplace_back(key, value);
        next.push_back(extended);
      }
    }
    grid = next;
  }
  return grid;
}

}  // namespace

void add_stability_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<StabilityArgs>();
  CLI::App* cmd = app.add_subcommand(
      "stability", "map where a method stays stable over a grid of scene or method settings");
  cmd->add_option("scene", args->scene, "scene file (TOML)")->required();
  cmd->add_option("--method", args->method, "sph | espfem | ispfem")->required();
  cmd->add_option("--vary", args->vary, "key=v1,v2,... (repeatable; the grid is their product)")
      ->required();
  cmd->add_option("--set", args->sets, "override a scene key: dotted.key=value (repeatable)");
  cmd->add_option("--out", args->out, "output folder (default runs/stability-<scene>-<method>)");
  cmd->add_option("--emit-jobs", args->emit_jobs,
                  "write one self-contained duet run command per cell into this file and run "
                  "nothing (GNU parallel, a Slurm array); then duet collect OUT");
  cmd->add_option("--jobs", args->jobs,
                  "cells at once as child processes, one thread each (default: one per core; 1: "
                  "in this process, one after another)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--force", args->force,
                "run even when a cell's estimated memory exceeds the machine's, or a modulus or "
                "strength looks like MPa or kPa written in Pa (refused otherwise)");
  cmd->callback([args, &exit_code] {
    const MethodInfo& method = builtin_methods().find(args->method);
    const auto cells_of = grid_of(args->vary);
    std::vector<Scene> scenes;  // every cell validated before any run
    for (const auto& cell : cells_of) {
      std::vector<std::string> overrides = args->sets;
      for (const auto& [key, value] : cell) overrides.push_back(key + "=" + value);
      scenes.push_back(load_scene_checked(args->scene, overrides, args->force));
      refuse_if_too_large(scenes.back(), method, args->force);
    }
    const std::string out =
        args->out.empty() ? "runs/stability-" + scenes.front().name + "-" + method.name : args->out;
    prepare_output_folder(out);
    Grid grid;
    grid.kind = "stability";
    grid.scene_file = std::filesystem::absolute(args->scene).lexically_normal().string();
    grid.scene_name = scenes.front().name;
    grid.title = scenes.front().name + " (" + method.name + ")";
    grid.force = args->force;
    for (const auto& settings : cells_of) {
      GridCell cell;
      cell.method = method.name;
      cell.settings = settings;
      cell.overrides = args->sets;
      for (const auto& [key, value] : settings) {
        cell.overrides.push_back(key + "=" + value);
        cell.dir += (cell.dir.empty() ? "" : "_") + key + "=" + value;
      }
      grid.cells.push_back(std::move(cell));
    }
    write_grid(out, grid);
    if (!args->emit_jobs.empty()) {
      write_job_file(args->emit_jobs, grid, out);
      std::cout << grid.cells.size() << " cells written to " << args->emit_jobs
                << " (one duet run per line); when they have run: duet collect " << out << '\n';
      exit_code = 0;
      return;
    }
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    run_grid(grid, out, args->jobs > 0 ? args->jobs : cores);
    std::cout << write_grid_reports(grid, out) << "results: " << out << '\n';
    exit_code = pending_interrupt() ? interrupted_exit_status(pending_interrupt()) : 0;
  });
}

void add_collect_command(CLI::App& app, int& exit_code) {
  auto dirs = std::make_shared<std::vector<std::string>>();
  CLI::App* cmd = app.add_subcommand(
      "collect",
      "build stability.csv/png or compare.csv/md/png of a grid from its runs' metrics.json (a grid "
      "run elsewhere from --emit-jobs, or one still running)");
  cmd->add_option("grid_dir", *dirs, "the --out folder(s) of duet stability or compare")
      ->required();
  cmd->callback([dirs, &exit_code] {
    for (const std::string& dir : *dirs) {
      const Grid grid = read_grid(dir);
      std::cout << write_grid_reports(grid, dir) << "results: " << dir << '\n';
    }
    exit_code = 0;
  });
}

void add_summary_command(CLI::App& app, int& exit_code) {
  auto dirs = std::make_shared<std::vector<std::string>>();
  auto target = std::make_shared<double>(0.05);
  auto out = std::make_shared<std::string>("runs/summary");
  CLI::App* cmd = app.add_subcommand(
      "summary",
      "accuracy against cost over several benchmarks: from the folders of duet compare, one "
      "error-against-wall-time chart per benchmark (summary.png) and a table of the coarsest "
      "spacing meeting the target per method and the cheapest method (summary.md, summary.csv)");
  cmd->add_option("grid_dir", *dirs, "the --out folders of duet compare, one per benchmark")
      ->required();
  cmd->add_option("--target", *target, "scored error to meet (default 0.05)")
      ->check(CLI::Range(1e-9, 1e9));
  cmd->add_option("--out", *out, "output folder (default runs/summary)");
  cmd->callback([dirs, target, out, &exit_code] {
    std::cout << write_accuracy_summary(*dirs, *target, *out) << "results: " << *out << '\n';
    exit_code = 0;
  });
}

void add_demo_command(CLI::App& app, int& exit_code) {
  auto out = std::make_shared<std::string>("runs/demo");
  CLI::App* cmd = app.add_subcommand(
      "demo",
      "the default demonstration: the coarse collapse comparison once a solver is "
      "registered, else the element tests of every soil model");
  auto elements = std::make_shared<bool>(false);
  cmd->add_option("--out", *out, "output folder (default runs/demo)");
  cmd->add_flag("--elements", *elements, "run the element tests of every soil model instead");
  cmd->callback([out, elements, &exit_code] {
    if (*elements) {
      exit_code = run_element_demo(*out);
      return;
    }
    if (builtin_methods().empty()) {
      std::cout << "No solver is registered in this build yet: running the element tests of "
                   "every soil model.\n";
      exit_code = run_element_demo(*out);
      return;
    }
    // The coarse collapse comparison (Peng 2015 5.2): every registered method at two smoke
    // spacings, so each method draws a line on the error-against-cost chart.
    const std::string scene_path =
        std::string(DUET_SOURCE_DIR) + "/benchmarks/scenes/collapse.toml";
    std::vector<RunSummary> runs;
    for (const auto& name : builtin_methods().names()) {
      // The collapse is dynamic: a quasi-static method (ispfem) has nothing to say about it
      if (!builtin_methods().find(name).dynamic) continue;
      for (const char* spacing : {"0.01", "0.0075"}) {
        if (pending_interrupt()) break;
        const Scene scene = load_scene_checked(scene_path, {std::string("spacing=") + spacing});
        RunOptions options;
        options.out_dir = *out + "/" + name + "-dp" + spacing;
        std::cerr << "duet demo: collapse through " << name << " at spacing " << spacing << " m\n";
        runs.push_back(run_scene(scene, builtin_methods().find(name), options));
        // The collapse itself: run-out and height against time, the deposit at three moments
        // coloured by the accumulated shear strain.
        if (!pending_interrupt()) draw_run_charts(options.out_dir, "equivalent_strain");
      }
    }
    write_compare_csv(*out + "/compare.csv", runs);
    write_compare_markdown(*out + "/compare.md", runs, 0.0);
    draw_chart("compare.py", {*out + "/compare.csv", *out + "/compare.png", "collapse (demo)"});
    std::vector<std::string> snapshots = {*out + "/snapshots_equivalent_strain.png",
                                          "equivalent_strain"};
    for (const RunSummary& r : runs) snapshots.push_back(r.out_dir);
    if (!runs.empty()) draw_chart("snapshots.py", snapshots);
    std::cout << compare_markdown(runs, 0.0) << "results: " << *out << '\n';
    exit_code = pending_interrupt() ? interrupted_exit_status(pending_interrupt()) : 0;
  });
}

}  // namespace duet
