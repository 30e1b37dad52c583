#include "benchmarks/git_commit.hpp"

#include <array>
#include <cstdio>
#include <memory>

namespace duet {

namespace {

std::string capture(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) return {};
  std::string out;
  std::array<char, 256> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe.get())) out += buffer.data();
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

}  // namespace

const std::string& source_commit() {
  static const std::string commit = [] {
    const std::string git = "git -C '" + std::string(DUET_SOURCE_DIR) + "' ";
    std::string hash = capture(git + "rev-parse HEAD 2>/dev/null");
    if (hash.empty()) return std::string("unknown");
    const std::string dirty = capture(git + "status --porcelain --untracked-files=no 2>/dev/null");
    if (!dirty.empty()) hash += "-dirty";
    return hash;
  }();
  return commit;
}

}  // namespace duet
