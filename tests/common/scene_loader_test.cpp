// The scene loader: defaults, --set overrides (type-checked like the file), messages that name
// the file, the line, the key and what was expected, and every bad scene under
// tests/data/bad-scenes refused with its expected message.
#include "common/scene_loader.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "benchmarks/scene_input.hpp"
#include "common/enum_names.hpp"
#include "common/input_error.hpp"
#include "common/lattice.hpp"
#include "common/particles.hpp"
#include "common/standing_faces.hpp"
#include "constitutive/registry.hpp"
#include "tests/common/column_scene.hpp"

namespace duet {
namespace {

const std::string kScene = test::kColumnScene;

/// The message of the InputError that loading throws ("" when it loads).
std::string refusal(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    load_scene_checked_from_string(text, "scene.toml", overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

/// Each name of a table reads back as itself, and no two names share a value (the loader and the
/// resolved scene go through the same table: a value missing or named twice would write one kind
/// as another).
template <class Enum, std::size_t N>
void expect_names_round_trip(const EnumName<Enum> (&table)[N]) {
  std::set<int> values;
  for (const std::string& name : names_of(table)) {
    const Enum value = value_named(name, table);
    EXPECT_EQ(std::string(name_of(value, table)), name);
    EXPECT_TRUE(values.insert(static_cast<int>(value)).second) << name << " shares its value";
  }
  // The enum's values are 0 .. N-1, each named
  for (int k = 0; k < static_cast<int>(N); ++k) EXPECT_EQ(values.count(k), 1u) << k;
}

TEST(SceneLoader, EveryEnumNameReadsBackAsItself) {
  expect_names_round_trip(kFormulationNames);
  expect_names_round_trip(kMeasureKindNames);
  expect_names_round_trip(kMeasureAtNames);
  expect_names_round_trip(kInitialStressKindNames);
  expect_names_round_trip(kWallConditionNames);
  expect_names_round_trip(kSurfaceNames);
  expect_names_round_trip(kSphKernelNames);
  expect_names_round_trip(kSphWallStressNames);
  expect_names_round_trip(kSphDummyVelocityNames);
  expect_names_round_trip(kSphIntegratorNames);
  expect_names_round_trip(kSpfemTimeStepNames);
  expect_names_round_trip(kRemeshNames);
  EXPECT_STREQ(to_string(MeasureKind::point_displacement), "point_displacement");
  EXPECT_STREQ(to_string(InitialStressKind::gravity_loading), "gravity-loading");
  EXPECT_THROW(name_of(static_cast<MeasureKind>(99), kMeasureKindNames), std::logic_error);
}

TEST(SceneLoader, FillsEveryDefaultFromThePapers) {
  const Scene s = load_scene_checked_from_string(kScene, "scene.toml");
  EXPECT_EQ(s.name, "column");
  EXPECT_DOUBLE_EQ(s.time.output_interval, 0.5 / 50);
  EXPECT_EQ(s.initial_stress.kind, InitialStressKind::none);
  EXPECT_DOUBLE_EQ(s.sph.h_over_dp, std::sqrt(2.0));  // Peng 2015 section 5
  EXPECT_DOUBLE_EQ(s.sph.alpha, 1.0);
  EXPECT_DOUBLE_EQ(s.sph.beta, 0.1);
  EXPECT_EQ(s.sph.dummy_layers, 3);
  EXPECT_EQ(s.walls[0].condition, WallCondition::no_slip);
  EXPECT_TRUE(s.walls[0].velocity.empty());
  EXPECT_DOUBLE_EQ(s.spfem.alpha_factor, 1.5);
  EXPECT_EQ(s.spfem_implicit.max_iterations, 40);  // a footing increment after a cut needs 13-18
  EXPECT_EQ(s.spfem_implicit.max_step_cuts, 8);
  EXPECT_EQ(s.bodies[0].material_index, 0);
}

TEST(SceneLoader, AWallWithARepeatedPointIsRefusedNamingIt) {
  // A segment of zero length has no normal (found by the scene fuzzer: exit 1 from the SPH walls)
  std::string text = kScene;
  text.replace(text.find("[[0.0, 0.0], [0.6, 0.0]]"), 24, "[[0.0, 0.0], [0.6, 0.0], [0.6, 0.0]]");
  const std::string message = refusal(text);
  EXPECT_NE(message.find("scene.toml:"), std::string::npos) << message;
  EXPECT_NE(message.find("wall.floor.points: point 3 repeats the one before it"), std::string::npos)
      << message;
}

TEST(SceneLoader, ANonFinitePointIsRefusedNamingIt) {
  std::string text = kScene;
  text.replace(text.find("[[0.0, 0.0], [0.6, 0.0]]"), 24, "[[0.0, 0.0], [nan, 0.0]]");
  const std::string message = refusal(text);
  EXPECT_NE(message.find("wall.floor.points: [nan, 0]"), std::string::npos) << message;
  EXPECT_NE(message.find("finite numbers in [x, y]"), std::string::npos) << message;
  EXPECT_NE(refusal(kScene, {"gravity=[0.0, inf]"}).find("finite numbers"), std::string::npos);
}

TEST(SceneLoader, GravityDefaultsToZero) {
  std::string text = kScene;
  text.replace(text.find("gravity = [0.0, -9.81]\n"), 24, "");
  EXPECT_EQ(load_scene_checked_from_string(text, "scene.toml").gravity, Vec2::Zero());
}

TEST(SceneLoader, DefaultDomainIsThePaddedBoundingBoxOfEverything) {
  const Scene s = load_scene_checked_from_string(kScene, "scene.toml");
  // Everything spans [0, 0.6] x [0, 0.1]; padding a quarter of 0.6.
  EXPECT_DOUBLE_EQ(s.domain.padding, 0.15);
  EXPECT_NEAR(s.domain.min.x(), -0.15, 1e-15);
  EXPECT_NEAR(s.domain.max.x(), 0.75, 1e-15);
  EXPECT_NEAR(s.domain.max.y(), 0.25, 1e-15);
}

TEST(SceneLoader, OverrideReplacesAValueByDottedPath) {
  const Scene s = load_scene_checked_from_string(
      kScene, "scene.toml", {"spacing=0.005", "material.sand.nu=0.25", "sph.alpha=0.5"});
  EXPECT_DOUBLE_EQ(s.spacing, 0.005);
  EXPECT_DOUBLE_EQ(std::get<double>(s.materials[0].parameters.at("nu")), 0.25);
  EXPECT_DOUBLE_EQ(s.sph.alpha, 0.5);
}

TEST(SceneLoader, OverrideTakesABareWordAsAString) {
  const Scene s = load_scene_checked_from_string(kScene, "scene.toml", {"sph.kernel=wendland-c2"});
  EXPECT_EQ(s.sph.kernel, SphKernel::wendland_c2);
}

TEST(SceneLoader, APolarLatticeNeedsItsCentreAndASquareOneRefusesIt) {
  EXPECT_EQ(load_scene_checked_from_string(kScene, "scene.toml").bodies[0].lattice,
            LatticeKind::square);
  const Scene polar = load_scene_checked_from_string(
      kScene, "scene.toml", {"body.column.lattice=polar", "body.column.lattice_centre=[0.1, 0.0]"});
  EXPECT_EQ(polar.bodies[0].lattice, LatticeKind::polar);
  EXPECT_EQ(polar.bodies[0].lattice_centre, Vec2(0.1, 0.0));
  EXPECT_NE(refusal(kScene, {"body.column.lattice=polar"}).find("lattice_centre"),
            std::string::npos);
  EXPECT_NE(refusal(kScene, {"body.column.lattice_centre=[0.1, 0.0]"}).find("square lattice"),
            std::string::npos);
}

TEST(SceneLoader, OverrideIsTypeCheckedLikeTheFile) {
  EXPECT_EQ(refusal(kScene, {"spacing=fine"}),
            "--set spacing=fine: spacing: wrong type: a string; expected a number");
}

TEST(SceneLoader, OverrideOfAnUnknownKeySuggestsTheKnownOne) {
  const std::string message = refusal(kScene, {"sph.alpah=1"});
  EXPECT_NE(message.find("--set sph.alpah=1: sph.alpah: unknown key (did you mean 'alpha'?)"),
            std::string::npos)
      << message;
}

TEST(SceneLoader, OverrideOfAnUnknownMaterialSuggestsTheKnownOne) {
  EXPECT_EQ(refusal(kScene, {"material.snad.nu=0.2"}),
            "--set material.snad.nu=0.2: material.snad: no material named 'snad' (did you mean "
            "'sand'?); expected one of sand");
}

TEST(SceneLoader, OverrideOfAModelParameterIsCheckedByTheModel) {
  const std::string message = refusal(kScene, {"material.sand.nu=0.62"});
  EXPECT_NE(message.find("material.sand.nu = 0.62: Poisson's ratio must lie in [0, 0.5)"),
            std::string::npos)
      << message;
  EXPECT_EQ(message.rfind("--set material.sand.nu=0.62: ", 0), 0u) << message;
}

// Bui's wall pair and the Gershgorin step are the defaults (common/scene.hpp says why); the
// other choices read back.
TEST(SceneLoader, MethodDefaultsAreBuisWallsAndTheGershgorinStep) {
  const Scene plain = load_scene_from_string(kScene, "scene.toml");
  EXPECT_EQ(plain.sph.dummy_velocity, SphDummyVelocity::extrapolated);
  EXPECT_EQ(plain.sph.wall_stress, SphWallStress::bui);
  EXPECT_EQ(plain.spfem.time_step, SpfemTimeStep::gershgorin);
  const Scene peng = load_scene_from_string(
      kScene, "scene.toml",
      {"sph.dummy_velocity=wall", "sph.wall_stress=sigma-max", "spfem.time_step=cell-size"});
  EXPECT_EQ(peng.sph.dummy_velocity, SphDummyVelocity::wall);
  EXPECT_EQ(peng.sph.wall_stress, SphWallStress::sigma_max);
  EXPECT_EQ(peng.spfem.time_step, SpfemTimeStep::cell_size);
}

TEST(SceneLoader, AnAxisymmetricSceneLiesRightOfTheAxisHeldOnItAndSamplesRings) {
  const std::string axisymmetric = "formulation = \"axisymmetric\"\n" + kScene;
  const std::string axis =
      "\n[wall.axis]\npoints = [[0.0, 0.0], [0.0, 0.2]]\n"
      "condition = \"symmetry\"\n";
  // The column reaches the axis: without a symmetry wall on it nothing holds u_r = 0 there
  EXPECT_NE(refusal(axisymmetric).find("reaches the axis (x = 0 m) with no symmetry wall"),
            std::string::npos)
      << refusal(axisymmetric);
  EXPECT_EQ(refusal(axisymmetric + axis), "");
  EXPECT_NE(refusal(axisymmetric + axis, {"body.column.min=[-0.1, 0.0]"}).find("at r = x < 0"),
            std::string::npos);
  EXPECT_NE(refusal(axisymmetric + axis, {"gravity=[1.0, -9.81]"}).find("radial component"),
            std::string::npos);
  const std::string load =
      "\n[load.push]\nbody = \"column\"\nmin = [0.0, 0.09]\nmax = [0.2, 0.1]\n"
      "force = [[0.0, 0.0, -1.0]]\n";
  EXPECT_EQ(refusal(kScene + load), "");
  EXPECT_NE(refusal(axisymmetric + axis + load).find("load.push: a load in an axisymmetric scene"),
            std::string::npos)
      << refusal(axisymmetric + axis + load);
  // Each particle stands for its ring: mass rho 2 pi r dp^2 (kg), r its centre's x
  const Scene scene = load_scene_from_string(axisymmetric + axis, "scene.toml");
  EXPECT_EQ(scene.formulation, Formulation::axisymmetric);
  EXPECT_EQ(load_scene_from_string(kScene, "scene.toml").formulation, Formulation::plane_strain);
  Particles particles;
  sample_body(scene, 0, particles);
  ASSERT_GT(particles.size(), 0u);
  double mass = 0.0;
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const double ring = 2.0 * std::numbers::pi * particles.position[p].x();
    EXPECT_NEAR(particles.mass[p], 1800.0 * ring * 1e-4, 1e-12) << p;
    mass += particles.mass[p];
  }
  // The column r <= 0.2 m, 0.1 m tall: rho pi R^2 H, exactly (Pappus on the lattice's cells)
  EXPECT_NEAR(mass, 1800.0 * std::numbers::pi * 0.04 * 0.1, 1e-9);
}

TEST(SceneLoader, UnknownDummyVelocityIsRefusedNamingTheChoices) {
  const std::string message = refusal(kScene, {"sph.dummy_velocity=extrapolate"});
  EXPECT_NE(message.find("sph.dummy_velocity"), std::string::npos) << message;
  EXPECT_NE(message.find("wall, extrapolated"), std::string::npos) << message;
}

TEST(SceneLoader, StiffnessStabilisationDefaultsToOffAndANegativeValueIsRefused) {
  EXPECT_DOUBLE_EQ(load_scene_from_string(kScene, "scene.toml").spfem.stiffness_stabilisation, 0.0);
  EXPECT_DOUBLE_EQ(
      load_scene_from_string(kScene, "scene.toml", {"spfem.stiffness_stabilisation=0.5"})
          .spfem.stiffness_stabilisation,
      0.5);
  const std::string message = refusal(kScene, {"spfem.stiffness_stabilisation=-1"});
  EXPECT_NE(message.find("spfem.stiffness_stabilisation"), std::string::npos) << message;
}

TEST(SceneLoader, ImplicitOptionsOutOfRangeAreRefusedNamingTheKey) {
  // [spfem.implicit]: a residual tolerance and a correction tolerance must be positive, an
  // increment non-negative, at least one load step and one iteration
  for (const std::string bad :
       {"spfem.implicit.tolerance=-1e-8", "spfem.implicit.tolerance=0",
        "spfem.implicit.displacement_tolerance=-1", "spfem.implicit.load_steps=0",
        "spfem.implicit.increment=-0.1", "spfem.implicit.max_iterations=0",
        "spfem.implicit.predictor=linear"}) {
    const std::string message = refusal(kScene, {bad});
    const std::string key = bad.substr(0, bad.find('='));
    EXPECT_NE(message.find(key), std::string::npos) << bad << ": " << message;
  }
  EXPECT_DOUBLE_EQ(load_scene_from_string(kScene, "scene.toml").spfem_implicit.tolerance, 1e-8);
  // Newton starts from rest unless a scene asks for the extrapolated start
  EXPECT_FALSE(load_scene_from_string(kScene, "scene.toml").spfem_implicit.extrapolate);
  EXPECT_TRUE(
      load_scene_from_string(kScene, "scene.toml", {"spfem.implicit.predictor=extrapolated"})
          .spfem_implicit.extrapolate);
}

TEST(SceneLoader, RemeshAngleFractionDefaultsToThePlainThresholdAndStaysWithinOne) {
  EXPECT_DOUBLE_EQ(load_scene_from_string(kScene, "scene.toml").spfem.remesh_angle_fraction, 0.0);
  EXPECT_DOUBLE_EQ(load_scene_from_string(kScene, "scene.toml", {"spfem.remesh_angle_fraction=0.5"})
                       .spfem.remesh_angle_fraction,
                   0.5);
  const std::string message = refusal(kScene, {"spfem.remesh_angle_fraction=1.5"});
  EXPECT_NE(message.find("spfem.remesh_angle_fraction"), std::string::npos) << message;
}

TEST(SceneLoader, UnknownKeyNamesFileLineKeyAndSuggestion) {
  std::string text = kScene;
  text.replace(text.find("min = [0.0, 0.0]"), 16, "mni = [0.0, 0.0]");
  const std::string message = refusal(text);
  EXPECT_EQ(message.rfind("scene.toml:16: body.column.mni: unknown key (did you mean 'min'?); "
                          "expected one of ",
                          0),
            0u)
      << message;
}

TEST(SceneLoader, KeyThatDoesNotApplyToTheShapeIsRefused) {
  // Appended at the end, vertices lands in [wall.floor]: not a wall key at all.
  const std::string text = kScene + "vertices = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]\n";
  EXPECT_NE(refusal(text).find("wall.floor.vertices: unknown key"), std::string::npos);
  std::string rectangle_with_vertices = kScene;
  rectangle_with_vertices.replace(rectangle_with_vertices.find("min = [0.0, 0.0]"), 16,
                                  "shape = \"rectangle\"\nvertices = [[0, 0], [1, 0], [0, 1]]\n"
                                  "min = [0.0, 0.0]");
  EXPECT_NE(refusal(rectangle_with_vertices).find("body.column.vertices: does not apply"),
            std::string::npos);
}

TEST(SceneLoader, ClockwisePolygonIsReorderedCounterClockwise) {
  std::string text = kScene;
  text.replace(text.find("min = [0.0, 0.0]\nmax = [0.2, 0.1]"), 33,
               "vertices = [[0.0, 0.0], [0.0, 0.1], [0.2, 0.1], [0.2, 0.0]]");
  const Scene s = load_scene_checked_from_string(text, "scene.toml");
  ASSERT_EQ(s.bodies[0].shape, ShapeKind::polygon);
  const auto& v = s.bodies[0].outline;
  double twice_area = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2& a = v[i];
    const Vec2& b = v[(i + 1) % v.size()];
    twice_area += a.x() * b.y() - a.y() * b.x();
  }
  EXPECT_NEAR(0.5 * twice_area, 0.02, 1e-15);
}

TEST(SceneLoader, ResolvedTomlLoadsBackToTheSameScene) {
  const Scene s = load_scene_checked_from_string(kScene, "scene.toml", {"sph.alpha=0.7"});
  const Scene again = load_scene_checked_from_string(s.resolved_toml, "resolved.toml");
  EXPECT_DOUBLE_EQ(again.spacing, s.spacing);
  EXPECT_DOUBLE_EQ(again.sph.alpha, 0.7);
  EXPECT_DOUBLE_EQ(again.time.output_interval, s.time.output_interval);
  EXPECT_EQ(again.domain.min, s.domain.min);
  EXPECT_EQ(again.bodies[0].outline, s.bodies[0].outline);
  EXPECT_EQ(again.resolved_toml.substr(again.resolved_toml.find('\n')),
            s.resolved_toml.substr(s.resolved_toml.find('\n')));
}

TEST(SceneLoader, StrengthReductionDividesCohesionAndTangentOfFriction) {
  const auto& names = constitutive::builtin_models().names();
  if (std::find(names.begin(), names.end(), "drucker-prager") == names.end()) {
    GTEST_SKIP() << "model 'drucker-prager' is not registered yet";
  }
  std::string text = kScene;
  text.replace(text.find("model = \"linear-elastic\""), 24,
               "model = \"drucker-prager\"\nphi = 20.0\npsi = 0.0\nc = 10.0e3");
  const Scene s =
      load_scene_checked_from_string(text, "scene.toml", {"strength_reduction.factor=1.4"});
  const double deg = std::numbers::pi / 180.0;
  // Peng 2015 eq 39: c / f; Griffiths & Lane: tan(phi_f) = tan(phi) / f.
  EXPECT_NEAR(std::get<double>(s.materials[0].parameters.at("c")), 10.0e3 / 1.4, 1e-9);
  EXPECT_NEAR(std::tan(std::get<double>(s.materials[0].parameters.at("phi")) * deg),
              std::tan(20.0 * deg) / 1.4, 1e-12);
  // The resolved scene (what `duet run --resume` loads) reduces once more as it loads: it keeps
  // the full strength. It once held the reduced values, and a resumed slope ran at c / f^2.
  const Scene again = load_scene_checked_from_string(s.resolved_toml, "resolved.toml");
  EXPECT_DOUBLE_EQ(again.strength_reduction.factor, 1.4);
  EXPECT_EQ(again.materials[0].parameters, s.materials[0].parameters);
  EXPECT_EQ(again.materials[0].full_strength, s.materials[0].full_strength);
}

// Every bad scene: refused with InputError whose message starts with the file's path and
// contains the fragment of its first line "# expect: ...".
std::string expected_fragment(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string first;
  std::getline(in, first);
  const std::string tag = "# expect: ";
  return first.rfind(tag, 0) == 0 ? first.substr(tag.size()) : "";
}

TEST(SceneLoader, EveryBadSceneIsRefusedWithItsExpectedMessage) {
  const std::filesystem::path folder =
      std::filesystem::path(DUET_SOURCE_DIR) / "tests/data/bad-scenes";
  int n_files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() != ".toml") continue;
    ++n_files;
    const std::string fragment = expected_fragment(entry.path());
    ASSERT_FALSE(fragment.empty()) << entry.path() << " lacks its '# expect: ' first line";
    std::string message;
    try {
      load_scene_checked(entry.path().string());
    } catch (const InputError& e) {
      message = e.what();
    }
    EXPECT_NE(message.find(fragment), std::string::npos)
        << entry.path().filename() << "\n  expected: " << fragment << "\n  got:      " << message;
    // FILE:LINE: (or FILE: for a key missing at the top level)
    EXPECT_EQ(message.rfind(entry.path().string() + ":", 0), 0u) << message;
  }
  EXPECT_GE(n_files, 10);
}

TEST(SceneLoader, BadSceneMessagesCarryTheLineOfTheOffendingKey) {
  const std::filesystem::path file =
      std::filesystem::path(DUET_SOURCE_DIR) / "tests/data/bad-scenes/bad-parameter.toml";
  std::string message;
  try {
    load_scene_checked(file.string());
  } catch (const InputError& e) {
    message = e.what();
  }
  // Line 14 of the file: "nu = 0.62" (two comment lines, then the base scene).
  EXPECT_EQ(message.rfind(file.string() + ":14: material.sand.nu = 0.62", 0), 0u) << message;
}

std::string bad_scene(const std::string& name) {
  return (std::filesystem::path(DUET_SOURCE_DIR) / "tests/data/bad-scenes" / name).string();
}

/// The message of the InputError that loading the file throws ("" when it loads).
std::string file_refusal(const std::string& path, const std::vector<std::string>& overrides,
                         bool force = false) {
  try {
    load_scene_checked(path, overrides, force);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneValidation, AWallThroughABodyIsRefusedNamingBothAndWhereUnlessMeant) {
  // issue 44: the soil runs 0.5 m past the far wall at x = 3 (dp 0.1): the wall's points from
  // y = 0.5 to 1 m lie 0.5 m from the outline, the deepest of the wall inside the body
  const std::string path = bad_scene("body-crossing-wall.toml");
  const std::string message = file_refusal(path, {});
  EXPECT_NE(message.find("body.sand: wall 'far' passes through the body: its point (3, "),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("lies 0.5 m inside the body's outline"), std::string::npos) << message;
  EXPECT_NE(message.find("crosses_walls = true"), std::string::npos) << message;
  EXPECT_EQ(file_refusal(path, {"body.sand.crosses_walls=true"}), "");
}

TEST(SceneValidation, AWallWithinHalfASpacingOfTheBodysEdgeIsAccepted) {
  // dp 0.1: the lattice's last column is centred at 2.95 m either way; 0.06 m past the wall is
  // more than half a spacing, and refused
  const std::string path = bad_scene("body-crossing-wall.toml");
  EXPECT_EQ(file_refusal(path, {"body.sand.max=[3.04, 1.5]"}), "");
  EXPECT_NE(file_refusal(path, {"body.sand.max=[3.06, 1.5]"}).find("wall 'far' passes through"),
            std::string::npos);
}

TEST(SceneValidation, ABodyOnAWallsFarSideIsRefusedUnlessMeant) {
  // within reach of the divider (2h = 0.141 m): 30 particles of the column on its left, 18 of
  // the heap on its right; the methods put the divider's dummies and contact on the heap's side
  const std::string path = bad_scene("body-beyond-wall.toml");
  const std::string message = file_refusal(path, {});
  EXPECT_NE(message.find("body.heap: lies beyond wall 'divider': 18 of its particles near the "
                         "wall's segment (1, 0) - (1, 0.6) are on its far side, away from the "
                         "soil it holds (body 'column', 30 particles)"),
            std::string::npos)
      << message;
  EXPECT_EQ(file_refusal(path, {"body.heap.crosses_walls=true"}), "");
}

TEST(SceneValidation, AModulusOrStrengthInTheWrongUnitLoadsWithForce) {
  EXPECT_EQ(file_refusal(bad_scene("modulus-in-megapascals.toml"), {}, /*force=*/true), "");
  EXPECT_EQ(file_refusal(bad_scene("strength-in-kilopascals.toml"), {}, /*force=*/true), "");
  // 10 kPa is the least modulus taken without it
  EXPECT_EQ(file_refusal(bad_scene("modulus-in-megapascals.toml"), {"material.sand.E=1e4"}), "");
}

/// A 0.2 m x 0.1 m body on a floor, of `material` (a TOML table body), with `extra` tables.
std::string standing_scene(const std::string& material, const std::string& body,
                           const std::string& extra = "") {
  return "name = \"standing\"\nspacing = 0.01\ngravity = [0.0, -9.81]\n[time]\nend_time = 0.5\n"
         "[material.soil]\ndensity = 1800.0\n" +
         material + "\n[body.column]\nmaterial = \"soil\"\n" + body +
         "\n[wall.floor]\npoints = [[-0.1, 0.0], [0.6, 0.0]]\n" + extra;
}

const std::string kSand =
    "model = \"drucker-prager\"\nE = 1e7\nnu = 0.3\nphi = 30.0\npsi = 0.0\nc = 0.0";
const std::string kBlock = "min = [0.0, 0.0]\nmax = [0.2, 0.1]";

std::string steep_face(const std::string& text) {
  return face_steeper_than_friction(load_scene_checked_from_string(text, "scene.toml"));
}

TEST(StandingFaces, AVerticalFreeFaceOfCohesionlessSandCannotStand) {
  const std::string why = steep_face(standing_scene(kSand, kBlock));
  EXPECT_NE(why.find("body.column"), std::string::npos) << why;
  EXPECT_NE(why.find("free face at 90 deg"), std::string::npos) << why;
  EXPECT_NE(why.find("phi = 30 deg"), std::string::npos) << why;
}

TEST(StandingFaces, AFaceHeldByAWallOrACohesionOrWithoutGravityStands) {
  const std::string walls =
      "[wall.left]\npoints = [[0.0, 0.0], [0.0, 0.2]]\n"
      "[wall.right]\npoints = [[0.2, 0.0], [0.2, 0.2]]\n";
  EXPECT_EQ(steep_face(standing_scene(kSand, kBlock, walls)), "");
  std::string cohesive = kSand;
  cohesive.replace(cohesive.find("c = 0.0"), 7, "c = 5000.0");
  EXPECT_EQ(steep_face(standing_scene(cohesive, kBlock)), "");
  std::string weightless = standing_scene(kSand, kBlock);
  weightless.replace(weightless.find("gravity = [0.0, -9.81]"), 22, "gravity = [0.0, 0.0]");
  EXPECT_EQ(steep_face(weightless), "");
}

TEST(StandingFaces, ASlopeStandsUpToItsFrictionAngle) {
  // A wedge against a wall on the left, its free slope at atan(0.1 / 0.2) = 26.6 deg, then at
  // atan(0.1 / 0.1) = 45 deg: stands in phi 30, not beyond
  const std::string wall = "[wall.left]\npoints = [[0.0, 0.0], [0.0, 0.2]]\n";
  const std::string gentle = "shape = \"polygon\"\nvertices = [[0.0, 0.0], [0.2, 0.0], [0.0, 0.1]]";
  const std::string steep = "shape = \"polygon\"\nvertices = [[0.0, 0.0], [0.1, 0.0], [0.0, 0.1]]";
  EXPECT_EQ(steep_face(standing_scene(kSand, gentle, wall)), "");
  const std::string why = steep_face(standing_scene(kSand, steep, wall));
  EXPECT_NE(why.find("free face at 45 deg"), std::string::npos) << why;
}

TEST(StandingFaces, AHypoplasticSandGivenByItsConstantsCannotStandVertical) {
  const std::string sand =
      "model = \"hypoplastic\"\nc1 = -55.6\nc2 = -171.2\nc3 = -540.9\n"
      "c4 = -170.9";
  const std::string why = steep_face(standing_scene(sand, kBlock));
  EXPECT_NE(why.find("phi below 90 deg"), std::string::npos) << why;
}

}  // namespace
}  // namespace duet
