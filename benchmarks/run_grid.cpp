#include "benchmarks/run_grid.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include "benchmarks/driver.hpp"
#include "benchmarks/listing_commands.hpp"
#include "benchmarks/methods.hpp"
#include "benchmarks/plotting.hpp"
#include "benchmarks/reports.hpp"
#include "benchmarks/scene_input.hpp"
#include "common/input_error.hpp"
#include "common/interrupt.hpp"
#include "common/json.hpp"

extern char** environ;

namespace duet {

namespace fs = std::filesystem;

namespace {

std::string this_program() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  return error ? std::string("duet") : self.string();
}

/// The cell's run folder, absolute.
std::string cell_folder(const std::string& grid_dir, const GridCell& cell) {
  return fs::absolute(fs::path(grid_dir) / cell.dir).lexically_normal().string();
}

/// The arguments of `duet run` for one cell (after the program name).
std::vector<std::string> run_arguments(const Grid& grid, const GridCell& cell,
                                       const std::string& grid_dir) {
  std::vector<std::string> a = {"run", grid.scene_file, "--method", cell.method};
  for (const std::string& o : cell.overrides) {
    a.push_back("--set");
    a.push_back(o);
  }
  a.push_back("--out");
  a.push_back(cell_folder(grid_dir, cell));
  a.push_back("--quiet");
  a.push_back("--no-plots");
  if (grid.force) a.push_back("--force");
  return a;
}

Json strings(const std::vector<std::string>& values) {
  Json j = Json::array();
  for (const std::string& v : values) j.push_back(v);
  return j;
}

std::string text_of(const Json& object, const char* key, const std::string& where) {
  const Json* j = object.find(key);
  if (!j || !j->is_string()) throw InputError(where + ": grid.json has no text '" + key + "'");
  return j->string();
}

/// Starts `duet run` for a cell as a child process; returns its pid.
pid_t spawn_cell(const Grid& grid, const GridCell& cell, const std::string& grid_dir) {
  const std::vector<std::string> arguments = run_arguments(grid, cell, grid_dir);
  const std::string cell_dir = cell_folder(grid_dir, cell);
  prepare_output_folder(cell_dir);
  const std::string program = this_program();
  std::vector<char*> argv = {const_cast<char*>(program.c_str())};
  for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::vector<std::string> environment;
  for (char** e = environ; *e; ++e) environment.emplace_back(*e);
  if (!std::getenv("OMP_NUM_THREADS")) environment.emplace_back("OMP_NUM_THREADS=1");
  std::vector<char*> envp;
  for (std::string& e : environment) envp.push_back(e.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  const std::string log = cell_dir + "/run.log";
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = -1;
  const int error = posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) {
    throw std::runtime_error("cannot start " + program + " for " + cell.dir + ": " +
                             std::strerror(error));
  }
  return pid;
}

}  // namespace

void write_grid(const std::string& grid_dir, const Grid& grid) {
  Json j = Json::object();
  j["kind"] = grid.kind;
  j["scene_file"] = grid.scene_file;
  j["scene"] = grid.scene_name;
  j["title"] = grid.title;
  j["target"] = grid.target;
  j["force"] = grid.force;
  Json cells = Json::array();
  for (const GridCell& c : grid.cells) {
    Json cell = Json::object();
    Json settings = Json::array();
    for (const auto& [key, value] : c.settings) settings.push_back(strings({key, value}));
    cell["settings"] = settings;
    cell["method"] = c.method;
    cell["overrides"] = strings(c.overrides);
    cell["dir"] = c.dir;
    cells.push_back(cell);
  }
  j["cells"] = cells;
  write_json(grid_dir + "/grid.json", j);
}

Grid read_grid(const std::string& grid_dir) {
  const std::string path = grid_dir + "/grid.json";
  if (!fs::exists(path)) {
    throw InputError(grid_dir +
                     ": no grid.json; expected the --out folder of duet stability or "
                     "duet compare (with or without --emit-jobs)");
  }
  Json j;
  try {
    j = read_json(path);
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
  Grid grid;
  grid.kind = text_of(j, "kind", path);
  grid.scene_file = text_of(j, "scene_file", path);
  grid.scene_name = text_of(j, "scene", path);
  grid.title = text_of(j, "title", path);
  if (const Json* t = j.find("target"); t && t->is_number()) grid.target = t->number();
  if (const Json* f = j.find("force"); f && f->is_bool()) grid.force = f->boolean();
  const Json* cells = j.find("cells");
  if (!cells || !cells->is_array()) throw InputError(path + ": grid.json has no list 'cells'");
  for (const Json& c : cells->elements()) {
    GridCell cell;
    cell.method = text_of(c, "method", path);
    cell.dir = text_of(c, "dir", path);
    if (const Json* s = c.find("settings"); s && s->is_array()) {
      for (const Json& pair : s->elements()) {
        if (!pair.is_array() || pair.elements().size() != 2) continue;
        cell.settings.emplace_back(pair.elements()[0].string(), pair.elements()[1].string());
      }
    }
    if (const Json* o = c.find("overrides"); o && o->is_array()) {
      for (const Json& v : o->elements()) cell.overrides.push_back(v.string());
    }
    grid.cells.push_back(std::move(cell));
  }
  return grid;
}

std::string job_command(const Grid& grid, const GridCell& cell, const std::string& grid_dir) {
  std::string line = shell_quote(this_program());
  for (const std::string& a : run_arguments(grid, cell, grid_dir)) line += " " + shell_quote(a);
  return line;
}

void write_job_file(const std::string& path, const Grid& grid, const std::string& grid_dir) {
  std::ofstream out(path, std::ios::trunc);
  if (!out) throw InputError("--emit-jobs " + path + ": cannot write the file");
  for (const GridCell& cell : grid.cells) out << job_command(grid, cell, grid_dir) << '\n';
  if (!out) throw InputError("--emit-jobs " + path + ": write failed");
}

void run_grid(const Grid& grid, const std::string& grid_dir, int jobs) {
  if (jobs <= 1) {
    for (const GridCell& cell : grid.cells) {
      if (pending_interrupt()) break;
      const Scene scene = load_scene_checked(grid.scene_file, cell.overrides, grid.force);
      RunOptions options;
      options.out_dir = grid_dir + "/" + cell.dir;
      std::cerr << "duet: " << cell.dir << '\n';
      run_scene(scene, builtin_methods().find(cell.method), options);
    }
    return;
  }
  std::map<pid_t, std::string> running;
  std::size_t next = 0;
  const auto reap_one = [&] {
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid <= 0) return;
    const auto it = running.find(pid);
    if (it == running.end()) return;
    std::cerr << "duet: " << it->second << " ended ("
              << (WIFEXITED(status) ? "exit " + std::to_string(WEXITSTATUS(status))
                                    : "signal " + std::to_string(WTERMSIG(status)))
              << ")\n";
    running.erase(it);
  };
  bool forwarded = false;
  while (next < grid.cells.size() || !running.empty()) {
    if (pending_interrupt() && !forwarded) {
      // Ctrl-C reached the children through the terminal; a SIGTERM to this process alone did not.
      for (const auto& [pid, dir] : running) kill(pid, SIGTERM);
      forwarded = true;
    }
    if (!forwarded && next < grid.cells.size() && running.size() < static_cast<std::size_t>(jobs)) {
      const GridCell& cell = grid.cells[next++];
      std::cerr << "duet: " << cell.dir << " started\n";
      running[spawn_cell(grid, cell, grid_dir)] = cell.dir;
      continue;
    }
    if (running.empty()) break;
    reap_one();
  }
}

std::vector<RunSummary> collect_runs(const Grid& grid, const std::string& grid_dir) {
  std::vector<RunSummary> runs;
  for (const GridCell& cell : grid.cells) {
    const std::string dir = grid_dir + "/" + cell.dir;
    const std::string metrics = dir + "/metrics.json";
    // A cell without a readable metrics.json: its row says so.
    RunSummary r;
    r.scene = grid.scene_name;
    r.method = cell.method;
    r.out_dir = dir;
    r.status = "not run";
    r.failure_reason = "no metrics.json in " + cell.dir;
    for (const auto& [key, value] : cell.settings) {
      if (key == "spacing") r.spacing = std::stod(value);
    }
    if (fs::exists(metrics)) {
      try {
        r = summary_from_metrics(read_json(metrics), dir);
      } catch (const std::runtime_error& e) {
        r.status = "unreadable";
        r.failure_reason = e.what();
      }
    }
    runs.push_back(r);
  }
  return runs;
}

std::string write_grid_reports(const Grid& grid, const std::string& grid_dir) {
  const std::vector<RunSummary> runs = collect_runs(grid, grid_dir);
  if (grid.kind == "compare") {
    write_compare_csv(grid_dir + "/compare.csv", runs);
    write_compare_markdown(grid_dir + "/compare.md", runs, grid.target);
    draw_chart("compare.py", {grid_dir + "/compare.csv", grid_dir + "/compare.png", grid.title});
    // Every run's frames side by side on one colour scale (each run's own chart has its own)
    std::vector<std::string> snapshots = {grid_dir + "/snapshots_von_mises.png", "von_mises"};
    for (const RunSummary& r : runs) {
      if (fs::exists(r.out_dir + "/run.h5")) snapshots.push_back(r.out_dir);
    }
    if (snapshots.size() > 2) draw_chart("snapshots.py", snapshots);
    return compare_markdown(runs, grid.target);
  }
  std::vector<StabilityCell> cells;
  for (std::size_t k = 0; k < runs.size(); ++k) cells.push_back({grid.cells[k].settings, runs[k]});
  write_stability_csv(grid_dir + "/stability.csv", cells);
  std::vector<std::string> chart = {grid_dir + "/stability.csv", grid_dir + "/stability.png",
                                    grid.title};
  if (!grid.cells.empty()) {
    for (const auto& [key, value] : grid.cells.front().settings)
      chart.push_back(key + "=" + scene_key_unit(key));
  }
  draw_chart("stability.py", chart);
  long completed = 0;
  for (const RunSummary& r : runs) completed += r.completed() ? 1 : 0;
  return std::to_string(completed) + " of " + std::to_string(runs.size()) +
         " cells completed: " + grid_dir + "/stability.csv\n";
}

}  // namespace duet
