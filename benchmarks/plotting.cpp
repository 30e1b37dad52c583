#include "benchmarks/plotting.hpp"

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "common/input_error.hpp"

namespace duet {

namespace {

bool imports_matplotlib(const std::string& python) {
  const std::string command = shell_quote(python) + " -c 'import matplotlib' >/dev/null 2>&1";
  return std::system(command.c_str()) == 0;
}

}  // namespace

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'')
      out += "'\\''";
    else
      out += c;
  }
  return out + "'";
}

std::string plotting_python() {
  static const std::string found = [] {
    for (const char* candidate : {"/usr/bin/python3", "/bin/python3"}) {
      if (std::filesystem::exists(candidate) && imports_matplotlib(candidate))
        return std::string(candidate);
    }
    if (imports_matplotlib("python3")) return std::string("python3");
    return std::string();
  }();
  return found;
}

namespace {

/// Runs `command`, returning its exit status and what it printed (stdout and stderr).
int run_capturing(const std::string& command, std::string& output) {
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return -1;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int raw = pclose(pipe);
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

}  // namespace

std::vector<std::string> plot_run(const std::string& run_dir, const std::string& field,
                                  std::string* why) {
  namespace fs = std::filesystem;
  for (const char* name : {"metrics.json", "run.h5"}) {
    if (!fs::exists(fs::path(run_dir) / name)) {
      throw InputError(run_dir + ": no " + name + "; expected the folder of a duet run");
    }
  }
  const std::string python = plotting_python();
  if (python.empty()) {
    if (why) *why = "no python3 with matplotlib found (install python3-matplotlib)";
    return {};
  }
  std::string command = shell_quote(python);
  command.append(" ")
      .append(shell_quote(std::string(DUET_SOURCE_DIR) + "/benchmarks/plot/run.py"))
      .append(" ")
      .append(shell_quote(run_dir))
      .append(" ")
      .append(shell_quote(field))
      .append(" 2>&1");
  std::string output;
  const int status = run_capturing(command, output);
  std::vector<std::string> files;
  std::string line;
  for (const char c : output) {
    if (c != '\n') {
      line += c;
      continue;
    }
    if (line.ends_with(".png") && fs::exists(line)) files.push_back(line);
    line.clear();
  }
  if (status != 0) {
    // The script names what is wrong (an unknown field) on its last line.
    while (!output.empty() && output.back() == '\n') output.pop_back();
    const std::string last = output.substr(output.find_last_of('\n') + 1);
    if (last.starts_with("run.py: ")) throw InputError("plot " + run_dir + ": " + last.substr(8));
    if (why) *why = "plot script run.py failed (status " + std::to_string(status) + "): " + last;
    return {};
  }
  return files;
}

void draw_chart(const std::string& script, const std::vector<std::string>& arguments) {
  std::string why;
  if (!run_plot_script(script, arguments, &why))
    std::cerr << "duet: chart skipped: " << why << '\n';
}

bool run_plot_script(const std::string& script, const std::vector<std::string>& arguments,
                     std::string* why) {
  const std::string python = plotting_python();
  if (python.empty()) {
    if (why) *why = "no python3 with matplotlib found (install python3-matplotlib)";
    return false;
  }
  std::string path = DUET_SOURCE_DIR;
  path.append("/benchmarks/plot/").append(script);
  // Appends only: GCC 12 warns falsely (-Wrestrict, PR 105651) on chained string operator+.
  std::string command = shell_quote(python);
  command.append(" ").append(shell_quote(path));
  for (const auto& a : arguments) command.append(" ").append(shell_quote(a));
  command.append(" 2>&1");
  const int status = std::system(command.c_str());
  if (status != 0) {
    if (why) *why = "plot script " + script + " failed (status " + std::to_string(status) + ")";
    return false;
  }
  return true;
}

}  // namespace duet
