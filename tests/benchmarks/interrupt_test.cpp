// SIGINT / SIGTERM on a running `duet run`: the step in progress is finished, the last frame and
// metrics.json are written with status "interrupted" and the signal, and the exit status is
// 128 + signal; a second signal ends the process at once, the same one repeated within a second
// does not.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include "common/h5_writer.hpp"
#include "tests/benchmarks/child_run.hpp"

namespace duet {
namespace {

namespace fs = std::filesystem;

/// Starts `duet run` on the sand collapse (16 s at dp 5 mm through SPH), waits until its first
/// frame is on disk (handlers installed, stepping), sends each of `signals`, and returns the
/// wait status.
int interrupt_run(const fs::path& out, const std::vector<int>& signals) {
  fs::remove_all(out);
  const pid_t child =
      test::start_collapse_run({"--spacing", "0.005", "--quiet", "--out", out.string()});
  test::wait_for_first_frame(out);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  for (int s : signals) kill(child, s);
  int status = 0;
  waitpid(child, &status, 0);
  return status;
}

TEST(Interrupt, SigintWritesTheFrameAndMetricsAndExits130) {
  const fs::path out = fs::temp_directory_path() / "duet-interrupt-int";
  const int status = interrupt_run(out, {SIGINT});
  ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 130);
  const std::string metrics = test::read_text(out / "metrics.json");
  EXPECT_NE(metrics.find("\"status\": \"interrupted\""), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("interrupted by signal 2"), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("\"signal\": 2"), std::string::npos) << metrics;
  // The initial frame and the interrupted state at least, readable.
  EXPECT_GE(count_frames((out / "run.h5").string()), 2u);
}

TEST(Interrupt, SigtermExits143) {
  const fs::path out = fs::temp_directory_path() / "duet-interrupt-term";
  const int status = interrupt_run(out, {SIGTERM});
  ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 143);
  EXPECT_NE(test::read_text(out / "metrics.json").find("interrupted by signal 15"),
            std::string::npos);
}

TEST(Interrupt, TheSameSignalDeliveredTwiceIsOneRequest) {
  // `timeout` and batch systems send SIGTERM to the process and then to its process group: the
  // handler may see it twice within microseconds. Once, that ended the fuzzer's run before its
  // metrics (one run in two under `timeout -k 10 11` on an espfem bar with density 1e-300).
  const fs::path out = fs::temp_directory_path() / "duet-interrupt-repeat";
  fs::remove_all(out);
  const pid_t child =
      test::start_collapse_run({"--spacing", "0.005", "--quiet", "--out", out.string()});
  test::wait_for_first_frame(out);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  kill(child, SIGTERM);
  std::this_thread::sleep_for(std::chrono::milliseconds(2));  // handled: not merged while pending
  kill(child, SIGTERM);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 143);
  EXPECT_NE(test::read_text(out / "metrics.json").find("interrupted by signal 15"),
            std::string::npos);
}

TEST(Interrupt, SecondSignalEndsAtOnce) {
  // Two different signals back to back (two of the same may merge into one while pending).
  const fs::path out = fs::temp_directory_path() / "duet-interrupt-twice";
  const int status = interrupt_run(out, {SIGINT, SIGTERM});
  ASSERT_TRUE(WIFSIGNALED(status)) << "exited with " << WEXITSTATUS(status);
  // Pending signals are delivered in the kernel's order: the second one handled ends it.
  EXPECT_TRUE(WTERMSIG(status) == SIGTERM || WTERMSIG(status) == SIGINT) << WTERMSIG(status);
  // The frames flushed before the second signal stay readable (the first one at least).
  EXPECT_GE(count_frames((out / "run.h5").string()), 1u);
}

}  // namespace
}  // namespace duet
