// A scene fuzzer (issue 17): every benchmark scene mutated a few hundred ways, deterministically
// (deleted and duplicated lines, every value replaced by a wrong type, an out-of-range or a
// non-finite number, huge and tiny spacings, empty and binary files, unicode names, deep nesting,
// degenerate polygons), each loaded as `duet run` and `duet check` load a scene (parse, read,
// validate, build the models, estimate the run's size against the machine). Each must end in a
// scene or an InputError (exit 2) that names a key, a line or the file, within a second or five
// times the unmutated scene's own load, whichever is longer (the sanitizer build loads the cavity's
// 31,000 polar-lattice particles in about a second); any other exception, a crash (the sanitizer
// build runs this too) or a hang is a defect. The count
// and the classes of message are printed (benchmarks/RESULTS.md records them).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "benchmarks/driver.hpp"
#include "benchmarks/methods.hpp"
#include "benchmarks/scene_input.hpp"
#include "common/input_error.hpp"
#include "tests/benchmarks/child_run.hpp"
#include "tests/benchmarks/scene_mutations.hpp"

namespace duet {
namespace {

namespace fs = std::filesystem;

/// Load a scene as `duet run` and `duet check` do: parse, validate, build, estimate its size.
void load_as_a_run_does(const std::string& text, const fs::path& path) {
  // The scene's own path: a reference curve beside it is read as a user's run reads it
  const Scene scene = load_scene_checked_from_string(text, path.string());
  for (const std::string& method : builtin_methods().names()) {
    refuse_if_too_large(scene, builtin_methods().find(method), false);
  }
}

/// Seconds the unmutated scene takes to load, the fastest of three (this build's own speed).
double own_load_seconds(const std::string& text, const fs::path& path) {
  double fastest = 1e300;
  for (int k = 0; k < 3; ++k) {
    const auto start = std::chrono::steady_clock::now();
    load_as_a_run_does(text, path);
    fastest = std::min(
        fastest, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return fastest;
}

/// What kind of refusal a message is: its text up to the first ':' after the location.
std::string message_class(const std::string& message) {
  std::string rest = message;
  // Drop "FILE:LINE: " or "--set ...: ".
  for (int k = 0; k < 2 && rest.find(": ") != std::string::npos; ++k) {
    const std::string head = rest.substr(0, rest.find(": "));
    if (head.find(".toml") == std::string::npos && head.rfind("--set", 0) != 0 &&
        head.find_first_not_of("0123456789") != std::string::npos)
      break;
    rest = rest.substr(rest.find(": ") + 2);
  }
  const auto colon = rest.find(": ");
  std::string key = colon == std::string::npos ? rest : rest.substr(colon + 2);
  return key.substr(0, std::min<std::size_t>(key.size(), 28));
}

TEST(SceneFuzz, EveryMutationLoadsOrIsRefusedNamingWhereInBoundedTime) {
  std::mt19937 random(20261202);
  long tried = 0, accepted = 0, refused = 0;
  std::map<std::string, long> classes;
  double slowest = 0.0;
  std::string slowest_label;
  for (const auto& entry :
       fs::directory_iterator(fs::path(DUET_SOURCE_DIR) / "benchmarks/scenes")) {
    if (entry.path().extension() != ".toml") continue;
    const std::string name = entry.path().filename().string();
    const std::string original = test::read_text(entry.path());
    const double limit = std::max(1.0, 5.0 * own_load_seconds(original, entry.path()));
    for (const auto& [label, text] : test::mutations(original, random)) {
      ++tried;
      const auto start = std::chrono::steady_clock::now();
      try {
        load_as_a_run_does(text, entry.path());
        ++accepted;
      } catch (const InputError& e) {
        ++refused;
        const std::string message = e.what();
        // It says where: the file (with its line), a --set, or a named key.
        EXPECT_TRUE(message.find(name) != std::string::npos ||
                    message.find("--set") != std::string::npos)
            << name << ", " << label << ": " << message;
        ++classes[message_class(message)];
      } catch (const std::exception& e) {
        ADD_FAILURE() << name << ", " << label << ": not an input error: " << e.what();
      }
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (seconds > slowest) {
        slowest = seconds;
        slowest_label = name + ", " + label;
      }
      EXPECT_LT(seconds, limit) << name << ", " << label;
    }
  }
  std::cout << tried << " mutations: " << accepted << " loaded, " << refused << " refused; slowest "
            << slowest << " s (" << slowest_label << ")\n";
  std::vector<std::pair<long, std::string>> sorted;
  for (const auto& [what, count] : classes) sorted.emplace_back(count, what);
  std::sort(sorted.rbegin(), sorted.rend());
  for (std::size_t k = 0; k < sorted.size() && k < 25; ++k) {
    std::cout << "  " << sorted[k].first << "  " << sorted[k].second << "\n";
  }
  EXPECT_GT(tried, 2000);
  EXPECT_GT(refused, tried / 2);
}

}  // namespace
}  // namespace duet
