// The rigid strip footing on weightless Tresca soil (benchmarks/scenes/footing.toml, rough, to
// w/B = 0.1) through the implicit SPFEM at a coarse spacing (dp 0.25 m: 400 nodes, B/2 = 4 dp):
// the bearing pressure q / c_u at w/B = 0.1 within the scene's tolerance (10 %) of Prandtl's
// (2 + pi). Measured at this spacing: 4.47 at w/B 0.05, 5.26 at 0.1 (spfem/README.md).
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <string>

#include "benchmarks/driver.hpp"
#include "common/scene_loader.hpp"
#include "spfem/method.hpp"

namespace duet {
namespace {

TEST(ImplicitFootingBenchmark, BearingPressureWithinTenPercentOfPrandtlAtCoarseSpacing) {
  // Arrange
  const Scene scene = load_scene(std::string(DUET_SOURCE_DIR) + "/benchmarks/scenes/footing.toml",
                                 {"spacing=0.25"});
  MethodRegistry methods;
  spfem::register_ispfem(methods);
  const auto dir = (std::filesystem::temp_directory_path() /
                    ("duet-ispfem-footing-" + std::to_string(::getpid())))
                       .string();
  std::filesystem::remove_all(dir);
  // Act
  const RunSummary run = run_scene(scene, methods.find("ispfem"), RunOptions{dir, false});
  // Assert: Prandtl q_u / c_u = 2 + pi = 5.1416 (the scene's reference)
  ASSERT_TRUE(run.completed()) << run.failure_reason << " at t = " << run.failure_time;
  const Accuracy& bearing = run.accuracy.at("bearing");
  std::printf("q / c_u at w/B = 0.1: %.4f (reference %.4f), %+.2f %%, %.1f s\n", bearing.value,
              bearing.reference, 100.0 * (bearing.value - bearing.reference) / bearing.reference,
              run.wall_seconds);
  EXPECT_LT(bearing.rel_error, 0.1);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace duet
