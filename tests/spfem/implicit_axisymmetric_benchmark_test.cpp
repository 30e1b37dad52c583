// The implicit SPFEM on an axisymmetric scene (x = r about x = 0): the spherical cavity of
// benchmarks/scenes/cavity-spherical.toml (a0 = 1 m, traction-free outer radius 20 m, E = 1 MPa,
// nu = 0.497) kept elastic (c_u far above any stress it reaches) and expanded to a/a0 = 1.02 at
// dp 0.25 m: the cavity pressure against the thick elastic sphere's closed form (large strain,
// incompressible: nu 0.497 changes it by less than 0.1 %). The hoop strain and the
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

/// p of an incompressible elastic thick sphere a0 <= R <= b0 expanded to radius a, large strain.
/// The motion is radial, so the stress rate's spin terms vanish and the hypoelastic law integrates
/// to 2 G times the logarithmic strain's deviator: with the hoop stretch r / R(r) and the radial
/// one its inverse square, sigma_rr - sigma_tt = -6 G ln(r / R), and equilibrium,
/// d sigma_rr / dr + 2 (sigma_rr - sigma_tt) / r = 0, traction free at b, gives
///   p = 12 G int_a^b ln(r / R(r)) dr / r,  R^3 = r^3 - a^3 + a0^3,  b^3 = b0^3 + a^3 - a0^3
/// (Simpson's rule in ln r). For a -> a0 it is Lame's 4 G (a - a0) / a0 (1 - a0^3 / b0^3); at
/// a / a0 = 1.02 it lies 2.4 % below that.
double large_strain_sphere_pressure(double a0, double a, double b0, double shear) {
  const double b = std::cbrt(b0 * b0 * b0 + a * a * a - a0 * a0 * a0);
  const auto integrand = [&](double s) {  // ln(r / R) at r = e^s (dr / r = ds)
    const double r = std::exp(s);
    return std::log(r / std::cbrt(r * r * r - a * a * a + a0 * a0 * a0));
  };
  const int n = 4000;  // even
  const double lo = std::log(a);
  const double h = (std::log(b) - lo) / n;
  double sum = integrand(lo) + integrand(lo + n * h);
  for (int i = 1; i < n; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * integrand(lo + i * h);
  return 12.0 * shear * sum * h / 3.0;
}

TEST(ImplicitAxisymmetricBenchmark,
     ElasticSphereExpansionWithinThreePercentOfTheLargeStrainSphere) {
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
  const double shear = 1.0e6 / (2.0 * (1.0 + 0.497));
  const double expected = large_strain_sphere_pressure(1.0, 1.02, 20.0, shear) * 1.0e-4;
  const double p = run.accuracy.at("pressure").value;
  std::printf("a/a0 1.02: p/c_u %.4f (the large-strain elastic sphere %.4f), %+.2f %%\n", p,
              expected, 100.0 * (p - expected) / expected);
  EXPECT_NEAR(p, expected, 0.03 * expected);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace duet
