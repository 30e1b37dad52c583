// The strength-reduction search on synthetic verdicts (a slope that fails above a known factor)
// and Peng's settle criterion on synthetic displacement curves.
#include "benchmarks/strength_reduction_search.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace duet {
namespace {

std::function<SrfTrial(double)> fails_above(double critical) {
  return [critical](double f) {
    SrfTrial t;
    t.stable = f <= critical;
    return t;
  };
}

TEST(SrfSearch, BracketsTheCriticalFactorToTheWidth) {
  for (double critical : {0.37, 1.0, 1.375, 1.38, 2.9}) {
    SrfSearchOptions options;
    const SrfResult r = srf_search(fails_above(critical), options);
    ASSERT_EQ(r.outcome, "bracketed") << critical;
    EXPECT_LE(r.last_stable, critical) << critical;
    EXPECT_GT(r.first_failed, critical) << critical;
    EXPECT_LE(r.first_failed - r.last_stable, options.width * (1 + 1e-9)) << critical;
    // Growing steps, then halving: a few tens of trials at most.
    EXPECT_LE(r.trials.size(), 15u) << critical;
    // Every trial's verdict agrees with the bracket.
    for (const SrfTrial& t : r.trials) {
      EXPECT_EQ(t.stable, t.factor <= r.last_stable) << t.factor;
    }
  }
}

TEST(SrfSearch, AWiderWidthTakesFewerTrials) {
  SrfSearchOptions fine, coarse;
  coarse.width = 0.1;
  const SrfResult a = srf_search(fails_above(1.38), fine);
  const SrfResult b = srf_search(fails_above(1.38), coarse);
  EXPECT_LT(b.trials.size(), a.trials.size());
  EXPECT_LE(b.first_failed - b.last_stable, 0.1 * (1 + 1e-9));
}

TEST(SrfSearch, AllStableAndAllFailedAreSaid) {
  SrfSearchOptions options;
  const SrfResult stable = srf_search(fails_above(100.0), options);
  EXPECT_EQ(stable.outcome, "all stable");
  EXPECT_EQ(stable.last_stable, options.highest);
  EXPECT_TRUE(std::isnan(stable.first_failed));
  const SrfResult failed = srf_search(fails_above(0.01), options);
  EXPECT_EQ(failed.outcome, "all failed");
  EXPECT_EQ(failed.first_failed, options.lowest);
  EXPECT_TRUE(std::isnan(failed.last_stable));
}

TEST(SrfSearch, TrialLimitAndStopEndTheSearch) {
  SrfSearchOptions options;
  options.max_trials = 4;
  EXPECT_EQ(srf_search(fails_above(1.38), options).outcome, "trial limit");
  int calls = 0;
  const SrfResult r = srf_search(
      [&](double f) {
        ++calls;
        return fails_above(1.38)(f);
      },
      SrfSearchOptions{}, [&] { return calls >= 2; });
  EXPECT_EQ(r.outcome, "interrupted");
  EXPECT_EQ(r.trials.size(), 2u);
}

std::vector<double> times(int n, double end) {
  std::vector<double> t(n);
  for (int k = 0; k < n; ++k) t[k] = end * k / (n - 1);
  return t;
}

TEST(SettleVerdict, ASlopeThatSettlesAndOneThatSlides) {
  const std::vector<double> t = times(51, 5.0);
  std::vector<double> settling(t.size()), sliding(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) {
    settling[k] = 0.02 * (1.0 - std::exp(-t[k] / 0.4));  // 1 - e^-x: 0.02 m, still 2e-8 m/s at 5 s
    sliding[k] = 0.02 + 0.1 * t[k];                      // a block sliding at 0.1 m/s
  }
  const SrfTrial a = settle_verdict(t, settling, SettleCriterion{});
  EXPECT_TRUE(a.stable) << a.reason;
  EXPECT_NEAR(a.final_displacement, 0.02, 1e-6);
  const SrfTrial b = settle_verdict(t, sliding, SettleCriterion{});
  EXPECT_FALSE(b.stable) << b.reason;
  // 0.1 m/s from the first sample in the last quarter (t = 3.8 s) to the end
  EXPECT_NEAR(b.window_increase, 0.12, 1e-12);
  EXPECT_EQ(b.reason.rfind("keeps moving", 0), 0u) << b.reason;
}

TEST(SettleVerdict, MotionBelowTheFloorIsNoise) {
  const std::vector<double> t = times(11, 1.0);
  std::vector<double> creep(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) creep[k] = 1e-4 * t[k];  // 0.1 mm in 1 s
  SettleCriterion criterion;
  EXPECT_FALSE(settle_verdict(t, creep, criterion).stable);
  criterion.floor = 1e-4;
  EXPECT_TRUE(settle_verdict(t, creep, criterion).stable);
}

}  // namespace
}  // namespace duet
