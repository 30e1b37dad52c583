#pragma once
#include <string>

namespace duet {

/// The git commit of the source tree this program was built from, with "-dirty" when the working
/// tree has uncommitted changes; "unknown" outside a git checkout. Computed once per process.
const std::string& source_commit();

}  // namespace duet
