#include "benchmarks/strength_reduction_search.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace duet {

SrfResult srf_search(const std::function<SrfTrial(double)>& run_trial,
                     const SrfSearchOptions& options, const std::function<bool()>& stop) {
  SrfResult result;
  const auto trial = [&](double f) {
    SrfTrial t = run_trial(f);
    t.factor = f;
    result.trials.push_back(t);
    if (t.stable) {
      result.last_stable = std::isnan(result.last_stable) ? f : std::max(result.last_stable, f);
    } else {
      result.first_failed = std::isnan(result.first_failed) ? f : std::min(result.first_failed, f);
    }
    return t.stable;
  };
  const auto out_of_trials = [&] {
    return static_cast<int>(result.trials.size()) >= options.max_trials;
  };
  const auto stopped = [&] { return stop && stop(); };

  // Bracket: up from a stable start, down from a failed one, with growing steps.
  double f = std::clamp(options.start, options.lowest, options.highest);
  double step = options.step;
  const bool start_stable = trial(f);
  while (!stopped() && !out_of_trials()) {
    if (start_stable && !std::isnan(result.first_failed)) break;
    if (!start_stable && !std::isnan(result.last_stable)) break;
    if (start_stable) {
      if (f >= options.highest) {
        result.outcome = "all stable";
        return result;
      }
      f = std::min(f + step, options.highest);
    } else {
      if (f <= options.lowest) {
        result.outcome = "all failed";
        return result;
      }
      f = std::max(f - step, options.lowest);
    }
    step *= 1.5;
    trial(f);
  }
  // Bisect the bracket.
  while (!std::isnan(result.last_stable) && !std::isnan(result.first_failed) &&
         result.first_failed - result.last_stable > options.width * (1.0 + 1e-9) && !stopped() &&
         !out_of_trials()) {
    trial(0.5 * (result.last_stable + result.first_failed));
  }
  if (stopped()) {
    result.outcome = "interrupted";
  } else if (std::isnan(result.last_stable) || std::isnan(result.first_failed) ||
             result.first_failed - result.last_stable > options.width * (1.0 + 1e-9)) {
    result.outcome = "trial limit";
  } else {
    result.outcome = "bracketed";
  }
  return result;
}

SrfTrial settle_verdict(const std::vector<double>& time, const std::vector<double>& displacement,
                        const SettleCriterion& criterion) {
  SrfTrial t;
  const std::size_t n = std::min(time.size(), displacement.size());
  if (n < 2) {
    t.stable = false;
    t.reason = "no displacement series to judge";
    return t;
  }
  const double end = time[n - 1];
  const double from = end - criterion.window * end;
  // The sample at the window's start (the first at or after it).
  std::size_t k = 0;
  while (k + 1 < n && time[k] < from) ++k;
  t.final_displacement = displacement[n - 1];
  t.window_increase = displacement[n - 1] - displacement[k];
  const double allowed =
      std::max(criterion.fraction * std::abs(t.final_displacement), criterion.floor);
  t.stable = t.window_increase <= allowed;
  char text[240];
  std::snprintf(text, sizeof text,
                "%s: largest displacement %.4g m, +%.3g m over the last %g s "
                "(allowed %.3g m)",
                t.stable ? "settles" : "keeps moving", t.final_displacement, t.window_increase,
                end - time[k], allowed);
  t.reason = text;
  return t;
}

}  // namespace duet
