// The clamped elastic bar set moving (benchmarks/scenes/bar.toml) through the implicit SPFEM with
// Newmark's average acceleration: the period within 1 % of the wave equation's 4 L / c and the
// tip's first excursion within 5 % of v0 L / c (the wave from the clamp reaches the tip after
// L / c, until then the tip moves at v0).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "benchmarks/driver.hpp"
#include "common/h5_writer.hpp"
#include "common/scene_loader.hpp"
#include "spfem/method.hpp"

namespace duet {
namespace {

TEST(ImplicitBarBenchmark, NewmarkPeriodAndFirstExcursionMatchTheWaveEquation) {
  // Arrange: the scene as it is (400 increments over three periods)
  const Scene scene = load_scene(std::string(DUET_SOURCE_DIR) + "/benchmarks/scenes/bar.toml", {});
  MethodRegistry methods;
  spfem::register_ispfem(methods);
  const auto dir =
      (std::filesystem::temp_directory_path() / ("duet-ispfem-bar-" + std::to_string(::getpid())))
          .string();
  std::filesystem::remove_all(dir);
  // Act
  const RunSummary run = run_scene(scene, methods.find("ispfem"), RunOptions{dir, false});
  // Assert
  ASSERT_TRUE(run.completed()) << run.failure_reason << " at t = " << run.failure_time;
  const Accuracy& period = run.accuracy.at("period");
  std::printf("period %.5f s (4 L / c = %.5f s), %+.2f %%\n", period.value, period.reference,
              100.0 * (period.value - period.reference) / period.reference);
  EXPECT_LT(period.rel_error, 0.01);
  const std::vector<double> time = read_series(dir + "/run.h5", "time");
  const std::vector<double> tip = read_series(dir + "/run.h5", "tip");
  double first = 0.0;  // the largest displacement within the first period
  for (std::size_t k = 0; k < time.size() && time[k] < 0.04; ++k) first = std::max(first, tip[k]);
  const double closed_form = 0.01 * 1.0 / 100.0;  // v0 L / c, c = sqrt(E / rho) = 100 m/s
  std::printf("first excursion %.4e m (v0 L / c = %.4e m)\n", first, closed_form);
  EXPECT_NEAR(first, closed_form, 0.05 * closed_form);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace duet
