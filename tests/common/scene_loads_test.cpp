// Scene loads on particles (common/scene_loads.cpp): a load's total force is shared equally by
// the particles of its body in its box, so the shares sum to the scheduled total.
#include <gtest/gtest.h>

#include "common/input_error.hpp"
#include "common/lattice.hpp"
#include "common/scene_loader.hpp"
#include "common/scene_loads.hpp"

namespace duet {
namespace {

// A 0.1 m x 0.05 m block at spacing 0.01 (50 particles), loaded on its last column (x > 0.09).
Scene loaded_block(const std::string& box_min) {
  return load_scene_from_string(R"(
name = "block"
spacing = 0.01
[time]
end_time = 1.0
[material.soil]
model = "linear-elastic"
density = 1000.0
E = 1e7
nu = 0.3
[body.block]
material = "soil"
shape = "rectangle"
min = [0.0, 0.0]
max = [0.1, 0.05]
[load.tip]
body = "block"
min = )" + box_min + R"(
max = [0.1, 0.05]
force = [[0.0, 0.0, 0.0], [1.0, 0.0, -100.0]]
)",
                                "block.toml");
}

TEST(SceneLoads, SharesOfALoadSumToItsScheduledTotal) {
  // Arrange
  const Scene scene = loaded_block("[0.09, 0.0]");
  const Particles particles = sample_bodies(scene);
  std::vector<Vec2> force(particles.size());
  // Act
  const LoadedParticles loaded = loaded_particles(scene, particles);
  apply_loads(scene, loaded, 0.5, force);
  // Assert: the five particles of the last column carry -50 N/m between them, equally
  ASSERT_EQ(loaded.at(0).size(), 5u);
  Vec2 total = Vec2::Zero();
  for (std::size_t i = 0; i < force.size(); ++i) {
    total += force[i];
    const bool carries = particles.position[i].x() > 0.09;
    EXPECT_NEAR(force[i].y(), carries ? -10.0 : 0.0, 1e-12);
  }
  EXPECT_NEAR(total.y(), -50.0, 1e-12);
  EXPECT_EQ(total.x(), 0.0);
}

TEST(SceneLoads, BoxWithoutParticlesIsRefusedNamingTheLoad) {
  // Arrange
  const Scene scene = loaded_block("[0.0999, 0.0]");
  const Particles particles = sample_bodies(scene);
  // Act / Assert
  EXPECT_THROW(
      {
        try {
          loaded_particles(scene, particles);
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("load.tip"), std::string::npos);
          throw;
        }
      },
      InputError);
}

}  // namespace
}  // namespace duet
