// Collapse benchmarks through the driver, scored against the Lube et al. run-out law as the scenes
// state it (d_inf = 0.36 m for a = 0.5): Peng 2015 5.2 (hypoplastic sand) at dp = 4 mm (1250
// particles; the run-out is the toe where the deposit is two spacings thick, which dp = 1 cm cannot
// resolve) and Bui 2008 (Drucker-Prager aluminium bars) at dp = 1 cm, both with the scenes' [sph].
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "benchmarks/driver.hpp"
#include "common/h5_writer.hpp"
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

/// Kinetic energy (J/m) between successive frames, from the displacement over the frame
/// interval (frames hold no velocity): one value per pair of frames.
std::vector<double> frame_kinetic_energy(const std::string& h5) {
  std::vector<double> energy;
  const std::size_t n = count_frames(h5);
  Frame previous = read_frame(h5, 0);
  const std::vector<double> mass = previous.scalars.at("mass");  // a copy: previous is reassigned
  for (std::size_t k = 1; k < n; ++k) {
    Frame frame = read_frame(h5, k);
    const double dt = frame.time - previous.time;
    if (dt > 0.0) {
      double e = 0.0;
      for (std::size_t i = 0; i < mass.size(); ++i) {
        e += 0.5 * mass[i] * (frame.position[i] - previous.position[i]).squaredNorm() / (dt * dt);
      }
      energy.push_back(e);
    }
    previous = std::move(frame);
  }
  return energy;
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
  // smoke resolution the 3-spacing thickness rule cuts the thin toe (measured 0.26 m at dp = 1 cm).
  // What must hold is that the column slumped: it spread beyond its initial 0.2 m and lost height.
  EXPECT_GT(runout.value, 0.2);
  EXPECT_LT(run.measures.at("height"), 0.1);
  EXPECT_EQ(metrics_count(read_text(run.out_dir + "/metrics.json"), "penetrations_max"), 0);
}

TEST(CollapseBenchmark, HypoplasticSandAtFourMillimetresRunsOutWithinFifteenPercent) {
  // Arrange / Act: the scene's [sph] settings (leapfrog, CFL 0.4, c_s = 100 m/s) at the coarsest
  // spacing the run-out has converged to within the scene's 15 %: measured (duet compare, RESULTS)
  // 0.3015 m at dp = 5 mm (-16.3 %), 0.3336 m at 4 mm, 0.3559 m at 3.5 mm, 0.3669 m at 2.5 mm,
  // 0.3833 m at 2 mm. At 5 mm the column is 20 particles high and its toe two.
  const RunSummary run = run_collapse("collapse.toml", {"spacing=0.004"},
                                      "duet-sph-collapse-4mm-" + std::to_string(::getpid()));
  // Assert
  ASSERT_TRUE(run.completed()) << run.failure_reason << " at t = " << run.failure_time;
  const Accuracy& runout = run.accuracy.at("runout");
  const auto energy = frame_kinetic_energy(run.out_dir + "/run.h5");
  const double peak = *std::max_element(energy.begin(), energy.end());
  std::printf(
      "run-out %.4f m (reference %.3f, error %.1f %%), kinetic energy at the end %.2e of "
      "its peak %.3e J/m, %ld steps, %.1f s\n",
      runout.value, runout.reference, 100 * runout.rel_error, energy.back() / peak, peak, run.steps,
      run.wall_seconds);
  EXPECT_LT(runout.rel_error, 0.15);
  EXPECT_EQ(metrics_count(read_text(run.out_dir + "/metrics.json"), "penetrations_max"), 0);
  // Not asserted: the "at rest" (kinetic energy below 1e-6 of its peak) is not reached at
  // 1 s; the deposit creeps (measured 1.2e-5 of the peak at dp 5 mm and at dp 2 mm; RESULTS).
}

}  // namespace
}  // namespace duet
