#include "benchmarks/driver.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "benchmarks/git_commit.hpp"
#include "benchmarks/material_points.hpp"
#include "benchmarks/reports.hpp"
#include "benchmarks/run_warnings.hpp"
#include "benchmarks/thread_choice.hpp"
#include "common/energy_budget.hpp"
#include "common/h5_writer.hpp"
#include "common/input_error.hpp"
#include "common/interrupt.hpp"
#include "common/kinetic_energy.hpp"
#include "common/lattice.hpp"
#include "common/measures.hpp"
#include "common/progress.hpp"
#include "common/reaction_mean.hpp"
#include "common/run_checks.hpp"
#include "common/state_bag.hpp"
#include "common/strength_reduction.hpp"

namespace duet {

std::string default_run_dir(const Scene& scene, const std::string& method) {
  return "runs/" + scene.name + "-" + method + "-dp" + format_number(scene.spacing);
}

void prepare_output_folder(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::exists(dir, error) && !fs::is_directory(dir, error)) {
    throw InputError("--out " + dir + ": exists and is not a folder; expected an output folder");
  }
  fs::create_directories(dir, error);
  if (error) {
    throw InputError("--out " + dir + ": cannot create the output folder (" + error.message() +
                     "); expected a folder that can be created and written");
  }
  const fs::path probe = fs::path(dir) / ".duet-write-probe";
  {
    std::ofstream out(probe);
    out << "probe\n";
    out.flush();
    if (!out) {
      throw InputError("--out " + dir + ": cannot write into the output folder (" +
                       std::strerror(errno) + "); expected a writable folder");
    }
  }
  fs::remove(probe, error);
}

RunEstimate estimate_run(const Scene& scene, const MethodInfo& method) {
  RunEstimate e;
  e.particles = estimated_particles(scene);
  constexpr double base = 200.0e6;  // the program, libraries and output buffers
  e.bytes = base + e.particles * method.bytes_per_particle;
  e.machine_bytes =
      static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  return e;
}

void refuse_if_too_large(const Scene& scene, const MethodInfo& method, bool force) {
  const RunEstimate e = estimate_run(scene, method);
  if (force || e.bytes <= 0.9 * e.machine_bytes) return;
  char text[400];
  std::snprintf(text, sizeof text,
                "%s at spacing %g m: about %.3g particles, %.3g GB through %s, more than this "
                "machine's %.3g GB; expected a coarser spacing (or --force to try anyway)",
                scene.path.c_str(), scene.spacing, e.particles, e.bytes / 1e9, method.name.c_str(),
                e.machine_bytes / 1e9);
  throw InputError(text);
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

/// The frame a resumed run goes on from: the last one holding the state.
struct ResumePoint {
  std::size_t frame = 0;
  double time = 0.0;
  StateBag state;
};

ResumePoint find_resume_point(const std::string& out_dir) {
  const std::string h5 = out_dir + "/run.h5";
  for (std::size_t k = count_frames(h5); k-- > 0;) {
    ResumePoint point{k, 0.0, read_state(h5, k)};
    if (point.state.empty()) continue;
    point.time = scalar(point.state, "driver.time");
    return point;
  }
  throw InputError("--resume " + out_dir + ": no frame holds the state a run needs to go on");
}

}  // namespace

RunSummary run_scene(const Scene& scene, const MethodInfo& method, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  prepare_output_folder(options.out_dir);

  Particles particles = sample_bodies(scene);
  initialise_material_points(scene, particles);
  std::unique_ptr<Solver> solver = method.make(scene);
  // Every frame carries the state where the solver can give it all (`duet run --resume`).
  const bool keeps_state = solver->resume_refusal().empty();
  std::optional<ResumePoint> resume;
  if (options.resume) {
    if (!keeps_state) {
      throw InputError("--resume " + options.out_dir + ": " + method.name + ": " +
                       solver->resume_refusal());
    }
    resume = find_resume_point(options.out_dir);
  }
  std::optional<Failure> failure;
  try {
    // Gravity loading happens here (ispfem's increments, espfem's damped steps): it can fail.
    solver->initialise(scene, particles);
  } catch (const NumericalFailure& e) {
    failure = Failure{std::string("before the clock started: ") + e.what(), 0.0, e.particle()};
  }

  std::optional<RunWriter> writer_storage;
  if (resume) {
    writer_storage.emplace(options.out_dir, RunWriter::ContinueAfter{resume->frame});
  } else {
    writer_storage.emplace(options.out_dir);
  }
  RunWriter& writer = *writer_storage;
  std::vector<std::string> boundary_names;
  for (const Wall& w : scene.walls) boundary_names.push_back(w.name);
  for (const RigidBody& r : scene.rigid_bodies) boundary_names.push_back(r.name);
  writer.write_metadata(scene.name, method.name, scene.resolved_toml, source_commit(),
                        scene.spacing, boundary_names);
  // The walls and rigid bodies where they are at `t`, and the solver's mesh.
  const auto shown = [&](double t) {
    return FrameGeometry{boundary_lines_at(scene, t), solver->mesh_triangles(particles)};
  };
  MeasureRecorder measures(scene);
  Timers output_timers;

  const double end_time = scene.time.end_time;
  const double output_interval = scene.time.output_interval;
  const double sample_interval = output_interval / 10.0;
  double time = 0.0;
  long steps = 0;
  int interrupted_by = 0;  // the signal that ended the run, or 0
  bool output_failed = false;
  double next_output = output_interval;
  double next_sample = sample_interval;
  double wall_before = 0.0;  // a resumed run: the wall time of the run up to its frame
  std::vector<Vec2> previous_position = particles.position;

  // After initialise: a solver that settles the soil under gravity first (gravity-loading) starts
  // the clock from that state (a resumed run has just repeated it: the same state as frame 0).
  const StateChecks checks(scene, particles);
  EnergyBudget budget(scene, particles, stored_elastic_energy(scene, particles));
  KineticEnergyRecord energy;
  // An inertial run's measures sample the reactions' mean since the last sample
  // (common/reaction_mean.hpp); a quasi-static run's, the equilibrium reactions at that time.
  const bool inertial = solver->inertial();
  ReactionMean reaction_mean;
  const auto sampled_reactions = [&] {
    return inertial ? reaction_mean.take(solver->reactions()) : solver->reactions();
  };
  // The load on each driven boundary at every sample, for the load-drop warning (run_warnings).
  std::vector<BoundaryLoad> boundary_loads = driven_boundaries(scene);
  const auto sample = [&](const std::vector<Reaction>& reactions) {
    measures.sample(time, particles, reactions);
    record_boundary_loads(scene, time, reactions, boundary_loads);
  };

  // The largest |F| each wall and rigid body carried since the run began: a moving one that
  // carried none never touched the material (run_warnings).
  std::vector<double> largest_reaction;
  const auto note_reactions = [&](const std::vector<Reaction>& reactions) {
    largest_reaction.resize(reactions.size(), 0.0);
    for (std::size_t k = 0; k < reactions.size(); ++k) {
      largest_reaction[k] = std::max(largest_reaction[k], reactions[k].force.norm());
    }
  };

  // All the run carries from one step to the next, for a frame's /state.
  const auto state_now = [&] {
    StateBag state;
    put(state, "driver.time", time);
    put(state, "driver.steps", static_cast<double>(steps));
    put(state, "driver.next_output", next_output);
    put(state, "driver.next_sample", next_sample);
    put(state, "driver.kinetic_energy",
        std::vector<double>{energy.peak, energy.peak_time, energy.end});
    put(state, "driver.wall_seconds",
        wall_before +
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    put(state, "driver.internal", particles.internal.values);
    measures.save_state(state);
    reaction_mean.save_state(state);
    put(state, "driver.reaction_largest", largest_reaction);
    for (const BoundaryLoad& b : boundary_loads) {
      put(state, "driver.load_time." + b.name, b.time);
      put(state, "driver.load." + b.name, b.load);
    }
    budget.save_state(state);
    solver->save_state(state);
    return state;
  };
  // A frame (and the series with it): a full disk or a quota ends the run, the frames written
  // before stay readable. A failure found before the write stays the run's reason. The first
  // frame and the frames at the output times hold the state (where the solver keeps one) and are
  // restart points: a resumed run starts from one of them, the last state-holding frame (the
  // frame written when a run stops is not one).
  const auto write_output = [&](bool with_series, bool restart_point) {
    ScopedTimer t(output_timers, Phase::output);
    try {
      if (with_series) writer.set_series(measures.names(), measures.columns());
      const bool with_state = keeps_state && restart_point;
      const std::optional<StateBag> state =
          with_state ? std::optional<StateBag>(state_now()) : std::nullopt;
      writer.write_frame(time, particles, shown(time), state ? &*state : nullptr);
      if (with_state) solver->restart_point();
    } catch (const std::exception& e) {
      output_failed = true;
      if (!failure) failure = Failure{std::string("writing the output failed: ") + e.what(), time};
    }
  };

  if (resume) {
    // The particles, the driver's counters and the solver as the frame holds them.
    const StateBag& state = resume->state;
    try {
      read_particle_state(writer.h5_path(), resume->frame, particles);
      std::vector<double> internal;
      get(state, "driver.internal", internal);
      if (internal.size() != particles.internal.values.size()) {
        throw std::runtime_error("its internal variables are not this scene's");
      }
      particles.internal.values = std::move(internal);
      time = scalar(state, "driver.time");
      steps = static_cast<long>(scalar(state, "driver.steps"));
      next_output = scalar(state, "driver.next_output");
      next_sample = scalar(state, "driver.next_sample");
      const std::vector<double>& k = entry(state, "driver.kinetic_energy");
      if (k.size() != 3) throw std::runtime_error("its kinetic energy record has another size");
      energy.peak = k[0];
      energy.peak_time = k[1];
      energy.end = k[2];
      wall_before = scalar(state, "driver.wall_seconds");
      measures.restore_state(state);
      reaction_mean.restore_state(state);
      // absent from frames written before it was kept: the record starts afresh
      if (state.count("driver.reaction_largest") != 0) {
        get(state, "driver.reaction_largest", largest_reaction);
      }
      for (BoundaryLoad& b : boundary_loads) {
        if (state.count("driver.load." + b.name) == 0) continue;  // as above
        get(state, "driver.load_time." + b.name, b.time);
        get(state, "driver.load." + b.name, b.load);
      }
      budget.restore_state(state);
      solver->restore_state(state, particles);
      solver->restart_point();
    } catch (const std::runtime_error& e) {
      throw InputError("--resume " + options.out_dir + ": frame " + std::to_string(resume->frame) +
                       ": " + e.what());
    }
    previous_position = particles.position;
  } else {
    write_output(false, true);
    sample(solver->reactions());
    energy.record(time, kinetic_energy(particles));
  }
  std::optional<Progress> progress;
  if (options.show_progress) progress.emplace(end_time, std::cerr, isatty(2) != 0);
  while (time < end_time * (1.0 - 1e-12) && !failure) {
    previous_position = particles.position;
    const double previous_time = time;
    try {
      const double dt = solver->step(scene, particles, time);
      time += dt;
      ++steps;
      energy.record(time, kinetic_energy(particles));
      const std::vector<Reaction> reactions = solver->reactions();
      note_reactions(reactions);
      if (inertial) reaction_mean.add(reactions, dt);
      budget.record(time, particles, reactions);
      budget.observe(energy.end);
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
    if (auto problem = checks.check_lift_off(particles)) {
      failure = Failure{problem->reason, time, problem->particle, problem->position};
      break;
    }
    // A quasi-static run's velocities are increments over a load step, not inertia.
    if (inertial) {
      if (auto reason = energy_runaway(scene.checks, energy.end, budget)) {
        failure = Failure{*reason, time};
        break;
      }
    }
    if (time >= next_sample) {
      sample(sampled_reactions());
      next_sample += sample_interval;
    }
    if (time >= next_output) {
      next_output += output_interval;  // before the write: the frame's state holds the next one
      write_output(true, true);
      if (output_failed) break;
    }
    if (progress) progress->update(time, steps);
    if ((interrupted_by = pending_interrupt()) != 0) break;
  }
  // The last state (or the state at failure) is always a frame, unless writing is what failed.
  if (!failure) sample(sampled_reactions());
  if (!output_failed) write_output(true, false);
  const std::string status = failure ? "failed" : interrupted_by ? "interrupted" : "completed";
  if (interrupted_by) {
    failure = Failure{"interrupted by signal " + std::to_string(interrupted_by), time};
  }
  if (progress) progress->finish(status == "completed" ? status : status + ": " + failure->reason);

  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  Json metrics = Json::object();
  metrics["scene"] = scene.name;
  metrics["method"] = method.name;
  metrics["spacing"] = scene.spacing;
  metrics["particles"] = static_cast<long>(particles.size());
  metrics["steps"] = steps;
  metrics["wall_seconds"] = wall_before + wall;  // a resumed run: both parts
  metrics["status"] = status;
  metrics["failure"] = failure ? failure_json(*failure) : Json();
  metrics["end_time"] = time;
  // Peng's order: the strength falls during the run; the factor it had reached at the end
  if (scene.strength_reduction.factor != 1.0) {
    metrics["strength_factor_at_end"] = strength_factor_at(scene, time);
  }
  if (interrupted_by) metrics["signal"] = static_cast<long>(interrupted_by);
  // Whether `duet run --resume` can continue this run from its frames, and if not why.
  metrics["resumable"] = keeps_state;
  if (!keeps_state) metrics["resume_refusal"] = solver->resume_refusal();
  if (resume) {
    // timing and the output timer cover this process only
    Json resumed = Json::object();
    resumed["from_frame"] = static_cast<long>(resume->frame);
    resumed["from_time"] = resume->time;
    resumed["wall_seconds_before"] = wall_before;
    resumed["wall_seconds_after"] = wall;
    metrics["resumed"] = resumed;
  }
  metrics["measures"] = measures.final_values();
  metrics["accuracy"] = measures.accuracy();
  Json timing = solver->timers().to_json();
  timing["output"] = output_timers.seconds(Phase::output);
  metrics["timing"] = timing;
  metrics["diagnostics"] = solver->diagnostics();
  energy.end_carriers = kinetic_energy_carriers(particles);
  metrics["kinetic_energy"] = energy.to_json();
  metrics["energy_input"] = budget.to_json();
  std::map<std::string, double> largest_by_name;
  {
    const std::vector<Reaction> names = solver->reactions();
    for (std::size_t k = 0; k < names.size() && k < largest_reaction.size(); ++k) {
      largest_by_name[names[k].name] = largest_reaction[k];
    }
  }
  const std::vector<std::string> warnings =
      status == "completed"
          ? run_warnings(scene, solver->inertial(), energy, budget, time, metrics["diagnostics"],
                         particles.size(), largest_by_name, boundary_loads)
          : std::vector<std::string>{};
  Json warning_list = Json::array();
  for (const std::string& w : warnings) {
    warning_list.push_back(w);
    std::cerr << "duet: warning: " << w << '\n';
  }
  metrics["warnings"] = warning_list;
  metrics["commit"] = source_commit();
  metrics["threads"] = thread_choice();
  metrics["scene_file"] = scene.path;
  write_json(options.out_dir + "/metrics.json", metrics);
  return summary_from_metrics(metrics, options.out_dir);
}

}  // namespace duet
