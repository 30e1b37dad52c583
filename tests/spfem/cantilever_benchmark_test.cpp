// Large-deflection elastic cantilever (benchmarks/scenes/cantilever.toml, P L^2 / EI = 1) through
// the explicit SPFEM with the scene's stiffness stabilisation (spfem.stiffness_stabilisation):
// the tip deflection within 3 % of the elastica at the scene's resolution, dp = 0.01 m (10 nodes
// across the beam). Without the stabilisation nodal integration leaves the beam +4.9 % too
// deflected there (spfem/README.md, "Stiffness stabilisation").
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <string>

#include "benchmarks/driver.hpp"
#include "common/scene_loader.hpp"
#include "spfem/method.hpp"

namespace duet {
namespace {

TEST(CantileverBenchmark, TipDeflectionWithinThreePercentOfTheElasticaAtTenNodesAcross) {
  // Arrange: the scene as it is, stopped at 3 s instead of 4 s: the load is ramped over 2 s and
  // held, and with the scene's damping (10 1/s) the tip deflection at 3 s is within 0.03 % of
  // that at 4 s (measured: 0.30244 against 0.30238 m)
  const Scene scene = load_scene(
      std::string(DUET_SOURCE_DIR) + "/benchmarks/scenes/cantilever.toml", {"time.end_time=3.0"});
  ASSERT_GT(scene.spfem.stiffness_stabilisation, 0.0);
  MethodRegistry methods;
  spfem::register_espfem(methods);
  const auto dir = (std::filesystem::temp_directory_path() /
                    ("duet-espfem-cantilever-" + std::to_string(::getpid())))
                       .string();
  std::filesystem::remove_all(dir);
  // Act
  const RunSummary run = run_scene(scene, methods.find("espfem"), RunOptions{dir, false});
  // Assert: reference v / L = 0.30172 (elastica, Bisshopp & Drucker 1945; the scene's reference)
  ASSERT_TRUE(run.completed()) << run.failure_reason << " at t = " << run.failure_time;
  const Accuracy& tip = run.accuracy.at("tip");
  std::printf("tip deflection %.5f m (reference %.5f), %+.2f %%, %ld steps, %.1f s\n", tip.value,
              tip.reference, 100.0 * (tip.value - tip.reference) / tip.reference, run.steps,
              run.wall_seconds);
  EXPECT_LT(tip.rel_error, 0.03);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace duet
