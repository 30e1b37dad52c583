#pragma once
#include <string>

namespace duet {

/// The git commit of the source tree this program was built from, with "-dirty" when its tracked
/// files had uncommitted changes; "unknown" outside a git checkout. Taken at build time
/// (cmake/WriteBuildCommit.cmake), so a binary copied elsewhere, or run after the tree moved on,
/// still names its own sources.
const std::string& source_commit();

}  // namespace duet
