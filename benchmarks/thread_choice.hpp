#pragma once
#include "common/json.hpp"

namespace duet {

/// The OpenMP threads a run used and how they wait, for metrics.json's "threads": the count, the
/// wait settings as the environment gave them (null: libgomp's default, a long spin), and who
/// chose them (`./duet run` measures the idle cores and says so in DUET_THREADS_CHOICE; otherwise
/// the caller's environment).
Json thread_choice();

}  // namespace duet
