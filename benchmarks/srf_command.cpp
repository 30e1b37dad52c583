#include "benchmarks/srf_command.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

#include "benchmarks/driver.hpp"
#include "benchmarks/methods.hpp"
#include "benchmarks/plotting.hpp"
#include "benchmarks/reports.hpp"
#include "benchmarks/scene_input.hpp"
#include "benchmarks/strength_reduction_search.hpp"
#include "common/h5_writer.hpp"
#include "common/input_error.hpp"
#include "common/interrupt.hpp"
#include "common/json.hpp"
#include "common/strength_reduction.hpp"

namespace duet {

namespace {

struct SrfArgs {
  std::string scene;
  std::string method;
  double spacing = 0.0;
  std::vector<std::string> sets;
  std::string out;
  bool force = false;
  SrfSearchOptions search;
  SettleCriterion settle;
  double floor_spacings = 0.01;
};

/// The scene's series of the largest displacement: the measure the verdict reads.
std::string displacement_measure(const Scene& scene) {
  for (const Measure& m : scene.measures) {
    if (m.kind == MeasureKind::max_displacement && m.at == MeasureAt::series) return m.name;
  }
  throw InputError(scene.path +
                   ": duet srf judges each trial by the largest displacement over time; expected "
                   "a [measure.<name>] with kind = \"max_displacement\" and at = \"series\"");
}

std::string factor_text(double f) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", f);
  return text;
}

void write_reports(const std::string& out, const SrfArgs& args, const Scene& scene,
                   const std::string& measure, const SrfResult& result, double wall) {
  {
    std::ofstream csv(out + "/srf.csv");
    csv << "factor,verdict,reason,final_max_displacement,window_increase,wall_seconds,dir\n";
    for (const SrfTrial& t : result.trials) {
      csv << factor_text(t.factor) << ',' << (t.stable ? "stable" : "failed") << ','
          << csv_field(t.reason) << ',' << format_number(t.final_displacement) << ','
          << format_number(t.window_increase) << ',' << format_number(t.wall_seconds) << ','
          << csv_field(t.dir) << '\n';
    }
  }
  Json j = Json::object();
  j["scene"] = scene.name;
  j["method"] = args.method;
  j["spacing"] = scene.spacing;
  j["rule"] = scene.strength_reduction.rule;
  // After gravity loading at full strength (Peng's order) or from the start; over `ramp` s
  j["stage"] = scene.initial_stress.kind == InitialStressKind::gravity_loading
                   ? scene.strength_reduction.stage
                   : std::string("no gravity loading");
  j["ramp"] = scene.strength_reduction.ramp;
  j["outcome"] = result.outcome;
  j["last_stable"] = result.last_stable;
  j["first_failed"] = result.first_failed;
  j["width"] = args.search.width;
  j["trials"] = static_cast<long>(result.trials.size());
  j["wall_seconds"] = wall;
  j["measure"] = measure;
  Json criterion = Json::object();
  criterion["window"] = args.settle.window;
  criterion["fraction"] = args.settle.fraction;
  criterion["floor"] = args.settle.floor;
  j["settle_criterion"] = criterion;
  write_json(out + "/srf.json", j);

  std::ofstream md(out + "/srf.md");
  md << "# " << scene.name << ": strength reduction through " << args.method << " at dp "
     << format_number(scene.spacing) << " m\n\n";
  md << "Factor of safety: between " << factor_text(result.last_stable) << " (last stable) and "
     << factor_text(result.first_failed) << " (first failed); " << result.outcome << ", "
     << result.trials.size() << " trials, " << format_number(std::round(wall)) << " s.\n\n";
  if (scene.initial_stress.kind == InitialStressKind::gravity_loading) {
    md << (scene.strength_reduction.stage == "after-loading"
               ? "Gravity loading at full strength, then the strength reduced over the first " +
                     format_number(scene.strength_reduction.ramp) + " s (Peng 2015 5.3).\n\n"
               : std::string("Gravity loading at the reduced strength.\n\n"));
  }
  md << "| factor | verdict | reason | wall (s) |\n|---|---|---|---|\n";
  for (const SrfTrial& t : result.trials) {
    md << "| " << factor_text(t.factor) << " | " << (t.stable ? "stable" : "failed") << " | "
       << t.reason << " | " << format_number(std::round(t.wall_seconds * 10) / 10) << " |\n";
  }
}

}  // namespace

void add_srf_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SrfArgs>();
  CLI::App* cmd = app.add_subcommand(
      "srf",
      "factor of safety by strength reduction: runs at c/f and tan(phi)/f (or phi/f), bracketing "
      "then bisecting f between the last stable and the first failed trial");
  cmd->add_option("scene", args->scene, "scene file (TOML) with a max_displacement series")
      ->required();
  cmd->add_option("--method", args->method, "sph | espfem | ispfem")->required();
  cmd->add_option("--spacing", args->spacing, "particle spacing dp (m), overrides the scene's");
  cmd->add_option("--set", args->sets, "override a scene key: dotted.key=value (repeatable)");
  cmd->add_option("--out", args->out, "output folder (default runs/srf-<scene>-<method>)");
  cmd->add_option("--start", args->search.start, "first factor tried (default 1)");
  cmd->add_option("--step", args->search.step, "first bracketing step (default 0.2)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--width", args->search.width, "bisect to this bracket width (default 0.01)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--settle-window", args->settle.window,
                  "stable: the largest displacement grows little over this last fraction of the "
                  "run (default 0.25)")
      ->check(CLI::Range(0.01, 1.0));
  cmd->add_option("--settle-fraction", args->settle.fraction,
                  "... by at most this fraction of its final value (default 0.05)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--settle-floor", args->floor_spacings,
                  "... or by at most this many spacings (growth below it is noise; default 0.01)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--force", args->force,
                "run even when the estimated memory exceeds the machine's, or a modulus or "
                "strength looks like MPa or kPa written in Pa (refused otherwise)");
  cmd->callback([args, cmd, &exit_code] {
    std::vector<std::string> base = args->sets;
    if (cmd->count("--spacing") > 0) base.push_back(spacing_override(args->spacing));
    const Scene scene = load_scene_checked(args->scene, base, args->force);
    const MethodInfo& method = builtin_methods().find(args->method);
    refuse_if_too_large(scene, method, args->force);
    const std::string measure = displacement_measure(scene);
    SettleCriterion settle = args->settle;
    settle.floor = args->floor_spacings * scene.spacing;
    args->settle = settle;
    const std::string out =
        args->out.empty() ? "runs/srf-" + scene.name + "-" + method.name : args->out;
    prepare_output_folder(out);

    const auto start = std::chrono::steady_clock::now();
    const auto run_trial = [&](double f) {
      std::vector<std::string> overrides = base;
      overrides.push_back("strength_reduction.factor=" + factor_text(f));
      // The scene at full strength was checked above: a cohesion reduced below 1 Pa is meant.
      const Scene trial_scene = load_scene_checked(args->scene, overrides, /*force=*/true);
      RunOptions options;
      options.out_dir = out + "/f=" + factor_text(f);
      options.show_progress = false;
      std::cerr << "duet srf: factor " << factor_text(f) << " ... ";
      const RunSummary run = run_scene(trial_scene, method, options);
      SrfTrial t;
      if (run.completed()) {
        const std::string h5 = options.out_dir + "/run.h5";
        t = settle_verdict(read_series(h5, "time"), read_series(h5, measure), settle);
      } else {
        char text[96];
        if (strength_changes_in_run(trial_scene)) {
          std::snprintf(text, sizeof text,
                        "run %s at t = %.4g s (strength factor %.4g): ", run.status.c_str(),
                        run.failure_time, strength_factor_at(trial_scene, run.failure_time));
        } else {
          std::snprintf(text, sizeof text, "run %s at t = %.4g s: ", run.status.c_str(),
                        run.failure_time);
        }
        t.stable = false;
        t.reason = text + run.failure_reason;
      }
      t.wall_seconds = run.wall_seconds;
      t.dir = options.out_dir;
      std::cerr << (t.stable ? "stable" : "failed") << " (" << t.reason << ")\n";
      return t;
    };
    const SrfResult result =
        srf_search(run_trial, args->search, [] { return pending_interrupt() != 0; });
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    write_reports(out, *args, scene, measure, result, wall);
    draw_chart("srf.py",
               {out + "/srf.csv", out + "/srf.png", measure,
                scene.name + " (" + method.name + ", dp " + format_number(scene.spacing) + " m)"});
    std::cout << "factor of safety of " << scene.name << " through " << method.name << ": between "
              << factor_text(result.last_stable) << " (stable) and "
              << factor_text(result.first_failed) << " (failed): " << result.outcome << ", "
              << result.trials.size() << " trials, " << format_number(std::round(wall))
              << " s\nresults: " << out << '\n';
    exit_code = pending_interrupt() ? interrupted_exit_status(pending_interrupt()) : 0;
  });
}

}  // namespace duet
