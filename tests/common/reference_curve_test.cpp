// Reference curves (common/reference_curve.hpp): the CSV reader and its refusals, interpolation,
// the score of a series over a window of its abscissa, and a scene's curve reference carried
// into the run's own resolved scene (so --resume scores against the same curve without the file).
#include "common/reference_curve.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "benchmarks/scene_input.hpp"
#include "common/input_error.hpp"
#include "common/measures.hpp"
#include "tests/common/column_scene.hpp"

namespace duet {
namespace {

std::string write_file(const std::string& name, const std::string& text) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("duet-reference-curve-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / name).string();
  std::ofstream(path) << text;
  return path;
}

const char* kCsv =
    "# source: a test curve\n"
    "# holds: x 0 to 0.1\n"
    "w_over_B,q_over_cu\n"
    "0.0,0.0\n"
    "0.05,4.0\n"
    "0.1,5.0\n";

std::string refusal_of_csv(const std::string& text) {
  try {
    read_reference_csv(write_file("bad.csv", text));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ReferenceCurve, ReadsRowsAfterTheCommentsAndTheHeader) {
  const std::vector<Vec2> curve = read_reference_csv(write_file("good.csv", kCsv));
  ASSERT_EQ(curve.size(), 3u);
  EXPECT_DOUBLE_EQ(curve[1].x(), 0.05);
  EXPECT_DOUBLE_EQ(curve[2].y(), 5.0);
}

TEST(ReferenceCurve, RefusesRowsThatAreNotTwoNumbersOrXNotIncreasingNamingTheLine) {
  EXPECT_NE(refusal_of_csv("x,y\n0,1\n0.1,2,3\n").find("bad.csv:3:"), std::string::npos);
  EXPECT_NE(refusal_of_csv("x,y\n0,1\n0.1,abc\n").find("two numbers"), std::string::npos);
  EXPECT_NE(refusal_of_csv("x,y\n0,1\n0.2,2\n0.1,3\n").find("bad.csv:4:"), std::string::npos);
  EXPECT_NE(refusal_of_csv("x,y\n0,1\n").find("at least two rows"), std::string::npos);
  EXPECT_THROW(read_reference_csv("/nonexistent/curve.csv"), InputError);
}

TEST(ReferenceCurve, InterpolatesLinearlyAndIsUndefinedOutside) {
  const std::vector<Vec2> curve{{0.0, 0.0}, {0.05, 4.0}, {0.1, 5.0}};
  EXPECT_NEAR(curve_value(curve, 0.025), 2.0, 1e-14);
  EXPECT_NEAR(curve_value(curve, 0.075), 4.5, 1e-14);
  EXPECT_DOUBLE_EQ(curve_value(curve, 0.1), 5.0);
  EXPECT_TRUE(std::isnan(curve_value(curve, 0.11)));
  EXPECT_TRUE(std::isnan(curve_value(curve, -0.01)));
}

TEST(ReferenceCurve, AScoreIsTheLargestRelativeErrorInTheWindowWithItsSignAndPlace) {
  // The reference curve with +4 % at x = 0.06 (a tent of errors from 0.04 to 0.08), -10 % before
  // the window (not scored), sampled every 0.005.
  const std::vector<Vec2> curve{{0.0, 0.0}, {0.05, 4.0}, {0.1, 5.0}};
  std::vector<double> x, y;
  for (int k = 0; k <= 20; ++k) {
    const double at = 0.005 * k;
    const double tent = std::max(0.0, 0.04 - std::abs(at - 0.06));
    x.push_back(at);
    y.push_back(curve_value(curve, at) * (at < 0.03 ? 0.9 : 1.0 + tent));
  }
  const CurveScore score = score_curve(x, y, Vec2(0.03, 0.1), curve, 0.0);
  EXPECT_NEAR(score.rel_error, 0.04, 1e-12);
  EXPECT_NEAR(score.signed_error, 0.04, 1e-12);
  EXPECT_NEAR(score.worst_at, 0.06, 1e-12);
  EXPECT_EQ(score.points, 15);  // 0.03 .. 0.1 every 0.005
  // Below the reference the sign says so; against a constant the constant is the reference.
  for (double& v : y) v = 5.0 * 0.97;
  EXPECT_NEAR(score_curve(x, y, Vec2(0.02, 0.05), {}, 5.0).signed_error, -0.03, 1e-12);
}

TEST(ReferenceCurve, ASeriesThatStopsShortOfTheWindowIsNotScored) {
  const std::vector<Vec2> curve{{0.0, 1.0}, {0.1, 1.0}};
  const CurveScore score =
      score_curve({0.0, 0.02, 0.04}, {1.0, 1.0, 1.0}, Vec2(0.03, 0.1), curve, 0.0);
  EXPECT_TRUE(std::isnan(score.rel_error));
  // No sign, place or mean either (compare.md would print "+0.0 % at 0" for a zero)
  EXPECT_TRUE(std::isnan(score.signed_error));
  EXPECT_TRUE(std::isnan(score.worst_at));
  EXPECT_TRUE(std::isnan(score.mean_error));
  EXPECT_NEAR(score.reached, 0.04, 1e-15);
}

const std::string kScene = test::kColumnScene + R"(
[measure.sideways]
kind = "max_displacement"
target = "column"
component = "x"
at = "series"

[measure.down]
kind = "max_displacement"
target = "column"
component = "y"
at = "curve"
abscissa = "sideways"
x_window = [0.03, 0.1]

[reference.down]
curve = "good.csv"
source = "a test curve"
tolerance = 0.05
)";

std::string refusal(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    load_scene_checked_from_string(text, write_file("scene.toml", text), overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ReferenceCurve, ASceneReadsItsCurveBesideItAndItsResolvedCopyCarriesThePoints) {
  write_file("good.csv", kCsv);
  const std::string path = write_file("scene.toml", kScene);
  const Scene scene = load_scene_checked_from_string(kScene, path);
  ASSERT_EQ(scene.references.size(), 1u);
  EXPECT_EQ(scene.references[0].curve.size(), 3u);
  EXPECT_DOUBLE_EQ(scene.references[0].holds.y(), 0.1);
  // What --resume reads (run.h5's copy, no folder beside it): the same curve.
  std::filesystem::remove(std::filesystem::path(path).parent_path() / "good.csv");
  const Scene again = load_scene_checked_from_string(scene.resolved_toml, "run.h5:/meta/scene");
  ASSERT_EQ(again.references[0].curve.size(), 3u);
  EXPECT_DOUBLE_EQ(again.references[0].curve[1].y(), 4.0);
  write_file("good.csv", kCsv);
}

TEST(ReferenceCurve, ACurveOnAMeasureThatIsNotACurveOrOutsideWhereItHoldsIsRefused) {
  write_file("good.csv", kCsv);
  std::string on_a_series = kScene;
  on_a_series.replace(on_a_series.find("[reference.down]"), 16, "[reference.sideways]");
  EXPECT_NE(refusal(on_a_series).find("not a curve"), std::string::npos) << refusal(on_a_series);
  EXPECT_NE(refusal(kScene, {"measure.down.x_window=[0.03, 0.12]"}).find("where the curve holds"),
            std::string::npos);
  EXPECT_NE(refusal(kScene, {"measure.down.abscissa=down"}).find("abscissa"), std::string::npos);
  EXPECT_NE(refusal(kScene, {"reference.down.value=1.0"}).find("given with value"),
            std::string::npos);
  EXPECT_NE(refusal(kScene, {"reference.down.curve=missing.csv"}).find("missing.csv"),
            std::string::npos);
}

TEST(ReferenceCurve, TheRecorderScoresACurveMeasureOverItsWindow) {
  // One particle moved along x = t, y = the reference curve at x with +2 % from x = 0.05 on.
  write_file("good.csv", kCsv);
  const Scene scene = load_scene_checked_from_string(kScene, write_file("scene.toml", kScene));
  MeasureRecorder recorder(scene);
  Particles p;
  p.resize(1);
  p.body[0] = 0;
  const std::vector<Vec2> curve = scene.references[0].curve;
  for (int k = 0; k <= 24; ++k) {
    const double x = 0.005 * k;
    const double y = curve_value(curve, std::min(x, 0.1)) * (x >= 0.05 ? 1.02 : 1.0);
    p.displacement[0] = Vec2(x, y);
    recorder.sample(x, p, {});
  }
  const Json accuracy = recorder.accuracy();
  const Json& down = *accuracy.find("down");
  EXPECT_NEAR(down.find("rel_error")->number(), 0.02, 1e-12);
  EXPECT_NEAR(down.find("value")->number(), 5.1, 1e-12);  // at the window's end, x = 0.1
  EXPECT_NEAR(down.find("reference")->number(), 5.0, 1e-12);
  EXPECT_TRUE(down.find("passed")->boolean());
  EXPECT_NEAR(recorder.final_value("down"), 5.1, 1e-12);
}

}  // namespace
}  // namespace duet
