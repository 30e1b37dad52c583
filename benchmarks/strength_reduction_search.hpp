#pragma once
// The factor of safety by strength reduction (Peng 2015 section 5.3, papers/000 eqs 39-40;
// Griffiths & Lane 1999): runs at reduced strength c/f, tan(phi)/f, a search over f that brackets
// the factor between the last stable and the first failed trial, then bisects the bracket to a set
// width. The search and the verdict on one run are free functions of their inputs, so the logic is
// tested on synthetic verdicts (tests/benchmarks/strength_reduction_search_test.cpp); `duet srf`
// (srf_command.cpp) runs the trials.

#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace duet {

/// One trial at factor f: stable or failed, and why.
struct SrfTrial {
  double factor = 0.0;
  bool stable = false;
  std::string reason;  // the verdict in words ("settles", "keeps moving: ...", "run failed: ...")
  double final_displacement = std::numeric_limits<double>::quiet_NaN();  // m
  double window_increase = std::numeric_limits<double>::quiet_NaN();     // m
  double wall_seconds = 0.0;
  std::string dir;  // the trial's run folder
};

struct SrfSearchOptions {
  double start = 1.0;     // first factor tried
  double step = 0.2;      // first step of the bracketing; grows by 1.5 at each further step
  double width = 0.01;    // bisect until first_failed - last_stable <= width
  double lowest = 0.1;    // no factor below this is tried
  double highest = 10.0;  // nor above
  int max_trials = 40;
};

struct SrfResult {
  std::vector<SrfTrial> trials;  // in the order run
  double last_stable = std::numeric_limits<double>::quiet_NaN();
  double first_failed = std::numeric_limits<double>::quiet_NaN();
  // "bracketed" (to the width), "all stable" (up to highest), "all failed" (down to lowest),
  // "trial limit" (max_trials reached before the width), "interrupted"
  std::string outcome;
};

/// Brackets, then bisects. `run_trial(f)` returns the verdict at f; `stop()` (optional) ends the
/// search between trials (an interrupt).
SrfResult srf_search(const std::function<SrfTrial(double)>& run_trial,
                     const SrfSearchOptions& options, const std::function<bool()>& stop = nullptr);

/// Peng's criterion made a number: the slope settles when its largest displacement grew by no
/// more than max(fraction x its final value, floor) over the last `window` fraction of the run.
struct SettleCriterion {
  double window = 0.25;    // of the run's end time
  double fraction = 0.05;  // of the final largest displacement
  double floor = 0.0;      // m (the search uses 0.1 spacing: motion below it is noise)
};

/// The verdict on one completed run from its series of the largest displacement.
SrfTrial settle_verdict(const std::vector<double>& time, const std::vector<double>& displacement,
                        const SettleCriterion& criterion);

}  // namespace duet
