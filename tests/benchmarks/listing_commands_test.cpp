// `duet keys`, `duet models` and `duet methods` against what the loader and the models accept:
// every key the loader fills in is listed, every listed literal default is the value the loader
// fills in, every listed key can be set, and every listed model parameter is read by its model.

#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "benchmarks/listing_commands.hpp"
#include "benchmarks/methods.hpp"
#include "benchmarks/scene_input.hpp"
#include "common/input_error.hpp"
#include "common/scene.hpp"
#include "common/scene_keys.hpp"
#include "constitutive/registry.hpp"
#include "tests/benchmarks/child_run.hpp"

namespace duet {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> benchmark_scenes() {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(fs::path(DUET_SOURCE_DIR) / "benchmarks/scenes")) {
    if (e.path().extension() == ".toml") out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// The resolved scene as a table (its first line is a comment).
toml::table resolved_table(const Scene& scene) {
  return toml::parse(scene.resolved_toml);
}

/// Tables of `root` that a schema section names: "sph" -> root.sph, "wall.<name>" -> every
/// root.wall.X, "" -> root. Pairs (dotted path, table).
std::vector<std::pair<std::string, const toml::table*>> tables_of(const toml::table& root,
                                                                  const std::string& section) {
  if (section.empty()) return {{"", &root}};
  const auto wildcard = section.find(".<");
  if (wildcard == std::string::npos) {
    const toml::node* node = root.at_path(section).node();
    if (node && node->is_table()) return {{section, node->as_table()}};
    return {};
  }
  std::vector<std::pair<std::string, const toml::table*>> out;
  const std::string kind = section.substr(0, wildcard);
  if (const toml::table* all = root[kind].as_table()) {
    for (const auto& [name, node] : *all) {
      if (node.is_table()) out.push_back({kind + "." + std::string(name.str()), node.as_table()});
    }
  }
  return out;
}

bool same_value(const toml::node& a, const toml::node& b) {
  if (a.is_number() && b.is_number()) {
    return a.value<double>().value() == b.value<double>().value();
  }
  if (a.is_array() && b.is_array()) {
    const toml::array& x = *a.as_array();
    const toml::array& y = *b.as_array();
    if (x.size() != y.size()) return false;
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (!same_value(*x.get(i), *y.get(i))) return false;
    }
    return true;
  }
  if (a.is_string() && b.is_string()) return a.value<std::string>() == b.value<std::string>();
  if (a.is_boolean() && b.is_boolean()) return a.value<bool>() == b.value<bool>();
  return false;
}

std::string text_of(const toml::node& node) {
  std::ostringstream out;
  node.visit([&out](const auto& n) { out << n; });
  return out.str();
}

const SceneKey* find_key(const std::string& section, const std::string& key) {
  for (const SceneKey& k : scene_keys()) {
    if (k.section == section && k.key == key) return &k;
  }
  return nullptr;
}

TEST(SceneKeys, EveryKeyTheLoaderFillsInIsListed) {
  for (const fs::path& path : benchmark_scenes()) {
    SCOPED_TRACE(path.filename().string());
    const toml::table resolved = resolved_table(load_scene_checked(path.string()));
    for (const std::string& section : scene_sections()) {
      if (section == "material.<name>") continue;  // open: the model's parameters
      for (const auto& [where, table] : tables_of(resolved, section)) {
        for (const auto& [key, node] : *table) {
          EXPECT_NE(find_key(section, std::string(key.str())), nullptr)
              << where << "." << key.str() << " is filled in by the loader but not in scene_keys()";
        }
      }
    }
  }
}

TEST(SceneKeys, ListedDefaultsAreTheLoadersDefaults) {
  int compared = 0;
  for (const fs::path& path : benchmark_scenes()) {
    SCOPED_TRACE(path.filename().string());
    const toml::table file = toml::parse_file(path.string());
    const toml::table resolved = resolved_table(load_scene_checked(path.string()));
    for (const SceneKey& k : scene_keys()) {
      if (!is_literal_default(k)) continue;
      const toml::table literal = toml::parse("v = " + k.fallback);
      const toml::node& expected = *literal.get("v");
      for (const auto& [where, table] : tables_of(resolved, k.section)) {
        const toml::node* given = where.empty() ? &file : file.at_path(where).node();
        if (given && given->is_table() && given->as_table()->contains(k.key)) continue;
        const toml::node* filled = table->get(k.key);
        ASSERT_NE(filled, nullptr) << where << "." << k.key << " has no value after loading";
        EXPECT_TRUE(same_value(*filled, expected))
            << where << "." << k.key << ": listed default " << k.fallback << ", loader fills in "
            << text_of(*filled);
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 300);
}

// A scene with no option tables: each listed option is set alone.
const char* kMinimalScene = R"(
spacing = 0.05
[time]
end_time = 0.1
[material.soil]
model = "linear-elastic"
density = 2000.0
E = 1e6
nu = 0.3
[body.block]
material = "soil"
min = [0.0, 0.0]
max = [0.5, 0.5]
)";

TEST(SceneKeys, EveryListedOptionCanBeSet) {
  // Setting each option table's key to its listed default is accepted (the loader knows it).
  int set = 0;
  for (const SceneKey& k : scene_keys()) {
    if (!is_literal_default(k) || k.section.find('<') != std::string::npos) continue;
    const std::string dotted = k.section.empty() ? k.key : k.section + "." + k.key;
    EXPECT_NO_THROW(
        load_scene_checked_from_string(kMinimalScene, "minimal.toml", {dotted + "=" + k.fallback}))
        << dotted;
    ++set;
  }
  EXPECT_GT(set, 30);
}

TEST(SceneKeys, UnlistedKeysAreRefused) {
  const std::string scene =
      (fs::path(DUET_SOURCE_DIR) / "benchmarks/scenes/collapse.toml").string();
  for (const std::string section : {"sph", "spfem", "spfem.implicit", "checks", "time"}) {
    EXPECT_THROW(load_scene_checked(scene, {section + std::string(".not_a_key=1")}), InputError)
        << section;
  }
}

TEST(KeysListing, ListsEveryKeyOfATable) {
  const std::string sph = keys_listing("sph");
  for (const std::string& key : scene_keys_of("sph")) {
    EXPECT_NE(sph.find("  " + key + " "), std::string::npos) << key;
  }
  const std::string walls = keys_listing("wall");
  EXPECT_NE(walls.find("[wall.<name>]"), std::string::npos);
  EXPECT_NE(walls.find("radial_velocity"), std::string::npos);
  const std::string all = keys_listing("");
  for (const SceneKey& k : scene_keys()) EXPECT_NE(all.find(k.key), std::string::npos) << k.key;
  try {
    keys_listing("sphh");
    FAIL() << "an unknown table was listed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'sph'"), std::string::npos) << e.what();
  }
}

TEST(ModelsListing, EveryRequiredParameterIsRequiredByTheModel) {
  for (const auto& info : constitutive::builtin_models().models()) {
    std::vector<std::map<std::string, ParameterValue>> forms = {info.example};
    forms.insert(forms.end(), info.other_forms.begin(), info.other_forms.end());
    for (const auto& form : forms) {
      constitutive::Parameters parameters(info.name, form);
      ASSERT_NO_THROW(info.make(parameters)) << info.name;
      ASSERT_FALSE(parameters.specs().empty()) << info.name;
      for (const constitutive::ParameterSpec& spec : parameters.specs()) {
        if (spec.kind == "required") {
          // Without it the model refuses, naming it.
          auto without = form;
          without.erase(spec.name);
          try {
            constitutive::make_model(info.name, without, info.name);
            ADD_FAILURE() << info.name << " built without its required " << spec.name;
          } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(spec.name), std::string::npos) << e.what();
          }
        } else if (spec.kind == "optional") {
          // Set to its listed default, it is accepted (a default that follows other parameters
          // is listed as its rule, "c cot(phi), the apex").
          if (spec.fallback.find_first_not_of("0123456789.-+e") != std::string::npos) continue;
          auto with = form;
          with[spec.name] = std::stod(spec.fallback);
          EXPECT_NO_THROW(constitutive::make_model(info.name, with, info.name))
              << info.name << "." << spec.name << " = " << spec.fallback;
        }
      }
    }
    const std::string listing = models_listing(info.name);
    EXPECT_NE(listing.find(info.name + ": "), std::string::npos);
  }
  EXPECT_THROW(models_listing("hypoplastik"), InputError);
}

TEST(ModelsListing, HypoplasticListsBothForms) {
  const std::string listing = models_listing("hypoplastic");
  EXPECT_NE(listing.find("form 2 of 2"), std::string::npos);
  for (const char* p : {"Ei", "nu", "phi", "psi", "c1", "c2", "c3", "c4"}) {
    EXPECT_NE(listing.find(std::string("    ") + p + " "), std::string::npos) << p;
  }
}

TEST(ModelsListing, ARangeThatFollowsAnotherParameterIsListedAsItsRule) {
  // Read from the example, psi's range was the example's phi: [0, 19.8] for drucker-prager
  for (const char* model : {"drucker-prager", "mohr-coulomb"}) {
    const std::string listing = models_listing(model);
    EXPECT_NE(listing.find("[0, phi]"), std::string::npos) << listing;
    EXPECT_EQ(listing.find("[0, 19.8]"), std::string::npos) << listing;
    EXPECT_EQ(listing.find("[0, 30]"), std::string::npos) << listing;
  }
  EXPECT_NE(models_listing("mohr-coulomb").find(">= 0 (> 0 when phi = 0)"), std::string::npos);
  const std::string dp = models_listing("drucker-prager");
  EXPECT_NE(dp.find("[0, c cot(phi)]"), std::string::npos) << dp;
  EXPECT_NE(dp.find("c cot(phi), the apex"), std::string::npos) << dp;
}

TEST(KeysListing, SphsSoundSpeedIsUsedAsGiven) {
  // sph/sph_solver.cpp takes sph.sound_speed as it is; no P-wave speed raises it
  const std::string sph = keys_listing("sph");
  EXPECT_EQ(sph.find("the larger of it and"), std::string::npos) << sph;
  EXPECT_NE(sph.find("used as given"), std::string::npos) << sph;
}

TEST(MethodsListing, ListsEveryRegisteredMethodWithItsOptionTables) {
  const std::string listing = methods_listing();
  for (const std::string& name : builtin_methods().names()) {
    const MethodInfo& m = builtin_methods().find(name);
    EXPECT_NE(listing.find(name), std::string::npos);
    ASSERT_FALSE(m.option_sections.empty()) << name;
    for (const std::string& s : m.option_sections) {
      EXPECT_FALSE(scene_keys_of(s).empty()) << name << " reads [" << s << "], not in the schema";
    }
  }
}

TEST(SceneKeyUnit, FromTheSchemaOrTheModel) {
  EXPECT_EQ(scene_key_unit("sph.sound_speed"), "m/s");
  EXPECT_EQ(scene_key_unit("spfem.implicit.increment"), "s");
  EXPECT_EQ(scene_key_unit("wall.base.velocity"), "s, m/s");
  EXPECT_EQ(scene_key_unit("spacing"), "m");
  EXPECT_EQ(scene_key_unit("material.sand.phi"), "deg");
  EXPECT_EQ(scene_key_unit("material.clay.cu"), "Pa");
  EXPECT_EQ(scene_key_unit("material.clay.density"), "kg/m^3");
  EXPECT_EQ(scene_key_unit("sph.no_such_key"), "");
}

TEST(ListingCommands, RunFromTheCommandLine) {
  const test::DuetResult keys = test::run_duet("keys spfem.implicit");
  EXPECT_EQ(keys.status, 0) << keys.output;
  EXPECT_NE(keys.output.find("max_step_cuts"), std::string::npos) << keys.output;
  const test::DuetResult unknown = test::run_duet("keys wal");
  EXPECT_EQ(unknown.status, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("did you mean 'wall'"), std::string::npos) << unknown.output;
  const test::DuetResult models = test::run_duet("models tresca");
  EXPECT_EQ(models.status, 0) << models.output;
  EXPECT_NE(models.output.find("cu"), std::string::npos) << models.output;
  const test::DuetResult methods = test::run_duet("methods");
  EXPECT_EQ(methods.status, 0) << methods.output;
  EXPECT_NE(methods.output.find("ispfem  quasi-static"), std::string::npos) << methods.output;
  const test::DuetResult help = test::run_duet("run --help");
  EXPECT_NE(help.output.find("duet keys"), std::string::npos) << help.output;
  EXPECT_NE(help.output.find("duet models"), std::string::npos) << help.output;
}

TEST(ListingCommands, VersionNamesTheCommit) {
  const test::DuetResult r = test::run_duet("--version");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.rfind("duet ", 0), 0u) << r.output;
  EXPECT_NE(r.output.find("(commit "), std::string::npos) << r.output;
}

}  // namespace
}  // namespace duet
