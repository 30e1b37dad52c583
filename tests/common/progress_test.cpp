// Progress display: plain lines off a terminal, an in-place bar on one, throttling and the cheap
// path of update(). The clock is injected, so the tests do not sleep.

#include "common/progress.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace duet {
namespace {

/// A clock the test sets (wall time of the simulated run) and that counts its reads.
struct ManualClock {
  std::shared_ptr<double> now = std::make_shared<double>(0.0);
  std::shared_ptr<long> reads = std::make_shared<long>(0);
  Progress::Clock clock() const {
    return [now = now, reads = reads] {
      ++*reads;
      return *now;
    };
  }
  void set(double seconds) const { *now = seconds; }
};

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(Progress, PlainModePrintsALineAtEveryTenPercentAndEndsWithTheStatus) {
  // Arrange
  std::ostringstream out;
  const ManualClock clock;
  Progress progress(2.0, out, false, clock.clock());
  // Act: 200 steps of 0.01 s of simulated time.
  for (long step = 1; step <= 200; ++step) {
    clock.set(1e-3 * step);
    progress.update(step / 100.0, step);
  }
  progress.finish("completed");
  // Assert
  const std::string text = out.str();
  EXPECT_EQ(text.find('\r'), std::string::npos);
  const std::vector<std::string> lines = lines_of(text);
  ASSERT_EQ(lines.size(), 11u);  // 10 %, 20 %, ..., 100 %, then the status line
  for (int k = 1; k <= 10; ++k) {
    const std::string percent = std::to_string(10 * k) + ".0%";
    EXPECT_NE(lines[static_cast<std::size_t>(k - 1)].find(percent), std::string::npos)
        << "line " << k << ": " << lines[static_cast<std::size_t>(k - 1)];
  }
  EXPECT_NE(lines[9].find("steps 200"), std::string::npos) << lines[9];
  const std::string& last = lines.back();
  EXPECT_EQ(last.substr(last.size() - 9), "completed");
}

TEST(Progress, PlainModeReportsTheStateWhereARunFailed) {
  // Arrange
  std::ostringstream out;
  const ManualClock clock;
  Progress progress(1.0, out, false, clock.clock());
  // Act: the run stops at 35 %.
  for (long step = 1; step <= 35; ++step) {
    clock.set(1e-3 * step);
    progress.update(step / 100.0, step);
  }
  progress.finish("failed: non-finite stress");
  // Assert: lines at 10, 20, 30 %, the final state at 35 %, then the status.
  const std::vector<std::string> lines = lines_of(out.str());
  ASSERT_EQ(lines.size(), 5u) << out.str();
  EXPECT_NE(lines[3].find("35.0%"), std::string::npos) << lines[3];
  EXPECT_NE(lines[4].find("failed: non-finite stress"), std::string::npos) << lines[4];
}

TEST(Progress, PlainModePrintsEveryThirtySecondsOfWallTimeBetweenMarks) {
  // Arrange: 1 s of wall time per step; simulated time creeps (never reaches 10 %).
  std::ostringstream out;
  const ManualClock clock;
  Progress progress(1.0, out, false, clock.clock());
  // Act
  for (long step = 1; step <= 100; ++step) {
    clock.set(1.0 * step);
    progress.update(1e-5 * step, step);
  }
  // Assert: about 100 s of wall time -> 3 lines (at 30, 60, 90 s), none at a 10 % mark.
  const std::vector<std::string> lines = lines_of(out.str());
  EXPECT_EQ(lines.size(), 3u) << out.str();
}

TEST(Progress, TerminalModeRedrawsOneLineWithCarriageReturns) {
  // Arrange
  std::ostringstream out;
  const ManualClock clock;  // 0.3 s per step, slower than the redraw interval
  Progress progress(1.0, out, true, clock.clock());
  // Act
  for (long step = 1; step <= 10; ++step) {
    clock.set(0.3 * step);
    progress.update(0.1 * step, step);
  }
  const std::string before_finish = out.str();
  progress.finish("completed");
  // Assert
  EXPECT_EQ(before_finish.find('\n'), std::string::npos);
  EXPECT_EQ(std::count(before_finish.begin(), before_finish.end(), '\r'), 10);
  EXPECT_NE(before_finish.find("100.0%"), std::string::npos);
  EXPECT_NE(before_finish.find("ETA"), std::string::npos);
  EXPECT_NE(before_finish.find("steps/s"), std::string::npos);
  const std::string text = out.str();
  EXPECT_EQ(text.substr(text.size() - 10), "completed\n");
}

TEST(Progress, TerminalModeRedrawsAtMostFiveTimesASecond) {
  // Arrange: 10 ms of wall time per step; 1000 steps = 10 s.
  std::ostringstream out;
  const ManualClock clock;
  Progress progress(1.0, out, true, clock.clock());
  // Act
  for (long step = 1; step <= 1000; ++step) {
    clock.set(0.01 * step);
    progress.update(1e-3 * step, step);
  }
  // Assert: at most 5 redraws per second of the clock's time.
  const std::string text = out.str();
  const auto redraws = std::count(text.begin(), text.end(), '\r');
  const double elapsed = *clock.now;
  EXPECT_GT(redraws, 0);
  EXPECT_LE(static_cast<double>(redraws), 5.0 * elapsed + 1.0);
}

TEST(Progress, UpdateReadsTheClockOnlyOnceInManyCallsWhenStepsAreFast) {
  // Arrange: fast steps, 1 us of wall time each.
  std::ostringstream out;
  const ManualClock clock;
  Progress progress(1.0, out, true, clock.clock());
  // Act
  const long n = 100000;
  for (long step = 1; step <= n; ++step) {
    clock.set(1e-6 * step);
    progress.update(0.5 * step / n, step);
  }
  // Assert: the stride grows, so the clock is read for well under 1 % of the calls.
  EXPECT_LT(*clock.reads, n / 100);
  EXPECT_EQ(progress.clock_reads(), *clock.reads);
}

TEST(Progress, UpdateReadsTheClockEveryCallWhenStepsAreSlow) {
  // Arrange: slow steps (an implicit solve), 1 s of wall time between updates.
  std::ostringstream out;
  const ManualClock clock;
  Progress progress(100.0, out, true, clock.clock());
  // Act
  for (long step = 1; step <= 20; ++step) {
    clock.set(1.0 * step);
    progress.update(1.0 * step, step);
  }
  // Assert: every update redraws (one clock read each, plus the one at construction).
  EXPECT_EQ(*clock.reads, 21);
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\r'), 20);
}

}  // namespace
}  // namespace duet
