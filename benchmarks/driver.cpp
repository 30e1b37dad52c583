#include "benchmarks/driver.hpp"

#include <unistd.h>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>

#include "benchmarks/git_commit.hpp"
#include "benchmarks/material_points.hpp"
#include "benchmarks/reports.hpp"
#include "common/h5_writer.hpp"
#include "common/kinetic_energy.hpp"
#include "common/lattice.hpp"
#include "common/measures.hpp"
#include "common/progress.hpp"
#include "common/run_checks.hpp"

namespace duet {

std::string default_run_dir(const Scene& scene, const std::string& method) {
  return "runs/" + scene.name + "-" + method + "-dp" + format_number(scene.spacing);
}

namespace {

struct Failure {
  std::string reason;
  double time = 0.0;
  long particle = -1;
  Vec2 position = Vec2::Constant(std::nan(""));
};

Json failure_json(const Failure& f) {
  Json j = Json::object();
  j["reason"] = f.reason;
  j["time"] = f.time;
  j["particle"] = f.particle;
  if (f.particle >= 0)
    j["position"] = Json::array(std::vector<double>{f.position.x(), f.position.y()});
  return j;
}

}  // namespace

RunSummary run_scene(const Scene& scene, const MethodInfo& method, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::filesystem::create_directories(options.out_dir);

  Particles particles = sample_bodies(scene);
  initialise_material_points(scene, particles);
  std::unique_ptr<Solver> solver = method.make(scene);
  solver->initialise(scene, particles);

  RunWriter writer(options.out_dir);
  writer.write_metadata(scene.name, method.name, scene.resolved_toml, source_commit(),
                        scene.spacing);
  MeasureRecorder measures(scene);
  Timers output_timers;

  const double end_time = scene.time.end_time;
  const double output_interval = scene.time.output_interval;
  const double sample_interval = output_interval / 10.0;
  double time = 0.0;
  long steps = 0;
  std::optional<Failure> failure;
  std::vector<Vec2> previous_position = particles.position;

  {
    ScopedTimer t(output_timers, Phase::output);
    writer.write_frame(time, particles);
  }
  measures.sample(time, particles, solver->reactions());
  std::optional<Progress> progress;
  if (options.show_progress) progress.emplace(end_time, std::cerr, isatty(2) != 0);
  double next_output = output_interval;
  double next_sample = sample_interval;

  const StateChecks checks(scene);
  KineticEnergyRecord energy;
  energy.record(time, kinetic_energy(particles));
  while (time < end_time * (1.0 - 1e-12) && !failure) {
    previous_position = particles.position;
    const double previous_time = time;
    try {
      const double dt = solver->step(scene, particles, time);
      time += dt;
      ++steps;
      energy.record(time, kinetic_energy(particles));
    } catch (const NumericalFailure& e) {
      failure = Failure{e.what(), time, e.particle()};
      if (e.particle() >= 0 && static_cast<std::size_t>(e.particle()) < particles.size()) {
        failure->position = particles.position[static_cast<std::size_t>(e.particle())];
      }
      break;
    }
    if (auto problem = checks.check(particles, previous_position, previous_time, time)) {
      failure = Failure{problem->reason, time, problem->particle, problem->position};
      break;
    }
    if (time >= next_sample) {
      measures.sample(time, particles, solver->reactions());
      next_sample += sample_interval;
    }
    if (time >= next_output) {
      ScopedTimer t(output_timers, Phase::output);
      writer.write_frame(time, particles);
      writer.write_series(measures.names(), measures.columns());
      next_output += output_interval;
    }
    if (progress) progress->update(time, steps);
  }
  // The last state (or the state at failure) is always a frame.
  {
    ScopedTimer t(output_timers, Phase::output);
    writer.write_frame(time, particles);
  }
  if (!failure) measures.sample(time, particles, solver->reactions());
  writer.write_series(measures.names(), measures.columns());
  if (progress) progress->finish(failure ? "failed: " + failure->reason : "completed");

  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  Json metrics = Json::object();
  metrics["scene"] = scene.name;
  metrics["method"] = method.name;
  metrics["spacing"] = scene.spacing;
  metrics["particles"] = static_cast<long>(particles.size());
  metrics["steps"] = steps;
  metrics["wall_seconds"] = wall;
  metrics["status"] = failure ? "failed" : "completed";
  metrics["failure"] = failure ? failure_json(*failure) : Json();
  metrics["end_time"] = time;
  metrics["measures"] = measures.final_values();
  metrics["accuracy"] = measures.accuracy();
  Json timing = solver->timers().to_json();
  timing["output"] = output_timers.seconds(Phase::output);
  metrics["timing"] = timing;
  metrics["diagnostics"] = solver->diagnostics();
  metrics["kinetic_energy"] = energy.to_json();
  metrics["commit"] = source_commit();
  metrics["scene_file"] = scene.path;
  write_json(options.out_dir + "/metrics.json", metrics);
  return summary_from_metrics(metrics, options.out_dir);
}

}  // namespace duet
