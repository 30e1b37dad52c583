// `duet run --resume DIR` (issue 17): a run killed at some moment and resumed from its last
// state-holding frame ends exactly as the run that was never stopped, bitwise (every measure, the
// method's counters, Newton's residual history, the last frame's positions and stresses), through
// ispfem and espfem; what cannot be resumed is refused with the reason, exit 2, before any work.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <ostream>
#include <string>
#include <thread>

#include "common/h5_writer.hpp"
#include "common/json.hpp"
#include "tests/benchmarks/child_run.hpp"

namespace duet {
namespace {

namespace fs = std::filesystem;

/// A benchmark scene through a method at a coarse spacing (a few seconds on one thread: one
/// thread so that the two runs sum in one order), killed once run.xdmf lists `frames` frames.
struct ResumeCase {
  std::string scene;
  std::string method;
  std::string spacing;
  std::size_t frames;
  std::string set = "";  // one --set override, or none
};

std::ostream& operator<<(std::ostream& out, const ResumeCase& c) {
  return out << c.scene << " through " << c.method << " at dp " << c.spacing
             << (c.set.empty() ? "" : " with " + c.set) << ", killed after " << c.frames
             << " frames";
}

std::string quoted(const fs::path& p) {
  return "'" + p.string() + "'";
}

int wait_for(pid_t child) {
  int status = 0;
  waitpid(child, &status, 0);
  return status;
}

/// Starts the case into `out` and kills it (SIGKILL) once run.xdmf lists its `frames` frames.
void kill_after(const fs::path& out, const ResumeCase& c) {
  fs::remove_all(out);
  std::vector<std::string> args = {"--spacing",  c.spacing, "--quiet",
                                   "--no-plots", "--out",   out.string()};
  if (!c.set.empty()) args.insert(args.end(), {"--set", c.set});
  const pid_t child =
      test::start_run(c.scene, c.method, args, [] { setenv("OMP_NUM_THREADS", "1", 1); });
  const std::size_t frames = c.frames;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while ((!fs::exists(out / "run.xdmf") || test::frames_listed(out / "run.xdmf") < frames) &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  kill(child, SIGKILL);
  wait_for(child);
}

class Resume : public testing::TestWithParam<ResumeCase> {};

TEST_P(Resume, AKilledRunGoesOnAsIfItHadNeverStopped) {
  const ResumeCase& c = GetParam();
  const std::string tag = c.scene + "-" + c.method + "-" + std::to_string(c.frames);
  const fs::path whole = fs::temp_directory_path() / ("duet-resume-whole-" + tag);
  const fs::path killed = fs::temp_directory_path() / ("duet-resume-killed-" + tag);
  fs::remove_all(whole);
  const test::DuetResult a = test::run_command(
      "OMP_NUM_THREADS=1 '" + std::string(DUET_BINARY) + "' run '" + DUET_SOURCE_DIR +
      "/benchmarks/scenes/" + c.scene + ".toml' --method " + c.method + " --spacing " + c.spacing +
      (c.set.empty() ? "" : " --set " + c.set) + " --quiet --no-plots --out " + quoted(whole));
  ASSERT_EQ(a.status, 0) << a.output;

  kill_after(killed, c);
  ASSERT_FALSE(fs::exists(killed / "metrics.json")) << "the run ended before the kill";
  const test::DuetResult b =
      test::run_command("OMP_NUM_THREADS=1 '" + std::string(DUET_BINARY) + "' run --resume " +
                        quoted(killed) + " --quiet --no-plots");
  ASSERT_EQ(b.status, 0) << b.output;

  const Json ma = read_json((whole / "metrics.json").string());
  const Json mb = read_json((killed / "metrics.json").string());
  ASSERT_NE(mb.find("resumed"), nullptr);
  const double from = mb.find("resumed")->find("from_frame")->number();
  EXPECT_GE(from, static_cast<double>(c.frames) - 1.0);
  EXPECT_EQ(mb.find("status")->string(), "completed");
  EXPECT_EQ(ma.find("steps")->number(), mb.find("steps")->number());
  // Every measure and the method's diagnostics but its timing (ispfem: Newton's whole residual
  // history), to the last bit (dump writes doubles exactly).
  EXPECT_EQ(ma.find("measures")->dump(), mb.find("measures")->dump());
  const Json::Object& da = ma.find("diagnostics")->members();
  const Json* db = mb.find("diagnostics");
  for (const auto& [key, value] : da) {
    if (key.find("second") != std::string::npos) continue;  // timing: this process's
    ASSERT_NE(db->find(key), nullptr) << key;
    EXPECT_EQ(value.dump(), db->find(key)->dump()) << key;
  }
  EXPECT_EQ(ma.find("kinetic_energy")->dump(), mb.find("kinetic_energy")->dump());

  const std::string ha = (whole / "run.h5").string();
  const std::string hb = (killed / "run.h5").string();
  ASSERT_EQ(count_frames(ha), count_frames(hb));
  const std::size_t last = count_frames(ha) - 1;
  const Frame fa = read_frame(ha, last);
  const Frame fb = read_frame(hb, last);
  EXPECT_EQ(fa.time, fb.time);
  ASSERT_EQ(fa.position.size(), fb.position.size());
  for (std::size_t i = 0; i < fa.position.size(); ++i) {
    ASSERT_EQ(fa.position[i], fb.position[i]) << "particle " << i;
    ASSERT_EQ(fa.stress[i], fb.stress[i]) << "particle " << i;
  }
  for (const auto& [name, value] : ma.find("measures")->members()) {
    EXPECT_EQ(read_series(ha, name), read_series(hb, name)) << name;
  }
}

// The footing (a rough rigid footing pushed into Tresca clay, 81 frames) early in the elastic part
// and late under the plateau, through the SPFEM methods; the sand collapse (hypoplastic, no-slip
// floor, 101 frames, Verlet) through sph; the Bui collapse through espfem, which keeps its mesh
// between remeshes on the angle trigger (spfem.remesh = angle: the kept mesh is in the state);
// the slope at f = 1.3, killed while its strength falls after the gravity loading (Peng's order:
// the resolved scene once held the reduced strength, and the resumed run reduced it twice).
INSTANTIATE_TEST_SUITE_P(
    KilledAfterFrames, Resume,
    testing::Values(
        ResumeCase{"footing", "ispfem", "0.25", 8}, ResumeCase{"footing", "ispfem", "0.25", 50},
        ResumeCase{"footing", "espfem", "0.25", 8}, ResumeCase{"footing", "espfem", "0.25", 50},
        ResumeCase{"collapse", "sph", "0.01", 12}, ResumeCase{"collapse", "sph", "0.01", 60},
        ResumeCase{"collapse-bui", "espfem", "0.01", 30},
        ResumeCase{"slope", "espfem", "1.0", 6, "strength_reduction.factor=1.3"},
        ResumeCase{"slope", "ispfem", "1.0", 6, "strength_reduction.factor=1.3"}));

/// `duet run --resume DIR` and what it said.
test::DuetResult resume(const fs::path& dir) {
  return test::run_command("'" + std::string(DUET_BINARY) + "' run --resume " + quoted(dir) +
                           " --quiet --no-plots");
}

TEST(ResumeRefusal, ACompletedRunHasNothingToGoOnWith) {
  const fs::path out = fs::temp_directory_path() / "duet-resume-completed";
  fs::remove_all(out);
  const test::DuetResult run = test::run_duet(
      std::string("run '") + DUET_SOURCE_DIR +
      "/benchmarks/scenes/footing.toml' --method ispfem --spacing 0.25 --set time.end_time=0.2 "
      "--quiet --no-plots --out " +
      quoted(out));
  ASSERT_EQ(run.status, 0) << run.output;
  const test::DuetResult r = resume(out);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("the run completed (t = 0.2 s); nothing to go on with"),
            std::string::npos)
      << r.output;
}

TEST(ResumeRefusal, AFolderWithoutARunOrWithASceneBeside) {
  const fs::path empty = fs::temp_directory_path() / "duet-resume-empty";
  fs::remove_all(empty);
  fs::create_directories(empty);
  const test::DuetResult r = resume(empty);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("no run.h5 there"), std::string::npos) << r.output;

  const test::DuetResult both =
      test::run_duet(std::string("run '") + DUET_SOURCE_DIR +
                     "/benchmarks/scenes/footing.toml' --resume " + quoted(empty));
  EXPECT_EQ(both.status, 2) << both.output;
  EXPECT_NE(both.output.find("takes no scene"), std::string::npos) << both.output;
}

}  // namespace
}  // namespace duet
