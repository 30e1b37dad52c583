// The unit hints of the model registry: legal values that are almost surely in the wrong unit.
#include <gtest/gtest.h>

#include "constitutive/registry.hpp"

namespace duet::constitutive {
namespace {

std::map<std::string, ParameterValue> resolved_of(const std::string& model,
                                                  std::map<std::string, ParameterValue> values) {
  std::map<std::string, ParameterValue> resolved;
  make_model(model, std::move(values), "material.m", &resolved);
  return resolved;
}

TEST(ImplausibleParameters, RadiansMegapascalsAndTonnesAreNamedWithWhatWasMeant) {
  const auto resolved = resolved_of(
      "drucker-prager", {{"E", 10.0}, {"nu", 0.3}, {"phi", 0.5}, {"psi", 0.0}, {"c", 5.0}});
  const auto w = implausible_parameters(resolved, 1.8, "material.m");
  ASSERT_EQ(w.size(), 4u);
  EXPECT_EQ(w[0], "material.m.phi = 0.5: looks like radians (28.6 deg); angles are in degrees");
  EXPECT_NE(w[1].find("material.m.E = 10: softer than any soil"), std::string::npos) << w[1];
  EXPECT_NE(w[2].find("material.m.c = 5: below 100 Pa"), std::string::npos) << w[2];
  EXPECT_NE(w[3].find("material.m.density = 1.8"), std::string::npos) << w[3];
}

TEST(ImplausibleParameters, TheBenchmarkMaterialsSayNothing) {
  // collapse-bui's bars and footing's clay
  EXPECT_TRUE(
      implausible_parameters(
          resolved_of("drucker-prager",
                      {{"E", 5.84e6}, {"nu", 0.3}, {"phi", 19.8}, {"psi", 0.0}, {"c", 0.0}}),
          2650.0, "material.bars")
          .empty());
  EXPECT_TRUE(
      implausible_parameters(resolved_of("tresca", {{"E", 1.0e6}, {"nu", 0.497}, {"cu", 1.0e4}}),
                             1800.0, "material.clay")
          .empty());
}

}  // namespace
}  // namespace duet::constitutive
