#include "benchmarks/git_commit.hpp"

#include "build_commit.hpp"  // generated at build time (cmake/WriteBuildCommit.cmake)

namespace duet {

const std::string& source_commit() {
  static const std::string commit = DUET_BUILD_COMMIT;
  return commit;
}

}  // namespace duet
