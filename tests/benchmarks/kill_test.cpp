// SIGKILL at any moment (issue 17): every frame that run.xdmf lists, i.e. every frame completed
// before the kill (each frame is a file of its own renamed into place when closed; run.h5, the
// index linking them, and then run.xdmf are replaced by a rename), opens and reads whole. The run
// writes a frame every few steps so that kills land inside frame writes as often as between them.
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

class Kill : public testing::TestWithParam<int> {};

TEST_P(Kill, EveryFrameListedBeforeTheKillReadsWhole) {
  const int delay_ms = GetParam();
  const fs::path out = fs::temp_directory_path() / ("duet-kill-" + std::to_string(delay_ms));
  fs::remove_all(out);
  const pid_t child =
      test::start_collapse_run({"--spacing", "0.003", "--set", "time.output_interval=0.0002",
                                "--quiet", "--out", out.string()});
  test::wait_for_first_frame(out);
  std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));

  const std::size_t listed = test::frames_listed(out / "run.xdmf");
  ASSERT_GE(listed, 1u);
  const std::string h5 = (out / "run.h5").string();
  ASSERT_GE(count_frames(h5), listed);  // a frame being written when killed may be there too
  for (std::size_t k = 0; k < listed; ++k) {
    const Frame frame = read_frame(h5, k);  // throws on a damaged frame
    ASSERT_EQ(frame.position.size(), 2211u) << "frame " << k;
    for (const Vec2& x : frame.position) ASSERT_TRUE(x.allFinite()) << "frame " << k;
  }
}

// Moments after the first frame, spread over the run's first two seconds.
INSTANTIATE_TEST_SUITE_P(RandomMoments, Kill, testing::Values(37, 211, 433, 758, 1290, 1877));

}  // namespace
}  // namespace duet
