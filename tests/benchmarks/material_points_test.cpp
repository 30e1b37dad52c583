// The initial state every method starts from (benchmarks/material_points.cpp): the scene's initial
// stress on every particle, checked against its closed form.
#include <gtest/gtest.h>

#include <string>

#include "benchmarks/material_points.hpp"
#include "common/lattice.hpp"
#include "common/scene_loader.hpp"

namespace duet {
namespace {

// A 0.1 m x 0.05 m block of 1000 kg/m^3 at spacing 0.01 under g = 10 m/s^2.
std::string block_scene(const std::string& initial_stress) {
  return R"(
name = "block"
spacing = 0.01
gravity = [0.0, -10.0]
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
[wall.floor]
points = [[-0.1, 0.0], [0.2, 0.0]]
[initial_stress]
)" + initial_stress;
}

TEST(MaterialPoints, IsotropicInitialStressIsMinusThePressureOnEveryParticle) {
  // Arrange
  const Scene scene =
      load_scene_from_string(block_scene("kind = \"isotropic\"\npressure = 1.0e4\n"), "block.toml");
  Particles particles = sample_bodies(scene);
  // Act
  initialise_material_points(scene, particles);
  // Assert
  ASSERT_EQ(particles.size(), 50u);
  for (const Mat3& s : particles.stress) {
    EXPECT_DOUBLE_EQ((s + 1.0e4 * Mat3::Identity()).norm(), 0.0);
  }
}

TEST(MaterialPoints, StoredElasticEnergyOfAnIsotropicStressIsVolumeTimesPSquaredOverTwoK) {
  const Scene scene =
      load_scene_from_string(block_scene("kind = \"isotropic\"\npressure = 1.0e4\n"), "block.toml");
  Particles particles = sample_bodies(scene);
  EXPECT_EQ(stored_elastic_energy(scene, particles), 0.0);  // no stress yet
  initialise_material_points(scene, particles);
  // K = E / (3 (1 - 2 nu)) = 1e7 / 1.2; no deviator; V = 0.1 x 0.05 m^2.
  const double bulk = 1.0e7 / 1.2;
  EXPECT_NEAR(stored_elastic_energy(scene, particles), 0.005 * 1.0e8 / (2.0 * bulk), 1e-15);
}

TEST(MaterialPoints, StoredElasticEnergyOfAUniaxialStressIsSigmaSquaredOverTwoE) {
  // sigma = -q e_y e_y: p^2 / 2K + s:s / 4G = q^2 / 18K + q^2 / 6G = q^2 / 2E (uniaxial stress).
  const Scene scene = load_scene_from_string(block_scene("kind = \"none\"\n"), "block.toml");
  Particles particles = sample_bodies(scene);
  initialise_material_points(scene, particles);
  const double q = 2.0e4;
  for (Mat3& s : particles.stress) s(1, 1) = -q;
  EXPECT_NEAR(stored_elastic_energy(scene, particles), 0.005 * q * q / (2.0 * 1.0e7), 1e-15);
}

TEST(MaterialPoints, GeostaticStressIsTheOverburdenWithK0Sideways) {
  // Arrange
  const Scene scene =
      load_scene_from_string(block_scene("kind = \"geostatic\"\nK0 = 0.5\n"), "block.toml");
  Particles particles = sample_bodies(scene);
  // Act
  initialise_material_points(scene, particles);
  // Assert: sigma_v = -rho g (0.05 - y), sigma_h = sigma_zz = K0 sigma_v
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const double sigma_v = -1000.0 * 10.0 * (0.05 - particles.position[i].y());
    EXPECT_NEAR(particles.stress[i](1, 1), sigma_v, 1e-9);
    EXPECT_NEAR(particles.stress[i](0, 0), 0.5 * sigma_v, 1e-9);
    EXPECT_NEAR(particles.stress[i](2, 2), 0.5 * sigma_v, 1e-9);
    EXPECT_EQ(particles.stress[i](0, 1), 0.0);
  }
}

}  // namespace
}  // namespace duet
