// Every benchmark scene loads; every bad scene is refused by the duet program itself with exit
// status 2 and its expected message on stderr (tests/data/bad-scenes, first line "# expect: ...").
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include "benchmarks/scene_input.hpp"
#include "common/input_error.hpp"
#include "constitutive/registry.hpp"

namespace duet {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> toml_files(const fs::path& folder) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

/// Models a scene file names that are not registered (yet).
std::vector<std::string> missing_models(const fs::path& file) {
  std::vector<std::string> missing;
  const auto known = constitutive::builtin_models().names();
  const toml::table scene = toml::parse_file(file.string());
  if (const toml::table* materials = scene["material"].as_table()) {
    for (const auto& [name, material] : *materials) {
      const auto model =
          material.as_table() ? (*material.as_table())["model"].value<std::string>() : std::nullopt;
      if (model && std::find(known.begin(), known.end(), *model) == known.end()) {
        missing.push_back(*model);
      }
    }
  }
  return missing;
}

class BenchmarkScene : public testing::TestWithParam<fs::path> {};

TEST_P(BenchmarkScene, Loads) {
  if (const auto missing = missing_models(GetParam()); !missing.empty()) {
    GTEST_SKIP() << GetParam().filename() << " needs model '" << missing.front()
                 << "', which is not registered yet";
  }
  Scene scene;
  try {
    scene = load_scene_checked(GetParam().string());
  } catch (const InputError& e) {
    FAIL() << e.what();
  }
  EXPECT_GT(scene.spacing, 0.0);
  EXPECT_FALSE(scene.bodies.empty());
  // Every scored reference says where it comes from.
  for (const Reference& r : scene.references) EXPECT_FALSE(r.source.empty()) << r.measure;
}

INSTANTIATE_TEST_SUITE_P(Scenes, BenchmarkScene,
                         testing::ValuesIn(toml_files(fs::path(DUET_SOURCE_DIR) /
                                                      "benchmarks/scenes")),
                         [](const testing::TestParamInfo<fs::path>& info) {
                           std::string name = info.param.stem().string();
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

TEST(BenchmarkScenes, AMeasureTakenAfterAShortenedEndTimeIsNamed) {
  const std::string cavity = std::string(DUET_SOURCE_DIR) + "/benchmarks/scenes/cavity.toml";
  EXPECT_TRUE(measures_after_the_end(load_scene_checked(cavity)).empty());
  // a/a0 = 1.2 at t = 2 s: the pressures at a/a0 1.5 (t = 5 s) and 2 (t = 10 s) are never taken
  const std::vector<std::string> late =
      measures_after_the_end(load_scene_checked(cavity, {"time.end_time=2"}));
  ASSERT_EQ(late.size(), 2u);
  EXPECT_NE(late[0].find("measure.pressure is taken at t = 10 s, after time.end_time = 2 s"),
            std::string::npos)
      << late[0];
  EXPECT_NE(late[1].find("measure.pressure_a15"), std::string::npos) << late[1];
}

/// The method options of `file` ([sph], [spfem], [spfem.implicit]) set without a reason: a key
/// line is explained by a comment on it, by a comment line right above it, or by the explained key
/// line right above it (a group under one comment); a table's first keys also by a comment right
/// above its header.
std::vector<std::string> unexplained_method_options(const fs::path& file) {
  std::vector<std::string> out;
  std::ifstream in(file);
  std::string line, table, previous;
  bool explained = false;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::size_t first = line.find_first_not_of(" \t");
    const std::string text = first == std::string::npos ? "" : line.substr(first);
    if (text.empty()) {
      explained = false;
    } else if (text.front() == '#') {
      explained = true;
    } else if (text.front() == '[') {
      table = text.substr(1, text.find(']') - 1);
      explained = !previous.empty() && previous.front() == '#';
    } else if (table == "sph" || table == "spfem" || table == "spfem.implicit") {
      explained = explained || text.find('#') != std::string::npos;
      if (!explained) out.push_back(file.filename().string() + ":" + std::to_string(number));
    }
    previous = text;
  }
  return out;
}

// A benchmark scene keeps a method option only where it states a modelling choice or a setting
// the method's default does not give, and says why; the defaults serve every other line.
TEST(BenchmarkScenes, EveryMethodOptionSaysWhy) {
  for (const fs::path& file : toml_files(fs::path(DUET_SOURCE_DIR) / "benchmarks/scenes")) {
    for (const std::string& where : unexplained_method_options(file)) {
      ADD_FAILURE() << where << ": a method option without a comment saying why";
    }
  }
  // The rule itself: a bare key is caught, a commented one is not.
  const fs::path probe = fs::temp_directory_path() / "duet-method-option-probe.toml";
  std::ofstream(probe) << "[sph]\ncfl = 0.4\n\n# why\n[spfem]\nstabilisation = 0.1\n";
  EXPECT_EQ(unexplained_method_options(probe),
            std::vector<std::string>{probe.filename().string() + ":2"});
}

TEST(BenchmarkScenes, AllEightArePresent) {
  EXPECT_GE(toml_files(fs::path(DUET_SOURCE_DIR) / "benchmarks/scenes").size(), 8u);
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

class BadScene : public testing::TestWithParam<fs::path> {};

TEST_P(BadScene, DuetRunExitsWithStatus2AndTheExpectedMessage) {
  std::ifstream in(GetParam());
  std::string first_line;
  std::getline(in, first_line);
  const std::string tag = "# expect: ";
  ASSERT_EQ(first_line.rfind(tag, 0), 0u) << GetParam() << " lacks its '# expect: ' first line";
  const std::string fragment = first_line.substr(tag.size());

  const fs::path err =
      fs::temp_directory_path() / ("duet-bad-scene-" + GetParam().stem().string() + ".stderr");
  const fs::path out_dir =
      fs::temp_directory_path() / ("duet-bad-scene-out-" + GetParam().stem().string());
  const std::string command = "'" + std::string(DUET_BINARY) + "' run '" + GetParam().string() +
                              "' --method sph --out '" + out_dir.string() + "' > /dev/null 2> '" +
                              err.string() + "'";
  const int status = std::system(command.c_str());
  const std::string stderr_text = read_text(err);
  fs::remove(err);
  ASSERT_TRUE(WIFEXITED(status)) << command;
  EXPECT_EQ(WEXITSTATUS(status), 2) << stderr_text;
  EXPECT_NE(stderr_text.find(fragment), std::string::npos)
      << "expected: " << fragment << "\ngot: " << stderr_text;
  EXPECT_NE(stderr_text.find(GetParam().string()), std::string::npos) << stderr_text;
}

INSTANTIATE_TEST_SUITE_P(BadScenes, BadScene,
                         testing::ValuesIn(toml_files(fs::path(DUET_SOURCE_DIR) /
                                                      "tests/data/bad-scenes")),
                         [](const testing::TestParamInfo<fs::path>& info) {
                           std::string name = info.param.stem().string();
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace duet
