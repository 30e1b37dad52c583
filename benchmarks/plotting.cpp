#include "benchmarks/plotting.hpp"

#include <cstdlib>
#include <filesystem>

namespace duet {

namespace {

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

bool imports_matplotlib(const std::string& python) {
  const std::string command = shell_quote(python) + " -c 'import matplotlib' >/dev/null 2>&1";
  return std::system(command.c_str()) == 0;
}

}  // namespace

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
