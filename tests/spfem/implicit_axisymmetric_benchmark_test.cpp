// The implicit SPFEM on an axisymmetric scene (x = r about x = 0): the spherical cavity of
// benchmarks/scenes/cavity-spherical.toml (a0 = 1 m, traction-free outer radius 20 m, E = 1 MPa,
// nu = 0.497) kept elastic (c_u far above any stress it reaches) and expanded to a/a0 = 1.02 at
// dp 0.25 m: the cavity pressure against Lame's thick sphere. The hoop strain u_r / r and the
// ring weights carry the whole answer here: the same mesh in plane strain is a cylinder, whose
// pressure 2 G u / a is half the sphere's.
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

/// p of an elastic thick sphere a <= r <= b, traction free at b, its inner surface displaced
/// radially by `u` (small strain; Timoshenko & Goodier, Theory of Elasticity, thick spherical
/// shell): u(r) = A r + B / r^2 with 3 K A = 4 G B / b^3, so p = 4 G B (1 / a^3 - 1 / b^3),
/// B = u / (1 / a^2 + 4 G a / (3 K b^3)).
double lame_sphere_pressure(double u, double a, double b, double shear, double bulk) {
  const double coefficient = u / (1.0 / (a * a) + 4.0 * shear * a / (3.0 * bulk * b * b * b));
  return 4.0 * shear * coefficient * (1.0 / (a * a * a) - 1.0 / (b * b * b));
}

TEST(ImplicitAxisymmetricBenchmark, ElasticSphereExpansionWithinThreePercentOfLame) {
  // Arrange: the scene's cavity, elastic, to a/a0 = 1.02 in 20 increments, the pressure read
  // at the end (t = 0.2 s at 0.1 m/s)
  const Scene scene =
      load_scene(std::string(DUET_SOURCE_DIR) + "/benchmarks/scenes/cavity-spherical.toml",
                 {"spacing=0.25", "material.clay.cu=1e12", "time.end_time=0.2",
                  "measure.pressure.time=0.2", "measure.pressure_a12.time=0.2",
                  "measure.pressure_a15.time=0.2", "spfem.implicit.load_steps=20"});
  MethodRegistry methods;
  spfem::register_ispfem(methods);
  const auto dir = (std::filesystem::temp_directory_path() /
                    ("duet-ispfem-sphere-" + std::to_string(::getpid())))
                       .string();
  std::filesystem::remove_all(dir);
  // Act
  const RunSummary run = run_scene(scene, methods.find("ispfem"), RunOptions{dir, false});
  // Assert: p / c_u (the measure's scale 1e-4 is 1 / c_u of the scene's 10 kPa)
  ASSERT_TRUE(run.completed()) << run.failure_reason << " at t = " << run.failure_time;
  const double e = 1.0e6;
  const double nu = 0.497;
  const double shear = e / (2.0 * (1.0 + nu));
  const double bulk = e / (3.0 * (1.0 - 2.0 * nu));
  const double expected = lame_sphere_pressure(0.02, 1.0, 20.0, shear, bulk) * 1.0e-4;
  const double p = run.accuracy.at("pressure").value;
  std::printf("a/a0 1.02: p/c_u %.4f (Lame's sphere %.4f), %+.2f %%\n", p, expected,
              100.0 * (p - expected) / expected);
  EXPECT_NEAR(p, expected, 0.03 * expected);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace duet
