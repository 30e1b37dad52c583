// A write that fails mid-run (a full disk, a quota, a folder gone) ends the run as `failed` with
// the reason, exit 3, and every frame run.xdmf lists before it reads whole. Two faults: the first
// frame file larger than the file-size limit set on the child (RLIMIT_FSIZE, SIGXFSZ ignored so
// the write returns EFBIG), and the frames folder replaced by a plain file after a few frames, so
// that the next frame file cannot be created.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "common/h5_writer.hpp"
#include "tests/benchmarks/child_run.hpp"

namespace duet {
namespace {

namespace fs = std::filesystem;

/// Waits for the child's exit; its exit status, or -1 when a signal ended it.
int exit_status(pid_t child) {
  int status = 0;
  waitpid(child, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void expect_failed_writing(const fs::path& out) {
  const std::string metrics = test::read_text(out / "metrics.json");
  EXPECT_NE(metrics.find("\"status\": \"failed\""), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("writing the output failed"), std::string::npos) << metrics;
}

TEST(OutputFault, AFrameBeyondTheFileSizeLimitEndsTheRunAsFailed) {
  const fs::path out = fs::temp_directory_path() / "duet-output-fault-size";
  fs::remove_all(out);
  // A frame of 2,211 particles is 0.63 MB; run.h5 (metadata, no series yet) is far smaller.
  const pid_t child = test::start_collapse_run(
      {"--spacing", "0.003", "--set", "time.end_time=0.01", "--quiet", "--out", out.string()}, [] {
        signal(SIGXFSZ, SIG_IGN);
        const rlimit limit{256 << 10, 256 << 10};
        setrlimit(RLIMIT_FSIZE, &limit);
      });
  ASSERT_EQ(exit_status(child), 3);
  expect_failed_writing(out);
  // Nothing half-written is named: run.h5 opens and lists no frame, no frame file is left.
  EXPECT_EQ(count_frames((out / "run.h5").string()), 0u);
  EXPECT_EQ(test::frames_listed(out / "run.xdmf"), 0u);
  EXPECT_TRUE(fs::is_empty(out / "frames"));
}

TEST(OutputFault, AFramesFolderGoneMidRunEndsTheRunAsFailedAndKeepsEarlierFrames) {
  const fs::path out = fs::temp_directory_path() / "duet-output-fault-folder";
  const fs::path kept = out.string() + "-kept";
  fs::remove_all(out);
  fs::remove_all(kept);
  const pid_t child =
      test::start_collapse_run({"--spacing", "0.003", "--set", "time.output_interval=0.0002",
                                "--set", "time.end_time=0.05", "--quiet", "--out", out.string()});
  // After three frames, the frames folder moves away and a plain file takes its name.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while ((!fs::exists(out / "run.xdmf") || test::frames_listed(out / "run.xdmf") < 3) &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  fs::rename(out / "frames", kept);
  std::ofstream(out / "frames") << "not a folder\n";
  ASSERT_EQ(exit_status(child), 3);
  expect_failed_writing(out);

  // The folder back in place: every frame listed reads whole through run.h5.
  fs::remove(out / "frames");
  fs::rename(kept, out / "frames");
  const std::size_t listed = test::frames_listed(out / "run.xdmf");
  ASSERT_GE(listed, 3u);
  EXPECT_GE(count_frames((out / "run.h5").string()), listed);
  for (std::size_t k = 0; k < listed; ++k) {
    EXPECT_EQ(read_frame((out / "run.h5").string(), k).position.size(), 2211u) << "frame " << k;
  }
}

}  // namespace
}  // namespace duet
