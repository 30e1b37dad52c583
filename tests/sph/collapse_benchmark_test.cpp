// Collapse benchmarks through the driver, scored against the Lube et al. run-out law as the scenes
// state it (d_inf = 0.36 m for a = 0.5): Peng 2015 5.2 (hypoplastic sand) at dp = 5 mm (800
// particles; the run-out is the toe where the deposit is two spacings thick, which dp = 1 cm cannot
// resolve), which must also come to rest, and Bui 2008 (Drucker-Prager aluminium bars) at dp = 1
// cm, both with the scenes' [sph].
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "benchmarks/driver.hpp"
#include "common/scene_loader.hpp"
#include "sph/method.hpp"

namespace duet {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The number after "key": in the metrics text (-1 when absent).
long metrics_count(const std::string& metrics, const std::string& key) {
  const auto at = metrics.find("\"" + key + "\":");
  if (at == std::string::npos) return -1;
  return std::stol(metrics.substr(at + key.size() + 3));
}

/// The number after "key": in the metrics text (NaN when absent).
double metrics_number(const std::string& metrics, const std::string& key) {
  const auto at = metrics.find("\"" + key + "\":");
  if (at == std::string::npos) return std::nan("");
  return std::stod(metrics.substr(at + key.size() + 3));
}

RunSummary run_collapse(const std::string& scene_file, const std::vector<std::string>& overrides,
                        const std::string& out) {
  const Scene scene =
      load_scene(std::string(DUET_SOURCE_DIR) + "/benchmarks/scenes/" + scene_file, overrides);
  MethodRegistry methods;
  sph::register_sph(methods);
  const auto dir = (std::filesystem::temp_directory_path() / out).string();
  std::filesystem::remove_all(dir);
  return run_scene(scene, methods.find("sph"), RunOptions{dir, false});
}

TEST(CollapseBenchmark, DruckerPragerBarsRunOutWithoutPenetration) {
  // Arrange / Act: Bui 2008 uses leapfrog; the same code path as the sand, another model
  const RunSummary run =
      run_collapse("collapse-bui.toml", {"spacing=0.01", "sph.integrator=leapfrog", "sph.cfl=0.2"},
                   "duet-sph-collapse-bui");
  // Assert
  ASSERT_TRUE(run.completed()) << run.failure_reason << " at t = " << run.failure_time;
  const Accuracy& runout = run.accuracy.at("runout");
  std::printf("run-out %.4f m (reference %.3f), %ld steps, %.1f s\n", runout.value,
              runout.reference, run.steps, run.wall_seconds);
  // Issue 5 asks for the Bui run-out to be reported against the Lube law, not scored: at this
  // smoke resolution it is coarse (0.355 m at dp = 1 cm, the 1 cm deep front; 0.36 m at 2-5 mm).
  // What must hold is that the column slumped: it spread beyond its initial 0.2 m and lost height.
  EXPECT_GT(runout.value, 0.2);
  EXPECT_LT(run.measures.at("height"), 0.1);
  EXPECT_EQ(metrics_count(read_text(run.out_dir + "/metrics.json"), "penetrations_max"), 0);
}

TEST(CollapseBenchmark, HypoplasticSandAtFiveMillimetresRunsOutWithinFifteenPercentAndComesToRest) {
  // Arrange / Act: the scene's [sph] settings (leapfrog, CFL 0.4, c_s = 100 m/s, dummies with the
  // extrapolated velocity and Bui's stress) at the coarse spacing, run to 1.2 s: measured
  // run-out 0.3099 m (-13.9 %) from 0.8 s on, kinetic energy 1.3e-6 of its peak at 1.05 s and
  // 5.9e-7 at 1.2 s (dp 2 mm: 0.3759 m, 4e-7 at 1 s). With the wall's velocity and sigma_max
  // the deposit crept (1.2e-5 at 1 s) and ran out 0.3015 m (-16.3 %).
  const RunSummary run = run_collapse("collapse.toml", {"spacing=0.005", "time.end_time=1.2"},
                                      "duet-sph-collapse-5mm-" + std::to_string(::getpid()));
  // Assert
  ASSERT_TRUE(run.completed()) << run.failure_reason << " at t = " << run.failure_time;
  const Accuracy& runout = run.accuracy.at("runout");
  const std::string metrics = read_text(run.out_dir + "/metrics.json");
  const double at_rest = metrics_number(metrics, "end_over_peak");
  std::printf(
      "run-out %.4f m (reference %.3f, error %.1f %%), kinetic energy at the end %.2e of its "
      "peak, %ld steps, %.1f s\n",
      runout.value, runout.reference, 100 * runout.rel_error, at_rest, run.steps, run.wall_seconds);
  EXPECT_LT(runout.rel_error, 0.15);
  EXPECT_EQ(metrics_count(metrics, "penetrations_max"), 0);
  // Issue 5: the final deposit is at rest, kinetic energy below 1e-6 of its peak
  EXPECT_LT(at_rest, 1e-6);
}

TEST(CollapseBenchmark, TheBarsFallWithoutArtificialViscosityBetweenBuisDummiesAndMakeNoEnergy) {
  // Arrange / Act: collapse-bui's [sph] (Bui's dummy stress, extrapolated velocity) with no
  // artificial viscosity at all, to t = 0.3 s (the flow's fast part; at dp 1 cm a particle later
  // slips through the free-slip back wall, at dp 2 mm alpha 0 loses one there at 0.12 s).
  const RunSummary run = run_collapse(
      "collapse-bui.toml", {"spacing=0.01", "sph.alpha=0", "sph.beta=0", "time.end_time=0.3"},
      "duet-sph-collapse-bui-inviscid-" + std::to_string(::getpid()));
  // Assert: no energy is made: the kinetic energy stays below the work gravity has done (the
  // driver's check fails a run at twice that). A Coulomb wedge sliding on the Rankine plane,
  // 45 + phi/2 (54.9 deg), turns 1 - tan(phi) / tan(45 + phi/2) = 0.747 of its fall into motion;
  // the column, sheared inside as well, turns a little less (measured 0.68 here, espfem 0.72), and
  // a viscous SPH much less (alpha 1: 0.48 with Peng's dummies). Peng's sigma_max dummies, which
  // give the toe's dummies the most compressive stress of its neighbours, made twice the energy
  // put in by t = 0.01 s without viscosity.
  ASSERT_TRUE(run.completed()) << run.failure_reason << " at t = " << run.failure_time;
  const std::string metrics = read_text(run.out_dir + "/metrics.json");
  const double share = metrics_number(metrics, "kinetic_over_input_max");
  const double phi = 19.8 * std::numbers::pi / 180.0;
  const double wedge = 1.0 - std::tan(phi) / std::tan(0.25 * std::numbers::pi + 0.5 * phi);
  std::printf("largest kinetic energy over the energy put in: %.3f (Coulomb wedge %.3f)\n", share,
              wedge);
  EXPECT_LT(share, 1.0);
  EXPECT_GT(share, 0.8 * wedge);

  const RunSummary peng =
      run_collapse("collapse-bui.toml",
                   {"spacing=0.01", "sph.alpha=0", "sph.beta=0", "sph.wall_stress=sigma-max",
                    "time.end_time=0.3"},
                   "duet-sph-collapse-bui-inviscid-peng-" + std::to_string(::getpid()));
  EXPECT_EQ(peng.status, "failed") << "Peng's dummies no longer make energy here: update";
  EXPECT_NE(peng.failure_reason.find("made energy"), std::string::npos) << peng.failure_reason;
}

}  // namespace
}  // namespace duet
