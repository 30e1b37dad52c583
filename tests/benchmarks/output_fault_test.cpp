// A write that fails mid-run (a full disk, a quota; here a file-size limit of 3 MB set on the
// child with RLIMIT_FSIZE, SIGXFSZ ignored so the write returns EFBIG) ends the run as `failed`
// with the reason, exit 3, and every frame run.xdmf lists before it reads whole.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "common/h5_writer.hpp"
#include "tests/benchmarks/child_run.hpp"

namespace duet {
namespace {

namespace fs = std::filesystem;

TEST(OutputFault, FailedWriteEndsTheRunAsFailedAndKeepsEarlierFrames) {
  const fs::path out = fs::temp_directory_path() / "duet-output-fault";
  fs::remove_all(out);
  const pid_t child =
      test::start_collapse_run({"--spacing", "0.003", "--set", "time.output_interval=0.0002",
                                "--set", "time.end_time=0.01", "--quiet", "--out", out.string()},
                               [] {
                                 signal(SIGXFSZ, SIG_IGN);
                                 const rlimit limit{3 << 20, 3 << 20};
                                 setrlimit(RLIMIT_FSIZE, &limit);
                               });
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 3);
  const std::string metrics = test::read_text(out / "metrics.json");
  EXPECT_NE(metrics.find("\"status\": \"failed\""), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("writing the output failed"), std::string::npos) << metrics;

  // 0.63 MB per frame of 2,211 particles: a few frames fit under 3 MB.
  const std::size_t listed = test::frames_listed(out / "run.xdmf");
  ASSERT_GE(listed, 1u);
  for (std::size_t k = 0; k < listed; ++k) {
    EXPECT_EQ(read_frame((out / "run.h5").string(), k).position.size(), 2211u) << "frame " << k;
  }
}

}  // namespace
}  // namespace duet
