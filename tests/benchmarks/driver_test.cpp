// The driver's loop, output and failure handling (benchmarks/driver.cpp), driven by a test-only
// solver that moves every particle ballistically (x += v dt, no forces), so every expected value
// is a closed form: the front of a block moving at v is x0 + v t.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "benchmarks/driver.hpp"
#include "common/h5_writer.hpp"
#include "common/input_error.hpp"
#include "common/scene_loader.hpp"

namespace duet {
namespace {

struct BallisticOptions {
  double dt = 0.01;
  long throw_at_step = -1;  // throw NumericalFailure at this step
  long nan_at_step = -1;    // write a NaN stress at this step
  long boost_at_step = -1;  // multiply every velocity by `boost` at this step (made energy)
  double boost = 1.0;
  bool throw_in_initialise = false;  // gravity loading that does not converge
};

class BallisticSolver final : public Solver {
 public:
  explicit BallisticSolver(BallisticOptions options) : options_(options) {}
  void initialise(const Scene&, Particles&) override {
    if (options_.throw_in_initialise) {
      throw NumericalFailure("gravity loading did not converge at gravity factor 0.9");
    }
  }
  double step(const Scene&, Particles& particles, double) override {
    ++steps_;
    if (steps_ == options_.throw_at_step) throw NumericalFailure("Newton did not converge", 7);
    for (std::size_t i = 0; i < particles.size(); ++i) {
      particles.position[i] += options_.dt * particles.velocity[i];
      particles.displacement[i] += options_.dt * particles.velocity[i];
    }
    if (steps_ == options_.nan_at_step) particles.stress[5](1, 1) = std::nan("");
    if (steps_ == options_.boost_at_step) {
      for (Vec2& v : particles.velocity) v *= options_.boost;
    }
    return options_.dt;
  }
  std::vector<Reaction> reactions() const override { return {}; }
  const Timers& timers() const override { return timers_; }

 private:
  BallisticOptions options_;
  long steps_ = 0;
  Timers timers_;
};

MethodInfo ballistic(BallisticOptions options) {
  return {"ballistic",
          "test-only rigid translation",
          [options](const Scene&) { return std::make_unique<BallisticSolver>(options); },
          /*dynamic=*/true,
          /*bytes_per_particle=*/2048.0,
          /*option_sections=*/{}};
}

// A 0.1 m x 0.05 m block at spacing 0.01 moving right at 0.1 m/s for 1 s.
const char* kScene = R"(
name = "moving-block"
spacing = 0.01
[time]
end_time = 1.0
output_interval = 0.1
[domain]
min = [-1.0, -1.0]
max = [2.0, 1.0]
[material.steel]
model = "linear-elastic"
density = 1000.0
E = 1e7
nu = 0.3
[body.block]
material = "steel"
shape = "rectangle"
min = [0.0, 0.0]
max = [0.1, 0.05]
initial_velocity = [0.1, 0.0]
[measure.front]
kind = "front"
target = "block"
[reference.front]
value = 0.195
source = "closed form: x0 + v t = 0.095 + 0.1 * 1.0"
)";

std::string out_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("duet_driver_test_" + name);
  std::filesystem::remove_all(dir);
  return dir.string();
}

std::string read_text(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

TEST(Driver, AMethodThatKeepsNoStateIsRefusedAResumeWithTheReason) {
  // A run of a method whose frames hold no state (the test solver keeps the default refusal)
  const Scene scene = load_scene_from_string(kScene, "moving-block.toml");
  RunOptions options{out_dir("no-state"), false};
  run_scene(scene, ballistic({}), options);
  EXPECT_NE(read_text(options.out_dir + "/metrics.json").find("\"resumable\": false"),
            std::string::npos);
  EXPECT_TRUE(read_state(options.out_dir + "/run.h5", 0).empty());
  // Act / Assert: resuming it is bad input naming the folder, the method and why
  options.resume = true;
  try {
    run_scene(scene, ballistic({}), options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(options.out_dir), std::string::npos) << message;
    EXPECT_NE(message.find("ballistic: this method does not save its state"), std::string::npos)
        << message;
  }
}

TEST(Driver, CompletedRunScoresItsMeasureAgainstTheReference) {
  const Scene scene = load_scene_from_string(kScene, "moving-block.toml");
  RunOptions options{out_dir("completed"), false};
  const RunSummary summary = run_scene(scene, ballistic({}), options);
  EXPECT_EQ(summary.status, "completed");
  EXPECT_EQ(summary.steps, 100);
  EXPECT_EQ(summary.particles, 50);
  EXPECT_NEAR(summary.measures.at("front"), 0.195, 1e-12);
  EXPECT_LT(summary.accuracy.at("front").rel_error, 1e-10);
  // Frames at t = 0, 0.1, ..., 1.0 (the final state coincides with the last output time).
  EXPECT_EQ(count_frames(options.out_dir + "/run.h5"), 11u);
  const std::string metrics = read_text(options.out_dir + "/metrics.json");
  EXPECT_NE(metrics.find("\"status\": \"completed\""), std::string::npos);
  EXPECT_NE(metrics.find("\"commit\""), std::string::npos);
}

TEST(Driver, ParticleCrossingAWallStopsTheRunAndKeepsItsFrames) {
  std::string text = kScene;
  text += "[wall.barrier]\npoints = [[0.1505, -0.5], [0.1505, 0.5]]\ncondition = \"no-slip\"\n";
  const Scene scene = load_scene_from_string(text, "moving-block.toml");
  RunOptions options{out_dir("crossing"), false};
  const RunSummary summary = run_scene(scene, ballistic({}), options);
  EXPECT_EQ(summary.status, "failed");
  EXPECT_NE(summary.failure_reason.find("crossed wall 'barrier'"), std::string::npos);
  // The front column (x0 = 0.095) passes x = 0.1505 after 0.555 s: at step 56 (t = 0.56).
  EXPECT_NEAR(summary.failure_time, 0.56, 1e-9);
  EXPECT_GE(count_frames(options.out_dir + "/run.h5"), 7u);  // 0 .. 0.5 and the failed state
}

TEST(Driver, ARadialWallOvertakingAParticleAtRestIsACrossing) {
  // A chorded arc of radius 0.4 m about (-0.5, 0.025) growing at 0.2 m/s; the block at rest.
  // Its vertex on the centre's row reaches the particle at (0.005, 0.025), 0.505 m from the
  // centre, at t = 0.525 s: at step 53 (t = 0.53 s). The particle never moves: only a test in
  // the wall's frame sees it.
  std::string text = kScene;
  text.replace(text.find("initial_velocity = [0.1, 0.0]"), 29, "initial_velocity = [0.0, 0.0]");
  text +=
      "[wall.piston]\npoints = [[-0.153590, -0.175], [-0.1, 0.025], [-0.153590, 0.225]]\n"
      "condition = \"free-slip\"\ncentre = [-0.5, 0.025]\nradial_velocity = [[0.0, 0.2]]\n";
  const Scene scene = load_scene_from_string(text, "moving-block.toml");
  RunOptions options{out_dir("radial-crossing"), false};
  const RunSummary summary = run_scene(scene, ballistic({}), options);
  EXPECT_EQ(summary.status, "failed");
  EXPECT_NE(summary.failure_reason.find("crossed wall 'piston'"), std::string::npos)
      << summary.failure_reason;
  EXPECT_NEAR(summary.failure_time, 0.53, 1e-9);
}

TEST(Driver, ParticleLeavingTheDomainIsAFailureWithTimeAndParticle) {
  std::string text = kScene;
  text.replace(text.find("max = [2.0, 1.0]"), 16, "max = [0.1505, 1.0]");
  const Scene scene = load_scene_from_string(text, "moving-block.toml");
  RunOptions options{out_dir("domain"), false};
  const RunSummary summary = run_scene(scene, ballistic({}), options);
  EXPECT_EQ(summary.status, "failed");
  EXPECT_NE(summary.failure_reason.find("left the domain"), std::string::npos);
  // The front particle (x0 = 0.095) passes x = 0.1505 after 0.555 s: at step 56 (t = 0.56).
  EXPECT_NEAR(summary.failure_time, 0.56, 1e-9);
  EXPECT_GE(count_frames(options.out_dir + "/run.h5"), 6u);  // 0 .. 0.5 and the failed state
  EXPECT_NE(read_text(options.out_dir + "/metrics.json").find("\"status\": \"failed\""),
            std::string::npos);
}

TEST(Driver, NonFiniteStressIsAFailure) {
  const Scene scene = load_scene_from_string(kScene, "moving-block.toml");
  RunOptions options{out_dir("nan"), false};
  const RunSummary summary = run_scene(scene, ballistic({.nan_at_step = 30}), options);
  EXPECT_EQ(summary.status, "failed");
  EXPECT_NE(summary.failure_reason.find("non-finite stress at particle 5"), std::string::npos);
  EXPECT_NEAR(summary.failure_time, 0.30, 1e-9);
}

TEST(Driver, SolverNumericalFailureIsReportedWithItsReason) {
  const Scene scene = load_scene_from_string(kScene, "moving-block.toml");
  RunOptions options{out_dir("newton"), false};
  const RunSummary summary = run_scene(scene, ballistic({.throw_at_step = 12}), options);
  EXPECT_EQ(summary.status, "failed");
  EXPECT_EQ(summary.failure_reason, "Newton did not converge");
  EXPECT_NEAR(summary.failure_time, 0.11, 1e-9);
  EXPECT_EQ(summary.steps, 11);
}

TEST(Driver, FailureBeforeTheClockStartsIsAFailedRunWithItsFrameAndMetrics) {
  // Gravity loading that does not converge (ispfem's settle threw out of initialise and ended the
  // program with exit 1, and a strength-reduction search with it).
  const Scene scene = load_scene_from_string(kScene, "moving-block.toml");
  RunOptions options{out_dir("initialise"), false};
  const RunSummary summary = run_scene(scene, ballistic({.throw_in_initialise = true}), options);
  EXPECT_EQ(summary.status, "failed");
  EXPECT_EQ(summary.failure_reason,
            "before the clock started: gravity loading did not converge at gravity factor 0.9");
  EXPECT_EQ(summary.failure_time, 0.0);
  EXPECT_EQ(summary.steps, 0);
  EXPECT_EQ(count_frames(options.out_dir + "/run.h5"), 1u);
  EXPECT_NE(read_text(options.out_dir + "/metrics.json").find("\"status\": \"failed\""),
            std::string::npos);
}

// The block carries 0.5 * 5 kg/m * (0.1 m/s)^2 = 0.025 J/m and nothing does work on it, so the
// energy put in stays 0.025 J/m. The floor of the check is 1e-6 M (L / T)^2 =
// 1e-6 * 5 * 13 = 6.5e-5 J/m (domain diagonal sqrt(3^2 + 2^2) m, 1 s).
TEST(Driver, KineticEnergyBeyondTwiceTheEnergyPutInIsAFailure) {
  const Scene scene = load_scene_from_string(kScene, "moving-block.toml");
  RunOptions options{out_dir("energy"), false};
  // Speed x3 at step 40: 0.225 J/m, 9 times the 0.025 J/m put in, above the floor.
  const RunSummary summary =
      run_scene(scene, ballistic({.boost_at_step = 40, .boost = 3.0}), options);
  EXPECT_EQ(summary.status, "failed");
  EXPECT_NE(summary.failure_reason.find("kinetic energy 0.225 J/m exceeds 2 x the energy put in "
                                        "(0.025 J/m"),
            std::string::npos)
      << summary.failure_reason;
  EXPECT_NE(summary.failure_reason.find("initial kinetic 0.025, initial elastic 0)"),
            std::string::npos)
      << summary.failure_reason;
  EXPECT_NEAR(summary.failure_time, 0.40, 1e-9);
}

TEST(Driver, KineticEnergyWithinTwiceTheEnergyPutInCompletes) {
  const Scene scene = load_scene_from_string(kScene, "moving-block.toml");
  RunOptions options{out_dir("energy-within"), false};
  // Speed x1.4: 0.049 J/m, 1.96 times the energy put in: within the factor 2.
  const RunSummary summary =
      run_scene(scene, ballistic({.boost_at_step = 40, .boost = 1.4}), options);
  EXPECT_EQ(summary.status, "completed") << summary.failure_reason;
  // ... and is warned of: 1.96 is above the warning's 1.2.
  EXPECT_NE(read_text(options.out_dir + "/metrics.json")
                .find("the kinetic energy reached 1.96 times the energy put in"),
            std::string::npos);
}

TEST(Driver, BodyLeavingAFixedNoSlipWallIsAFailure) {
  std::string text = kScene;
  text.replace(text.find("initial_velocity = [0.1, 0.0]"), 29, "initial_velocity = [0.0, 0.1]");
  text += "[wall.floor]\npoints = [[-0.5, -0.0025], [0.5, -0.0025]]\ncondition = \"no-slip\"\n";
  const Scene scene = load_scene_from_string(text, "moving-block.toml");
  RunOptions options{out_dir("lift-off"), false};
  const RunSummary summary = run_scene(scene, ballistic({}), options);
  EXPECT_EQ(summary.status, "failed");
  // The ten particles of the bottom row start 0.0075 m above the floor; they are more than two
  // spacings (0.02 m) from it once 0.0075 + 0.1 t > 0.02: at step 13 (t = 0.13 s).
  EXPECT_NE(summary.failure_reason.find("lifted off no-slip wall 'floor': 100 % of the 10 "
                                        "particles"),
            std::string::npos)
      << summary.failure_reason;
  EXPECT_NEAR(summary.failure_time, 0.13, 1e-9);
}

TEST(Driver, LiftOffCheckTurnedOffLetsTheBodyLeave) {
  std::string text = kScene;
  text.replace(text.find("initial_velocity = [0.1, 0.0]"), 29, "initial_velocity = [0.0, 0.1]");
  text += "[wall.floor]\npoints = [[-0.5, 0.0], [0.5, 0.0]]\ncondition = \"no-slip\"\n";
  text += "[checks]\nlift_off_fraction = 0.0\n";
  const Scene scene = load_scene_from_string(text, "moving-block.toml");
  RunOptions options{out_dir("lift-off-off"), false};
  EXPECT_EQ(run_scene(scene, ballistic({}), options).status, "completed");
}

// A scene under gravity on a free-slip floor, nothing driven: the end-of-run "not at rest"
// warning applies to it.
std::string settling(std::string text) {
  text.replace(text.find("spacing = 0.01"), 14, "spacing = 0.01\ngravity = [0.0, -10.0]");
  text += "[wall.floor]\npoints = [[-0.5, 0.0], [1.5, 0.0]]\ncondition = \"free-slip\"\n";
  return text;
}

TEST(Driver, DepositStillMovingAtTheEndIsWarnedOf) {
  // Under gravity, nothing driven, the block still sliding at 0.1 m/s at the end: its kinetic
  // energy at the end is its peak.
  const Scene scene = load_scene_from_string(settling(kScene), "moving-block.toml");
  RunOptions options{out_dir("not-at-rest"), false};
  const RunSummary summary = run_scene(scene, ballistic({}), options);
  ASSERT_EQ(summary.status, "completed") << summary.failure_reason;
  const std::string metrics = read_text(options.out_dir + "/metrics.json");
  EXPECT_NE(metrics.find("not at rest: the kinetic energy at t = 1 s is 1 of its peak"),
            std::string::npos)
      << metrics;
}

TEST(Driver, ParticlesThrownOffARestingBodyAreNamedInTheNotAtRestWarning) {
  // Under gravity, nothing driven: a 1 m x 0.05 m block (500 particles) at rest, a grain of
  // four particles sliding at 1 m/s. All the kinetic energy at the end is the grain's: two of
  // 504 particles carry half, within 1 %.
  std::string text = settling(kScene);
  text.replace(text.find("max = [0.1, 0.05]"), 17, "max = [1.0, 0.05]");
  text.replace(text.find("initial_velocity = [0.1, 0.0]"), 29, "initial_velocity = [0.0, 0.0]");
  text +=
      "[body.grain]\nmaterial = \"steel\"\nshape = \"rectangle\"\nmin = [0.3, 0.06]\n"
      "max = [0.32, 0.08]\ninitial_velocity = [1.0, 0.0]\n";
  const Scene scene = load_scene_from_string(text, "moving-block.toml");
  RunOptions options{out_dir("thrown-off"), false};
  const RunSummary summary = run_scene(scene, ballistic({}), options);
  ASSERT_EQ(summary.status, "completed") << summary.failure_reason;
  const std::string metrics = read_text(options.out_dir + "/metrics.json");
  // the grain's first particle, row 500, at (0.305 + 1.0 m/s x 1 s, 0.065)
  EXPECT_NE(metrics.find("not at rest, and thrown off: the kinetic energy at t = 1 s is 1 of its "
                         "peak (at t = 0 s), and 2 of 504 particles carry half of it; the most, "
                         "particle 500 at (1.305, 0.065) m, moves at 1 m/s"),
            std::string::npos)
      << metrics;
}

TEST(Driver, RunWithoutGravityOrStillAtTheEndHasNoWarning) {
  const Scene scene = load_scene_from_string(kScene, "moving-block.toml");  // no gravity
  RunOptions options{out_dir("no-warning"), false};
  ASSERT_EQ(run_scene(scene, ballistic({}), options).status, "completed");
  EXPECT_NE(read_text(options.out_dir + "/metrics.json").find("\"warnings\": []"),
            std::string::npos);
}

TEST(Driver, OutputFolderThatIsAFileOrCannotBeCreatedIsBadInput) {
  const std::string file = out_dir("not-a-folder");
  std::ofstream(file) << "x";
  EXPECT_THROW(prepare_output_folder(file), InputError);
  try {
    prepare_output_folder(file + "/below");
    FAIL() << "a folder below a file was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot create the output folder"), std::string::npos)
        << e.what();
  }
  std::filesystem::remove(file);
}

TEST(Driver, SceneNeedingMoreMemoryThanTheMachineIsRefusedUnlessForced) {
  std::string text = kScene;
  text.replace(text.find("spacing = 0.01"), 14, "spacing = 1e-6");
  const Scene scene = load_scene_from_string(text, "moving-block.toml");
  // 0.1 m x 0.05 m at 1 um: 5e9 particles.
  const RunEstimate e = estimate_run(scene, ballistic({}));
  EXPECT_NEAR(e.particles, 5e9, 1.0);
  EXPECT_GT(e.bytes, 5e9 * 2048.0);
  try {
    refuse_if_too_large(scene, ballistic({}), false);
    FAIL() << "a 5e9-particle scene was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("about 5e+09 particles"), std::string::npos)
        << error.what();
  }
  EXPECT_NO_THROW(refuse_if_too_large(scene, ballistic({}), true));
}

}  // namespace
}  // namespace duet
