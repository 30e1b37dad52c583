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
#include "common/enum_names.hpp"
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
#include "common/units.hpp"

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

/// The particles sampled from the scene's bodies, their material points in their initial state.
Particles sampled_material_points(const Scene& scene) {
  Particles particles = sample_bodies(scene);
  initialise_material_points(scene, particles);
  return particles;
}

/// `--resume`: the frame to go on from, or nothing for a fresh run. Refused before any work when
/// the solver cannot write all it carries into the frames.
std::optional<ResumePoint> resume_point(const RunOptions& options, const MethodInfo& method,
                                        const Solver& solver) {
  if (!options.resume) return std::nullopt;
  if (!solver.resume_refusal().empty()) {
    throw InputError("--resume " + options.out_dir + ": " + method.name + ": " +
                     solver.resume_refusal());
  }
  return find_resume_point(options.out_dir);
}

/// Gravity loading happens here (ispfem's increments, espfem's damped steps): it can fail, and
/// the run then stops before its first step with that reason.
std::optional<Failure> initialise_solver(const Scene& scene, Solver& solver, Particles& particles) {
  try {
    solver.initialise(scene, particles);
  } catch (const NumericalFailure& e) {
    return Failure{std::string("before the clock started: ") + e.what(), 0.0, e.particle()};
  }
  return std::nullopt;
}

/// A fresh run's files, or a resumed run's kept up to its frame.
RunWriter open_writer(const std::string& out_dir, const std::optional<ResumePoint>& resume) {
  if (resume) return RunWriter(out_dir, RunWriter::ContinueAfter{resume->frame});
  return RunWriter(out_dir);
}

std::vector<std::string> boundary_names(const Scene& scene) {
  std::vector<std::string> names;
  for (const Wall& w : scene.walls) names.push_back(w.name);
  for (const RigidBody& r : scene.rigid_bodies) names.push_back(r.name);
  return names;
}

/// One run of a scene through a method: what it carries from one step to the next, and its
/// stages in the order run_scene calls them. The members are declared in the order the run is set
/// up in, each built from those above it: the material points, the solver, the frame to resume
/// from (refused before any work), the solver's initialisation, the output files, then what
/// watches the steps, built from the initialised particles (a solver that settles the soil under
/// gravity first starts the clock from that state; a resumed run has just repeated it: the same
/// state as frame 0).
class Run {
 public:
  Run(const Scene& scene, const MethodInfo& method, const RunOptions& options,
      std::chrono::steady_clock::time_point start);

  /// A fresh run's first frame and sample, or a resumed run's state as its frame holds it.
  void begin();
  /// Steps to the end time, a failure, a failed write or a signal.
  void step_loop();
  /// The last sample and frame; returns the status ("completed", "failed", "interrupted").
  std::string finish();
  /// Writes metrics.json.
  RunSummary report(const std::string& status);

 private:
  void resume_from(const ResumePoint& point);
  void restore_driver_state(const StateBag& state);
  StateBag state_now() const;
  bool take_step();
  std::optional<Failure> check_step(double previous_time) const;
  void sample_if_due();
  bool write_if_due();
  void write_output(bool with_series, bool restart_point);
  FrameGeometry frame_geometry(double t);
  std::vector<Reaction> sampled_reactions();
  void sample(const std::vector<Reaction>& reactions);
  void note_reactions(const std::vector<Reaction>& reactions);
  double wall_seconds() const;
  Json metrics_json(const std::string& status);
  Json resumed_json(double wall) const;
  Json warnings_json(const std::string& status, const Json& diagnostics) const;

  const Scene& scene_;
  const MethodInfo& method_;
  const RunOptions& options_;
  const std::chrono::steady_clock::time_point start_;
  Particles particles_;
  std::unique_ptr<Solver> solver_;
  // Every frame carries the state where the solver can give it all (`duet run --resume`).
  const bool keeps_state_;
  const std::optional<ResumePoint> resume_;
  std::optional<Failure> failure_;
  RunWriter writer_;
  MeasureRecorder measures_;
  Timers output_timers_;

  const double sample_interval_;
  double time_ = 0.0;
  long steps_ = 0;
  double next_output_;
  double next_sample_;
  int interrupted_by_ = 0;  // the signal that ended the run, or 0
  bool output_failed_ = false;
  double wall_before_ = 0.0;  // a resumed run: the wall time of the run up to its frame
  std::vector<Vec2> previous_position_;

  const StateChecks checks_;
  EnergyBudget budget_;
  KineticEnergyRecord energy_;
  // An inertial run's measures sample the reactions' mean since the last sample
  // (common/reaction_mean.hpp); a quasi-static run's, the equilibrium reactions at that time.
  const bool inertial_;
  ReactionMean reaction_mean_;
  // The load on each driven boundary at every sample, for the load-drop warning (run_warnings).
  std::vector<BoundaryLoad> boundary_loads_;
  // The largest |F| each wall and rigid body carried since the run began: a moving one that
  // carried none never touched the material (run_warnings).
  std::vector<double> largest_reaction_;
  std::optional<Progress> progress_;
};

Run::Run(const Scene& scene, const MethodInfo& method, const RunOptions& options,
         std::chrono::steady_clock::time_point start)
    : scene_(scene),
      method_(method),
      options_(options),
      start_(start),
      particles_(sampled_material_points(scene)),
      solver_(method.make(scene)),
      keeps_state_(solver_->resume_refusal().empty()),
      resume_(resume_point(options, method, *solver_)),
      failure_(initialise_solver(scene, *solver_, particles_)),
      writer_(open_writer(options.out_dir, resume_)),
      measures_(scene),
      sample_interval_(scene.time.output_interval / 10.0),
      next_output_(scene.time.output_interval),
      next_sample_(sample_interval_),
      previous_position_(particles_.position),
      checks_(scene, particles_),
      budget_(scene, particles_, stored_elastic_energy(scene, particles_)),
      inertial_(solver_->inertial()),
      boundary_loads_(driven_boundaries(scene)) {
  writer_.write_metadata(scene.name, method.name, scene.resolved_toml, source_commit(),
                         scene.spacing, boundary_names(scene));
}

void Run::begin() {
  if (resume_) {
    resume_from(*resume_);
    return;
  }
  write_output(false, true);
  sample(solver_->reactions());
  energy_.record(time_, kinetic_energy(particles_));
}

/// The particles, the driver's counters and the solver as the frame holds them.
void Run::resume_from(const ResumePoint& point) {
  try {
    read_particle_state(writer_.h5_path(), point.frame, particles_);
    restore_driver_state(point.state);
    solver_->restore_state(point.state, particles_);
    solver_->restart_point();
  } catch (const std::runtime_error& e) {
    throw InputError("--resume " + options_.out_dir + ": frame " + std::to_string(point.frame) +
                     ": " + e.what());
  }
  previous_position_ = particles_.position;
}

/// state_now's entries, read back. Throws std::runtime_error when one does not fit.
void Run::restore_driver_state(const StateBag& state) {
  std::vector<double> internal;
  get(state, "driver.internal", internal);
  if (internal.size() != particles_.internal.values.size()) {
    throw std::runtime_error("its internal variables are not this scene's");
  }
  particles_.internal.values = std::move(internal);
  time_ = scalar(state, "driver.time");
  steps_ = static_cast<long>(scalar(state, "driver.steps"));
  next_output_ = scalar(state, "driver.next_output");
  next_sample_ = scalar(state, "driver.next_sample");
  const std::vector<double>& k = entry(state, "driver.kinetic_energy");
  if (k.size() != 3) throw std::runtime_error("its kinetic energy record has another size");
  energy_.peak = k[0];
  energy_.peak_time = k[1];
  energy_.end = k[2];
  wall_before_ = scalar(state, "driver.wall_seconds");
  measures_.restore_state(state);
  reaction_mean_.restore_state(state);
  // absent from frames written before it was kept: the record starts afresh
  if (state.count("driver.reaction_largest") != 0) {
    get(state, "driver.reaction_largest", largest_reaction_);
  }
  for (BoundaryLoad& b : boundary_loads_) {
    if (state.count("driver.load." + b.name) == 0) continue;  // as above
    get(state, "driver.load_time." + b.name, b.time);
    get(state, "driver.load." + b.name, b.load);
  }
  budget_.restore_state(state);
}

/// All the run carries from one step to the next, for a frame's /state.
StateBag Run::state_now() const {
  StateBag state;
  put(state, "driver.time", time_);
  put(state, "driver.steps", static_cast<double>(steps_));
  put(state, "driver.next_output", next_output_);
  put(state, "driver.next_sample", next_sample_);
  put(state, "driver.kinetic_energy",
      std::vector<double>{energy_.peak, energy_.peak_time, energy_.end});
  put(state, "driver.wall_seconds", wall_before_ + wall_seconds());
  put(state, "driver.internal", particles_.internal.values);
  measures_.save_state(state);
  reaction_mean_.save_state(state);
  put(state, "driver.reaction_largest", largest_reaction_);
  for (const BoundaryLoad& b : boundary_loads_) {
    put(state, "driver.load_time." + b.name, b.time);
    put(state, "driver.load." + b.name, b.load);
  }
  budget_.save_state(state);
  solver_->save_state(state);
  return state;
}

void Run::step_loop() {
  if (options_.show_progress) progress_.emplace(scene_.time.end_time, std::cerr, isatty(2) != 0);
  while (time_ < scene_.time.end_time * (1.0 - 1e-12) && !failure_) {
    previous_position_ = particles_.position;
    const double previous_time = time_;
    if (!take_step()) break;
    if (std::optional<Failure> problem = check_step(previous_time)) {
      failure_ = std::move(problem);
      break;
    }
    sample_if_due();
    if (!write_if_due()) break;
    if (progress_) progress_->update(time_, steps_);
    if ((interrupted_by_ = pending_interrupt()) != 0) break;
  }
}

/// One solver step and what follows it: the kinetic energy, the reactions, the energy put in.
/// false when the step failed (failure_ says why).
bool Run::take_step() {
  try {
    const double dt = solver_->step(scene_, particles_, time_);
    time_ += dt;
    ++steps_;
    energy_.record(time_, kinetic_energy(particles_));
    const std::vector<Reaction> reactions = solver_->reactions();
    note_reactions(reactions);
    if (inertial_) reaction_mean_.add(reactions, dt);
    budget_.record(time_, particles_, reactions);
    budget_.observe(energy_.end);
    return true;
  } catch (const NumericalFailure& e) {
    failure_ = Failure{e.what(), time_, e.particle()};
    if (e.particle() >= 0 && static_cast<std::size_t>(e.particle()) < particles_.size()) {
      failure_->position = particles_.position[static_cast<std::size_t>(e.particle())];
    }
    return false;
  }
}

/// The state after a step: what the checks (common/run_checks.hpp) find wrong, or nothing.
std::optional<Failure> Run::check_step(double previous_time) const {
  if (auto problem = checks_.check(particles_, previous_position_, previous_time, time_)) {
    return Failure{problem->reason, time_, problem->particle, problem->position};
  }
  if (auto problem = checks_.check_lift_off(particles_)) {
    return Failure{problem->reason, time_, problem->particle, problem->position};
  }
  // A quasi-static run's velocities are increments over a load step, not inertia.
  if (inertial_) {
    if (auto reason =
            energy_runaway(scene_.checks, energy_.end, budget_, energy_unit(scene_.formulation))) {
      return Failure{*reason, time_};
    }
  }
  return std::nullopt;
}

void Run::sample_if_due() {
  if (time_ < next_sample_) return;
  sample(sampled_reactions());
  next_sample_ += sample_interval_;
}

/// A frame at each output time; false when writing it failed (the run ends there).
bool Run::write_if_due() {
  if (time_ < next_output_) return true;
  // before the write: the frame's state holds the next output time
  next_output_ += scene_.time.output_interval;
  write_output(true, true);
  return !output_failed_;
}

/// A frame (and the series with it): a full disk or a quota ends the run, the frames written
/// before stay readable. A failure found before the write stays the run's reason. The first frame
/// and the frames at the output times hold the state (where the solver keeps one) and are restart
/// points: a resumed run starts from one of them, the last state-holding frame (the frame written
/// when a run stops is not one).
void Run::write_output(bool with_series, bool restart_point) {
  ScopedTimer t(output_timers_, Phase::output);
  try {
    if (with_series) writer_.set_series(measures_.names(), measures_.columns());
    const bool with_state = keeps_state_ && restart_point;
    const std::optional<StateBag> state =
        with_state ? std::optional<StateBag>(state_now()) : std::nullopt;
    writer_.write_frame(time_, particles_, frame_geometry(time_), state ? &*state : nullptr);
    if (with_state) solver_->restart_point();
  } catch (const std::exception& e) {
    output_failed_ = true;
    if (!failure_) failure_ = Failure{std::string("writing the output failed: ") + e.what(), time_};
  }
}

/// The walls and rigid bodies where they are at `t`, and the solver's mesh.
FrameGeometry Run::frame_geometry(double t) {
  return FrameGeometry{boundary_lines_at(scene_, t), solver_->mesh_triangles(particles_)};
}

std::vector<Reaction> Run::sampled_reactions() {
  return inertial_ ? reaction_mean_.take(solver_->reactions()) : solver_->reactions();
}

void Run::sample(const std::vector<Reaction>& reactions) {
  measures_.sample(time_, particles_, reactions);
  record_boundary_loads(scene_, time_, reactions, boundary_loads_);
}

void Run::note_reactions(const std::vector<Reaction>& reactions) {
  largest_reaction_.resize(reactions.size(), 0.0);
  for (std::size_t k = 0; k < reactions.size(); ++k) {
    largest_reaction_[k] = std::max(largest_reaction_[k], reactions[k].force.norm());
  }
}

/// Wall time of this process's part of the run.
double Run::wall_seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::string Run::finish() {
  // The last state (or the state at failure) is always a frame, unless writing is what failed.
  if (!failure_) sample(sampled_reactions());
  if (!output_failed_) write_output(true, false);
  const std::string status = failure_ ? "failed" : interrupted_by_ ? "interrupted" : "completed";
  if (interrupted_by_) {
    failure_ = Failure{"interrupted by signal " + std::to_string(interrupted_by_), time_};
  }
  if (progress_) {
    progress_->finish(status == "completed" ? status : status + ": " + failure_->reason);
  }
  return status;
}

RunSummary Run::report(const std::string& status) {
  const Json metrics = metrics_json(status);
  write_json(options_.out_dir + "/metrics.json", metrics);
  return summary_from_metrics(metrics, options_.out_dir);
}

/// metrics.json; its fields and their order are what readers of the file rely on.
Json Run::metrics_json(const std::string& status) {
  const double wall = wall_seconds();
  Json metrics = Json::object();
  metrics["scene"] = scene_.name;
  metrics["method"] = method_.name;
  metrics["spacing"] = scene_.spacing;
  // How the plane is read: per metre (plane strain) or the whole circumference (axisymmetric)
  metrics["formulation"] = std::string(name_of(scene_.formulation, kFormulationNames));
  metrics["particles"] = static_cast<long>(particles_.size());
  metrics["steps"] = steps_;
  metrics["wall_seconds"] = wall_before_ + wall;  // a resumed run: both parts
  metrics["status"] = status;
  metrics["failure"] = failure_ ? failure_json(*failure_) : Json();
  metrics["end_time"] = time_;
  // Peng's order: the strength falls during the run; the factor it had reached at the end
  if (scene_.strength_reduction.factor != 1.0) {
    metrics["strength_factor_at_end"] = strength_factor_at(scene_, time_);
  }
  if (interrupted_by_) metrics["signal"] = static_cast<long>(interrupted_by_);
  // Whether `duet run --resume` can continue this run from its frames, and if not why.
  metrics["resumable"] = keeps_state_;
  if (!keeps_state_) metrics["resume_refusal"] = solver_->resume_refusal();
  if (resume_) metrics["resumed"] = resumed_json(wall);
  metrics["measures"] = measures_.final_values();
  metrics["accuracy"] = measures_.accuracy();
  Json timing = solver_->timers().to_json();
  timing["output"] = output_timers_.seconds(Phase::output);
  metrics["timing"] = timing;
  metrics["diagnostics"] = solver_->diagnostics();
  energy_.end_carriers = kinetic_energy_carriers(particles_);
  metrics["kinetic_energy"] = energy_.to_json();
  metrics["energy_input"] = budget_.to_json();
  const Json warnings = warnings_json(status, metrics["diagnostics"]);
  metrics["warnings"] = warnings;
  metrics["commit"] = source_commit();
  metrics["threads"] = thread_choice();
  metrics["scene_file"] = scene_.path;
  return metrics;
}

/// Where a resumed run went on from; its timing and output timer cover this process only.
Json Run::resumed_json(double wall) const {
  Json resumed = Json::object();
  resumed["from_frame"] = static_cast<long>(resume_->frame);
  resumed["from_time"] = resume_->time;
  resumed["wall_seconds_before"] = wall_before_;
  resumed["wall_seconds_after"] = wall;
  return resumed;
}

/// run_warnings' findings on a completed run (none on another), each also said on stderr.
Json Run::warnings_json(const std::string& status, const Json& diagnostics) const {
  std::map<std::string, double> largest_by_name;
  const std::vector<Reaction> reactions = solver_->reactions();
  for (std::size_t k = 0; k < reactions.size() && k < largest_reaction_.size(); ++k) {
    largest_by_name[reactions[k].name] = largest_reaction_[k];
  }
  const std::vector<std::string> warnings =
      status == "completed" ? run_warnings(scene_, inertial_, energy_, budget_, time_, diagnostics,
                                           particles_.size(), largest_by_name, boundary_loads_)
                            : std::vector<std::string>{};
  Json list = Json::array();
  for (const std::string& w : warnings) {
    list.push_back(w);
    std::cerr << "duet: warning: " << w << '\n';
  }
  return list;
}

}  // namespace

RunSummary run_scene(const Scene& scene, const MethodInfo& method, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  prepare_output_folder(options.out_dir);
  Run run(scene, method, options, start);
  run.begin();
  run.step_loop();
  const std::string status = run.finish();
  return run.report(status);
}

}  // namespace duet
