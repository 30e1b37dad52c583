// The scene fuzzer's second half (issue 17): a deterministic sample of the mutations that load
// (one in four, methods in turn) is run by `duet run` to a short end time, each in its own process
// under a time limit. Each must end in exit 0 (completed), 2 (refused: bad input) or 3 (failed
// with a reason), or be still stepping at the time limit (60 s: SIGTERM, on which a run ends as
// `interrupted` between steps); an internal error (1), an abort, a crash or a hang (no end 10 s
// after SIGTERM: SIGKILL, 137) is a defect. The counts per exit status are printed
// (benchmarks/RESULTS.md records them).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <random>
#include <string>

#include "benchmarks/driver.hpp"
#include "benchmarks/methods.hpp"
#include "benchmarks/scene_input.hpp"
#include "common/input_error.hpp"
#include "tests/benchmarks/child_run.hpp"
#include "tests/benchmarks/scene_mutations.hpp"

namespace duet {
namespace {

namespace fs = std::filesystem;

/// Short runs: a few steps or increments of every method, gravity loading cut short (each only
/// where the scene's other settings take it, so that the run is not refused for it).
std::string short_run(const Scene& scene, const std::string& method) {
  std::string sets = " --set time.end_time=0.002 --set time.output_interval=0.001";
  if (method == "ispfem" && !(scene.spfem_implicit.increment > 0.0)) {
    sets += " --set spfem.implicit.load_steps=2";
  }
  if (scene.initial_stress.kind == InitialStressKind::gravity_loading) {
    sets += " --set initial_stress.time=0.002";
  }
  return sets + " --quiet --no-plots";
}

TEST(SceneFuzzRun, SampledMutationsThatLoadRunToAnEndWithinTheirTime) {
  std::mt19937 random(20261202);  // the loading test's mutations, in its order
  const fs::path folder = fs::temp_directory_path() / "duet-fuzz-run";
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::vector<std::string> methods = builtin_methods().names();
  // One in four by default; DUET_FUZZ_EVERY=1 runs every mutation that loads (a few minutes).
  const char* every_text = std::getenv("DUET_FUZZ_EVERY");
  const long every = every_text ? std::max(1L, std::atol(every_text)) : 4;
  long loaded = 0, ran = 0, too_large = 0;
  std::map<int, long> by_status;
  for (const auto& entry :
       fs::directory_iterator(fs::path(DUET_SOURCE_DIR) / "benchmarks/scenes")) {
    if (entry.path().extension() != ".toml") continue;
    const std::string name = entry.path().stem().string();
    for (const auto& [label, text] : test::mutations(test::read_text(entry.path()), random)) {
      std::optional<Scene> scene;
      try {
        scene.emplace(load_scene_checked_from_string(text, name));
      } catch (const InputError&) {
        continue;
      }
      if (loaded++ % every != 0) continue;
      const std::string method = methods[static_cast<std::size_t>(ran) % methods.size()];
      // A mutation that only makes the run large (a spacing of 1 mm on the footing) is not run:
      // its steps are slow, not wrong; nor are the collapses at their 2 mm (5,000 particles),
      // where a Newton that does not converge takes 140 s over its cuts before it fails.
      if (estimate_run(*scene, builtin_methods().find(method)).particles > 3000) {
        ++too_large;
        continue;
      }
      const fs::path file = folder / (name + "-" + std::to_string(ran) + ".toml");
      { std::ofstream(file) << text; }
      const test::DuetResult r =
          test::run_command("timeout -k 10 60 '" + std::string(DUET_BINARY) + "' run '" +
                            file.string() + "' --method " + method + short_run(*scene, method) +
                            " --out '" + (folder / ("run-" + std::to_string(ran))).string() + "'");
      ++ran;
      // 124: the time limit's SIGTERM came and the run ended on it, as `interrupted` with its
      // metrics: alive but slow (a legal, absurd value: a density of 1e-300 kg/m^3 shrinks the
      // explicit step a hundredfold and more), not a defect. A run that ignored it took SIGKILL
      // (137): a hang.
      const fs::path metrics = folder / ("run-" + std::to_string(ran - 1)) / "metrics.json";
      const bool slow =
          r.status == 124 && fs::exists(metrics) &&
          test::read_text(metrics).find("\"status\": \"interrupted\"") != std::string::npos;
      ++by_status[slow ? -124 : r.status];
      if (slow) continue;
      EXPECT_TRUE(r.status == 0 || r.status == 2 || r.status == 3)
          << name << ", " << label << ", " << method << ": exit " << r.status << "\n"
          << r.output.substr(r.output.size() > 2000 ? r.output.size() - 2000 : 0);
    }
  }
  std::cout << loaded << " mutations load; " << ran << " run (" << too_large
            << " sampled ones over 3,000 particles not run):";
  for (const auto& [status, count] : by_status) {
    if (status == -124) {
      std::cout << " interrupted at the time limit x " << count;
    } else {
      std::cout << " exit " << status << " x " << count;
    }
  }
  std::cout << "\n";
  EXPECT_GT(ran, 120 / every);
  fs::remove_all(folder);
}

}  // namespace
}  // namespace duet
