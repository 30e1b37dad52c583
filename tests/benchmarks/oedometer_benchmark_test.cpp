// Oedometer benchmark (Peng 2015 5.1) through SPH and espfem, the same scene file, at smoke
// resolution (dp = 2.5 cm, 800 particles): the axial stress-strain curve in loading against the
// element test of the same model, and K0 against Peng eq (38).
//
// Strain: the sample stays uniform, so the velocity gradient is the logarithmic strain rate
// v / L(t), and the element driver sums strain increments, i.e. it also integrates the
// logarithmic strain. The curves are compared at eps = -ln(1 - u / H): with the stress growing
// about exp(348 |eps|), comparing at u / H instead would put 5.5 % between them at 1.7 % strain.
//
// DUET_SPH_SET / DUET_ESPFEM_SET="key=value;key=value" append scene overrides to that method's
// run (e.g. spacing=0.01 for the paper's resolution, or sph.cfl=... for a stability map).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "benchmarks/driver.hpp"
#include "common/h5_writer.hpp"
#include "common/scene_loader.hpp"
#include "constitutive/element_test.hpp"
#include "constitutive/registry.hpp"
#include "spfem/method.hpp"
#include "sph/method.hpp"

namespace duet {
namespace {

constexpr double kHeight = 1.0;             // m, the initial sample height (oedometer.toml)
constexpr double kEndOfLoading = 1.75;      // s, the plate turns (oedometer.toml)
constexpr double kTransientStrain = 0.001;  // log strain below which wave transients may dominate

std::vector<std::string> overrides(const std::string& method) {
  // Only loading is scored: stop just past the turn of the plate (the K0 measure is taken at
  // 1.75 s) instead of running the 0.25 s of unloading.
  std::vector<std::string> out{"spacing=0.025", "time.end_time=1.76"};
  std::string variable = "DUET_" + method + "_SET";
  for (char& c : variable) c = char(std::toupper(static_cast<unsigned char>(c)));
  if (const char* extra = std::getenv(variable.c_str())) {
    std::stringstream s(extra);
    for (std::string item; std::getline(s, item, ';');) out.push_back(item);
  }
  return out;
}

struct OedometerRun {
  Scene scene;
  RunSummary summary;
  std::vector<double> time, axial_stress, radial_stress, plate_displacement;
};

OedometerRun run_oedometer(const std::string& method) {
  OedometerRun r;
  r.scene = load_scene(std::string(DUET_SOURCE_DIR) + "/benchmarks/scenes/oedometer.toml",
                       overrides(method));
  MethodRegistry methods;
  sph::register_sph(methods);
  spfem::register_espfem(methods);
  // One folder per process: concurrent runs of this test (shared machines) do not mix files
  const auto dir = (std::filesystem::temp_directory_path() /
                    ("duet-" + method + "-oedometer-" + std::to_string(::getpid())))
                       .string();
  std::filesystem::remove_all(dir);
  r.summary = run_scene(r.scene, methods.find(method), RunOptions{dir, false});
  const std::string h5 = dir + "/run.h5";
  r.time = read_series(h5, "time");
  r.axial_stress = read_series(h5, "axial_stress");
  r.radial_stress = read_series(h5, "radial_stress");
  r.plate_displacement = read_series(h5, "plate_displacement");
  std::printf("oedometer, %s: dp %.3f m, %ld particles, %ld steps, %.1f s wall, in %s\n",
              method.c_str(), r.scene.spacing, r.summary.particles, r.summary.steps,
              r.summary.wall_seconds, dir.c_str());
  return r;
}

/// Element test of the scene's material along the oedometric path from its isotropic start.
std::vector<constitutive::ElementRow> element_curve(const Scene& scene, double strain) {
  const Material& m = scene.materials.front();
  const auto model = constitutive::make_model(m.model, m.parameters, "material." + m.name);
  constitutive::ElementTest test;
  test.kind = constitutive::ElementTestKind::oedometer;
  test.initial_stress = -scene.initial_stress.pressure;
  test.strain = -strain;
  test.increments = static_cast<int>(std::ceil(strain / 5e-5));
  return constitutive::run_element_test(*model, test);
}

/// sigma_yy of the element curve at (negative) axial strain eps, log-linear between rows (the
/// curve is close to exponential).
double element_axial_stress(const std::vector<constitutive::ElementRow>& rows, double eps) {
  for (std::size_t k = 1; k < rows.size(); ++k) {
    if (rows[k].axial_strain <= eps) {
      const auto& a = rows[k - 1];
      const auto& b = rows[k];
      const double s = (eps - a.axial_strain) / (b.axial_strain - a.axial_strain);
      return -std::exp(std::log(-a.axial_stress) +
                       s * (std::log(-b.axial_stress) - std::log(-a.axial_stress)));
    }
  }
  return std::nan("");
}

/// K0 in loading: the scene's score, sigma_3 / sigma_1 at the end of loading, within 2 % of eq 38.
void expect_k0_within_two_percent(const OedometerRun& run) {
  const Accuracy& k0 = run.summary.accuracy.at("K0");
  // The plate's last recorded displacement in loading gives the element test's strain
  double displacement = 0.0;
  for (std::size_t k = 0; k < run.time.size() && run.time[k] <= kEndOfLoading + 1e-9; ++k) {
    displacement = run.plate_displacement[k];
  }
  const auto rows = element_curve(run.scene, -std::log(1.0 + displacement / kHeight));
  std::printf("K0 %.4f (eq 38: %.4f, error %.2f %%; element test at the same strain %.4f)\n",
              k0.value, k0.reference, 100 * k0.rel_error,
              rows.back().lateral_stress / rows.back().axial_stress);
  EXPECT_LT(k0.rel_error, 0.02);
}

class OedometerBenchmark : public ::testing::TestWithParam<std::string> {};

// One test per method, so each runs the scene once (CTest runs every test in its own process).
TEST_P(OedometerBenchmark, LoadingCurveWithinFivePercentOfTheElementTestAndK0WithinTwoPercent) {
  // Arrange
  const OedometerRun run = run_oedometer(GetParam());
  ASSERT_TRUE(run.summary.completed())
      << run.summary.failure_reason << " at t = " << run.summary.failure_time;
  const auto rows = element_curve(run.scene, 0.018);
  // Act: the relative deviation at every recorded sample of the loading
  double worst = 0.0, worst_at = 0.0, worst_transient = 0.0, worst_transient_at = 0.0;
  long samples = 0;
  for (std::size_t k = 1; k < run.time.size(); ++k) {
    if (run.time[k] > kEndOfLoading + 1e-9) break;
    // Tension positive: the soil pushes the plate up, sigma_yy = -force_y / width
    const double eps = std::log(1.0 + run.plate_displacement[k] / kHeight);
    const double sigma_run = -run.axial_stress[k];
    const double sigma_element = element_axial_stress(rows, eps);
    const double deviation = std::abs(sigma_run - sigma_element) / std::abs(sigma_element);
    if (-eps < kTransientStrain) {
      if (deviation > worst_transient) worst_transient = deviation, worst_transient_at = -eps;
    } else {
      ++samples;
      if (deviation > worst) worst = deviation, worst_at = -eps;
    }
  }
  std::printf(
      "axial stress vs element curve: worst %.2f %% at strain %.4f %% over %ld samples from "
      "%.2f %%; below it (wave transients) worst %.2f %% at %.4f %%\n",
      100 * worst, 100 * worst_at, samples, 100 * kTransientStrain, 100 * worst_transient,
      100 * worst_transient_at);
  // Assert
  EXPECT_GT(samples, 100);
  EXPECT_LT(worst, 0.05);
  expect_k0_within_two_percent(run);
}

INSTANTIATE_TEST_SUITE_P(Methods, OedometerBenchmark, ::testing::Values("sph", "espfem"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

}  // namespace
}  // namespace duet
