// The unit hints of the model registry: legal values that are almost surely in the wrong unit.
#include <gtest/gtest.h>

#include <optional>

#include "common/input_error.hpp"
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
  EXPECT_EQ(w[0].message,
            "material.m.phi = 0.5: looks like radians (28.6 deg); angles are in degrees");
  EXPECT_NE(w[1].message.find("material.m.E = 10: a modulus below 10 kPa, softer than any soil"),
            std::string::npos)
      << w[1].message;
  EXPECT_NE(w[2].message.find("material.m.c = 5: below 100 Pa"), std::string::npos) << w[2].message;
  EXPECT_NE(w[3].message.find("material.m.density = 1.8"), std::string::npos) << w[3].message;
}

/// Whether `name` = `value` is refused (true), said (false) or passes (nullopt) in `model`.
std::optional<bool> doubt_of(const std::string& model, std::map<std::string, ParameterValue> values,
                             const std::string& name) {
  for (const UnitDoubt& d :
       implausible_parameters(resolved_of(model, std::move(values)), 1800.0, "material.m")) {
    if (d.message.starts_with("material.m." + name + " = ")) return d.refused;
  }
  return std::nullopt;
}

TEST(ImplausibleParameters, MegapascalsAndKilopascalsWrittenInPascalsAreRefused) {
  const auto dp = [](double E, double c) {
    return std::map<std::string, ParameterValue>{
        {"E", E}, {"nu", 0.3}, {"phi", 30.0}, {"psi", 0.0}, {"c", c}};
  };
  // issue 44: E = 20 meant in MPa
  EXPECT_EQ(doubt_of("drucker-prager", dp(20.0, 0.0), "E"), true);
  EXPECT_EQ(doubt_of("drucker-prager", dp(9999.0, 0.0), "E"), true);
  EXPECT_EQ(doubt_of("drucker-prager", dp(5e4, 0.0), "E"), false);  // said: kPa?
  EXPECT_EQ(doubt_of("drucker-prager", dp(1e5, 0.0), "E"), std::nullopt);
  EXPECT_EQ(doubt_of("drucker-prager", dp(1e7, 0.01), "c"), true);  // 10 kPa in MPa
  EXPECT_EQ(doubt_of("drucker-prager", dp(1e7, 5.0), "c"), false);  // a few Pa can be meant
  const auto tresca = [](double cu) {
    return std::map<std::string, ParameterValue>{{"E", 1e7}, {"nu", 0.49}, {"cu", cu}};
  };
  EXPECT_EQ(doubt_of("tresca", tresca(50.0), "cu"), true);  // 50 kPa in kPa
  EXPECT_EQ(doubt_of("tresca", tresca(500.0), "cu"), false);
  EXPECT_EQ(doubt_of("tresca", tresca(1e3), "cu"), std::nullopt);
  // simhypo-sand's stiffness is E_i
  std::map<std::string, ParameterValue> sand = builtin_models().find("simhypo-sand").example;
  sand["E_i"] = 40.0;
  EXPECT_EQ(doubt_of("simhypo-sand", sand, "E_i"), true);
}

TEST(ParameterRanges, ADilatancyAboveFrictionIsRefusedWithTheRuleAndItsNumbers) {
  try {
    make_model("drucker-prager",
               {{"E", 1e7}, {"nu", 0.3}, {"phi", 30.0}, {"psi", 35.0}, {"c", 0.0}}, "material.m");
    FAIL() << "psi > phi accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("material.m.psi = 35: dilatancy angle (at most phi) must "
                                         "lie in [0, phi] = [0, 30] (unit deg)"),
              std::string::npos)
        << e.what();
  }
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
