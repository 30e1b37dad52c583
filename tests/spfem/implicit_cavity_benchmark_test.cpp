// Cylindrical cavity expansion in Tresca soil (benchmarks/scenes/cavity.toml: a0 = 1 m, traction
// free outer radius 20 m, to a/a0 = 2) through the implicit SPFEM at a coarse spacing (dp
// 0.35 m, polar lattice: 2,000 nodes, five on the cavity's quarter arc): the cavity pressure
// p / c_u within 3 % of the closed form for the finite ring at a/a0 = 1.2, 1.5 and 2 (issue:
// "cavity within 3 % at the radii"). Measured at this spacing: +0.5 %, -2.4 %, -2.1 %
// (benchmarks/RESULTS.md). Before the polar lattice (a square lattice leaves the nodes nearest
// the arc 0 to dp off it) it lagged by 4 % at a/a0 1.2; before the wall kept the nodes it held,
// the first ring lost the wall at every other increment.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "benchmarks/driver.hpp"
#include "common/scene_loader.hpp"
#include "spfem/method.hpp"

namespace duet {
namespace {

/// p / c_u of an incompressible Tresca ring a0 <= r <= b0, outer radius traction free (Yu 2000,
/// ch. 3, large strain): c^2 = I_r (a^2 - a0^2), b^2 = b0^2 + a^2 - a0^2.
double ring_pressure(double a_over_a0, double rigidity, double b0) {
  const double a2 = a_over_a0 * a_over_a0;
  const double c2 = rigidity * (a2 - 1.0);
  const double b2 = b0 * b0 + a2 - 1.0;
  return 1.0 - c2 / b2 + std::log(c2 / a2);
}

TEST(ImplicitCavityBenchmark, PressureWithinThreePercentOfTheFiniteRingAtThreeRadii) {
  // Arrange
  const Scene scene =
      load_scene(std::string(DUET_SOURCE_DIR) + "/benchmarks/scenes/cavity.toml", {"spacing=0.35"});
  MethodRegistry methods;
  spfem::register_ispfem(methods);
  const auto dir = (std::filesystem::temp_directory_path() /
                    ("duet-ispfem-cavity-" + std::to_string(::getpid())))
                       .string();
  std::filesystem::remove_all(dir);
  // Act
  const RunSummary run = run_scene(scene, methods.find("ispfem"), RunOptions{dir, false});
  // Assert: the scene's references are the closed form (G = E / 2 (1 + nu), I_r = G / c_u)
  ASSERT_TRUE(run.completed()) << run.failure_reason << " at t = " << run.failure_time;
  const double rigidity = 1.0e6 / (2.0 * 1.497) / 1.0e4;
  const struct {
    const char* measure;
    double a_over_a0;
  } radii[] = {{"pressure_a12", 1.2}, {"pressure_a15", 1.5}, {"pressure", 2.0}};
  for (const auto& r : radii) {
    const Accuracy& p = run.accuracy.at(r.measure);
    EXPECT_NEAR(p.reference, ring_pressure(r.a_over_a0, rigidity, 20.0), 1e-4);
    std::printf("a/a0 %.1f: p/c_u %.4f (closed form %.4f), %+.2f %%\n", r.a_over_a0, p.value,
                p.reference, 100.0 * (p.value - p.reference) / p.reference);
    EXPECT_LT(p.rel_error, 0.03) << r.measure;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace duet
