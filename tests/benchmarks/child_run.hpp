#pragma once
// For the tests that run the duet program as a child process and look at what it left behind
// (signals, kills, output faults, listings): run it, or start it and wait for its first frame;
// read its files.

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace duet::test {

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

struct DuetResult {
  int status = -1;     // exit status, -1 when killed by a signal
  std::string output;  // stdout and stderr
};

/// Runs a shell command to its end, stdout and stderr captured.
inline DuetResult run_command(const std::string& shell_command) {
  const std::string command = shell_command + " 2>&1";
  DuetResult r;
  FILE* pipe = popen(command.c_str(), "r");
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) r.output += buffer;
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

/// Runs `duet ARGUMENTS` (a shell word list) to its end.
inline DuetResult run_duet(const std::string& arguments) {
  return run_command(std::string("'") + DUET_BINARY + "' " + arguments);
}

struct PngSize {
  std::uint32_t width = 0, height = 0;
};

/// Width and height of a PNG from its IHDR chunk; {0, 0} when the file is not a PNG.
inline PngSize png_size(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char h[24] = {};
  in.read(reinterpret_cast<char*>(h), sizeof h);
  const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (!in || !std::equal(signature, signature + 8, h)) return {};
  const auto word = [&](int at) {
    return std::uint32_t(h[at]) << 24 | std::uint32_t(h[at + 1]) << 16 |
           std::uint32_t(h[at + 2]) << 8 | std::uint32_t(h[at + 3]);
  };
  return {word(16), word(20)};
}

/// `duet run` on benchmarks/scenes/<scene>.toml through `method` with `arguments` after it, stdout
/// and stderr to /dev/null; `in_child` runs in the child before exec (resource limits, signal
/// dispositions).
inline pid_t start_run(const std::string& scene, const std::string& method,
                       const std::vector<std::string>& arguments,
                       const std::function<void()>& in_child = {}) {
  const std::string file = std::string(DUET_SOURCE_DIR) + "/benchmarks/scenes/" + scene + ".toml";
  std::vector<std::string> words = {DUET_BINARY, "run", file, "--method", method};
  words.insert(words.end(), arguments.begin(), arguments.end());
  const pid_t child = fork();
  if (child == 0) {
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(null, 2);
    if (in_child) in_child();
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    execv(DUET_BINARY, argv.data());
    _exit(127);
  }
  return child;
}

/// start_run on the sand collapse through SPH.
inline pid_t start_collapse_run(const std::vector<std::string>& arguments,
                                const std::function<void()>& in_child = {}) {
  return start_run("collapse", "sph", arguments, in_child);
}

/// Frames run.xdmf lists: those completed (flushed) before it was last replaced.
inline std::size_t frames_listed(const std::filesystem::path& xdmf) {
  const std::string s = read_text(xdmf);
  std::size_t count = 0;
  for (auto at = s.find("<Grid Name=\"frame_"); at != std::string::npos;
       at = s.find("<Grid Name=\"frame_", at + 1)) {
    ++count;
  }
  return count;
}

/// Waits (at most a minute) until the run in `out` has written its first frame: its signal
/// handlers are installed and it is stepping. run.xdmf alone is not enough: the writer lists no
/// frame in it until frame 0 is closed (a kill 37 ms after the file appeared found none under the
/// sanitizers).
inline void wait_for_first_frame(const std::filesystem::path& out) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  const std::filesystem::path xdmf = out / "run.xdmf";
  while (!(std::filesystem::exists(xdmf) && frames_listed(xdmf) >= 1) &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

}  // namespace duet::test
