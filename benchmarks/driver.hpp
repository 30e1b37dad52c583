#pragma once
// The driver owns the loop, the output and failure handling for every method: it samples the
// particles, sets the material points' initial state, steps the solver to the end time, writes
// frames (run.h5 + run.xdmf), samples the scene's measures, scores them against the references,
// and writes metrics.json. A run that fails numerically stops cleanly with status "failed", its
// reason, time and particle, and every frame written so far.

#include <string>

#include "benchmarks/run_summary.hpp"
#include "common/scene.hpp"
#include "common/solver.hpp"

namespace duet {

struct RunOptions {
  std::string out_dir;
  bool show_progress = true;
  /// Continue the run in out_dir from its last frame that holds the state (`duet run --resume`):
  /// frames up to it are kept, the time, step count, measures, energy budget and the solver's
  /// state are restored, and the run goes on as if it had never stopped. `scene` and `method`
  /// must be those the run recorded.
  bool resume = false;
};

/// Runs `scene` through `method`; never throws for numerical failure (it is reported in the
/// summary and metrics.json). Throws InputError for bad input discovered while setting up.
RunSummary run_scene(const Scene& scene, const MethodInfo& method, const RunOptions& options);

/// Creates `dir` (and its parents) and proves it writable by writing and removing a file; throws
/// InputError (exit 2) naming the folder and why, before any work is done.
void prepare_output_folder(const std::string& dir);

/// What a run of `scene` through `method` would take: particles (from the bodies' areas) and peak
/// memory (the method's measured bytes per particle).
struct RunEstimate {
  double particles = 0.0;
  double bytes = 0.0;
  double machine_bytes = 0.0;  // physical memory of this machine
};
RunEstimate estimate_run(const Scene& scene, const MethodInfo& method);

/// Throws InputError with the estimate when the run would need more memory than the machine has
/// (unless `force`): refused in a second instead of a std::bad_alloc after minutes.
void refuse_if_too_large(const Scene& scene, const MethodInfo& method, bool force);

/// Default output folder for a run: runs/<scene>-<method>-dp<spacing>.
std::string default_run_dir(const Scene& scene, const std::string& method);

}  // namespace duet
