// RunWriter: frames written to run.h5 read back exactly, the XDMF names datasets that exist with
// the shapes it states, the file pair is valid while the writer is still open, series and
// metadata round trip, and failures name the path.

#include "common/h5_writer.hpp"

#include "common/state_bag.hpp"

#include <hdf5.h>

#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace duet {
namespace {

namespace fs = std::filesystem;

/// A fresh directory per test.
fs::path test_directory() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::temp_directory_path() /
                       ("duet_h5_writer_test_" + std::to_string(::getpid()) + "_" + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// n particles whose every value is distinct and depends on `seed`; two materials, the first with
/// internal variables (void_ratio, corrections), the second with void_ratio only.
Particles make_particles(std::size_t n, double seed) {
  Particles p;
  p.internal.names = {"void_ratio", "corrections"};
  p.internal.slot = {{0, 1}, {0, -1}};
  p.internal.width = 2;
  p.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double s = seed + 0.1 * static_cast<double>(i);
    p.position[i] = Vec2(s + 1.0 / 3.0, -s * 0.7);
    p.velocity[i] = Vec2(2.0 * s, -3.0 * s);
    p.displacement[i] = Vec2(1e-3 * s, -1e-4 * s);
    p.mass[i] = 1.5 + s;
    p.volume[i] = 1e-4 * (1.0 + s);
    p.density[i] = 2000.0 + s;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        p.stress[i](r, c) = -1000.0 * s - 10.0 * (r + c) - (r == c ? 500.0 * r : 0.0);
        p.strain[i](r, c) = 1e-3 * (s + r - c * c) * (r == c ? 2.0 : 1.0);
      }
    }
    p.stress[i] = 0.5 * (p.stress[i] + p.stress[i].transpose()).eval();
    p.body[i] = static_cast<std::int32_t>(i % 2);
    p.material[i] = static_cast<std::int32_t>(i % 2);
    p.internal.of(i)[0] = 0.6 + 0.01 * s;                 // void_ratio
    p.internal.of(i)[1] = static_cast<double>(i) + seed;  // corrections (material 0 only)
  }
  return p;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Value of attribute `name` in the XML start tag `tag` ("" when absent).
std::string attribute(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const std::size_t at = tag.find(key);
  if (at == std::string::npos) return "";
  const std::size_t begin = at + key.size();
  return tag.substr(begin, tag.find('"', begin) - begin);
}

std::vector<hsize_t> parse_dimensions(const std::string& text) {
  std::vector<hsize_t> dims;
  std::istringstream in(text);
  for (hsize_t d; in >> d;) dims.push_back(d);
  return dims;
}

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++n;
  }
  return n;
}

struct OpenFile {
  hid_t id;
  ~OpenFile() {
    if (id >= 0) H5Fclose(id);
  }
};

hid_t open_unlocked(const fs::path& path) {
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_file_locking(fapl, false, true);
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl);
  H5Pclose(fapl);
  return file;
}

/// Walks run.xdmf in `dir`: every DataItem must name an existing dataset at the root of a frame
/// file frames/NNNNNN.h5 that run.h5 links as /frames/NNNNNN, with the dimensions of its
/// Dimensions; attribute types must match the column count; the Topology's NumberOfElements must
/// equal the rows of the geometry. Returns the number of DataItems checked.
std::size_t check_xdmf_against_h5(const fs::path& dir) {
  const std::string xdmf = read_text(dir / "run.xdmf");
  const hid_t index = open_unlocked(dir / "run.h5");
  EXPECT_GE(index, 0) << dir / "run.h5";
  if (index < 0) return 0;

  std::size_t checked = 0;
  std::string enclosing;            // start tag of the Attribute or Geometry around the item
  std::size_t topology_points = 0;  // NumberOfElements of the current grid
  for (std::size_t at = xdmf.find('<'); at != std::string::npos; at = xdmf.find('<', at + 1)) {
    const std::string tag = xdmf.substr(at, xdmf.find('>', at) - at + 1);
    if (tag.rfind("<Topology", 0) == 0) {
      EXPECT_EQ(attribute(tag, "TopologyType"), "Polyvertex");
      topology_points = std::stoul(attribute(tag, "NumberOfElements"));
      enclosing = tag;
    } else if (tag.rfind("<Attribute", 0) == 0 || tag.rfind("<Geometry", 0) == 0) {
      enclosing = tag;
    } else if (tag.rfind("<DataItem", 0) == 0) {
      const std::size_t text_begin = at + tag.size();
      const std::string text = xdmf.substr(text_begin, xdmf.find('<', text_begin) - text_begin);
      const std::size_t colon = text.find(':');
      const std::string frame_file = text.substr(0, colon);  // frames/NNNNNN.h5
      EXPECT_EQ(frame_file.rfind("frames/", 0), 0u) << text;
      if (frame_file.rfind("frames/", 0) != 0) continue;
      const std::string number = frame_file.substr(7, frame_file.size() - 7 - 3);
      EXPECT_GT(H5Lexists(index, ("/frames/" + number).c_str(), H5P_DEFAULT), 0) << text;
      const std::string dataset = text.substr(colon + 1);
      EXPECT_EQ(dataset.rfind('/'), 0u) << dataset;  // at the file's root
      const std::vector<hsize_t> stated = parse_dimensions(attribute(tag, "Dimensions"));

      const OpenFile opened{open_unlocked(dir / frame_file)};
      const hid_t file = opened.id;
      EXPECT_GE(file, 0) << frame_file;
      if (file < 0) continue;
      EXPECT_GT(H5Lexists(file, dataset.c_str(), H5P_DEFAULT), 0) << text;
      const hid_t set = H5Dopen2(file, dataset.c_str(), H5P_DEFAULT);
      EXPECT_GE(set, 0) << text;
      if (set < 0) continue;
      const hid_t space = H5Dget_space(set);
      std::vector<hsize_t> actual(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
      H5Sget_simple_extent_dims(space, actual.data(), nullptr);
      H5Sclose(space);
      H5Dclose(set);
      EXPECT_EQ(stated, actual) << dataset;

      EXPECT_FALSE(stated.empty()) << dataset;
      if (stated.empty()) continue;
      EXPECT_EQ(stated[0], topology_points) << dataset;
      const std::size_t columns = stated.size() == 1 ? 1 : stated[1];
      std::string type = attribute(enclosing, "AttributeType");
      if (enclosing.rfind("<Geometry", 0) == 0) type = "Geometry";
      if (enclosing.rfind("<Topology", 0) == 0) type = "Topology";
      if (type == "Topology") {
        // One vertex cell per particle: the connectivity is 0, 1, ..., n-1.
        EXPECT_EQ(stated.size(), 1u) << dataset;
        EXPECT_EQ(attribute(tag, "NumberType"), "Int") << dataset;
        std::vector<int> vertices(stated[0]);
        const hid_t connectivity = H5Dopen2(file, dataset.c_str(), H5P_DEFAULT);
        H5Dread(connectivity, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, vertices.data());
        H5Dclose(connectivity);
        for (std::size_t i = 0; i < vertices.size(); ++i) {
          EXPECT_EQ(vertices[i], static_cast<int>(i)) << dataset;
        }
      } else if (type == "Geometry" || type == "Vector") {
        EXPECT_EQ(columns, 3u) << dataset;
      } else if (type == "Tensor") {
        EXPECT_EQ(columns, 9u) << dataset;
      } else {
        EXPECT_EQ(type, "Scalar") << dataset;
        EXPECT_EQ(stated.size(), 1u) << dataset;
      }
      ++checked;
    }
  }
  H5Fclose(index);
  return checked;
}

TEST(RunWriter, TwoFramesReadBackExactly) {
  // Arrange
  const fs::path dir = test_directory();
  const Particles first = make_particles(5, 0.25);
  const Particles second = make_particles(5, 1.75);
  // Act
  {
    RunWriter writer(dir.string());
    writer.write_frame(0.0, first);
    writer.write_frame(0.125, second);
  }
  // Assert
  const std::string h5 = (dir / "run.h5").string();
  ASSERT_EQ(count_frames(h5), 2u);
  const Particles* expected[] = {&first, &second};
  const double times[] = {0.0, 0.125};
  for (std::size_t f = 0; f < 2; ++f) {
    const Frame frame = read_frame(h5, f);
    const Particles& p = *expected[f];
    EXPECT_EQ(frame.time, times[f]);
    ASSERT_EQ(frame.position.size(), p.size());
    ASSERT_EQ(frame.stress.size(), p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
      EXPECT_EQ(frame.position[i].x(), p.position[i].x());
      EXPECT_EQ(frame.position[i].y(), p.position[i].y());
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) EXPECT_EQ(frame.stress[i](r, c), p.stress[i](r, c));
      }
      EXPECT_EQ(frame.scalars.at("void_ratio")[i], p.internal.of(i)[0]);
      EXPECT_EQ(frame.scalars.at("mass")[i], p.mass[i]);
      EXPECT_EQ(frame.scalars.at("material")[i], p.material[i]);
    }
  }
}

TEST(RunWriter, InternalVariableAMaterialLacksIsNaN) {
  // Arrange
  const fs::path dir = test_directory();
  const Particles particles = make_particles(4, 0.5);  // odd particles: material 1, no corrections
  // Act
  {
    RunWriter writer(dir.string());
    writer.write_frame(1.0, particles);
  }
  // Assert
  const Frame frame = read_frame((dir / "run.h5").string(), 0);
  const std::vector<double>& corrections = frame.scalars.at("corrections");
  EXPECT_EQ(corrections[0], particles.internal.of(0)[1]);
  EXPECT_EQ(corrections[2], particles.internal.of(2)[1]);
  EXPECT_TRUE(std::isnan(corrections[1]));
  EXPECT_TRUE(std::isnan(corrections[3]));
}

TEST(RunWriter, DerivedScalarsFollowTheirDefinitions) {
  // Arrange: particle 0 isotropic compression, particle 1 pure shear with a deviatoric strain.
  const fs::path dir = test_directory();
  Particles particles = make_particles(2, 0.0);
  particles.stress[0] = Mat3::Zero();
  particles.stress[0].diagonal() << -100e3, -200e3, -300e3;
  particles.strain[0] = -1e-3 * Mat3::Identity();  // purely volumetric
  const double tau = 40e3;
  const double eps = 2e-3;
  particles.stress[1] = Mat3::Zero();
  particles.stress[1](0, 1) = particles.stress[1](1, 0) = tau;
  particles.strain[1] = Mat3::Zero();
  particles.strain[1].diagonal() << eps, -eps, 0.0;  // already deviatoric
  // Act
  {
    RunWriter writer(dir.string());
    writer.write_frame(0.0, particles);
  }
  // Assert
  const Frame frame = read_frame((dir / "run.h5").string(), 0);
  // p = -tr(sigma)/3, compression positive.
  EXPECT_DOUBLE_EQ(frame.scalars.at("pressure")[0], 200e3);
  EXPECT_DOUBLE_EQ(frame.scalars.at("pressure")[1], 0.0);
  // q = sqrt(3 J2): q(pure shear tau) = sqrt(3) tau; q of diag(-100, -200, -300) kPa:
  // J2 = ((100)^2 + (100)^2 + (200)^2)/6 kPa^2 = 1e4 kPa^2 -> q = sqrt(3) * 100 kPa.
  EXPECT_NEAR(frame.scalars.at("von_mises")[1], std::sqrt(3.0) * tau, 1e-9 * tau);
  EXPECT_NEAR(frame.scalars.at("von_mises")[0], std::sqrt(3.0) * 100e3, 1e-9 * 100e3);
  // eq strain = sqrt(2/3 e:e): 0 for volumetric strain, sqrt(2/3 * 2 eps^2) = 2 eps / sqrt(3).
  EXPECT_NEAR(frame.scalars.at("equivalent_strain")[0], 0.0, 1e-15);
  EXPECT_NEAR(frame.scalars.at("equivalent_strain")[1], 2.0 * eps / std::sqrt(3.0), 1e-15);
}

TEST(RunWriter, XdmfNamesDatasetsThatExistWithTheirShapes) {
  // Arrange
  const fs::path dir = test_directory();
  const std::vector<double> times = {0.0, 0.05, 0.1};
  // Act
  {
    RunWriter writer(dir.string());
    for (std::size_t f = 0; f < times.size(); ++f) {
      writer.write_frame(times[f], make_particles(7, static_cast<double>(f)));
    }
  }
  // Assert
  const std::string xdmf = read_text(dir / "run.xdmf");
  EXPECT_EQ(count_of(xdmf, "GridType=\"Uniform\""), times.size());
  EXPECT_EQ(count_of(xdmf, "CollectionType=\"Temporal\""), 1u);
  EXPECT_EQ(count_of(xdmf, "<Time Value=\"0.050000000000000003\"/>"), 1u);
  // Per frame: topology, geometry, velocity, displacement, stress, strain, mass, volume, density,
  // body, material, pressure, von_mises, equivalent_strain (14) + 2 internal variables = 16 items.
  EXPECT_EQ(check_xdmf_against_h5(dir), 16u * times.size());
  EXPECT_EQ(count_of(xdmf, "AttributeType=\"Tensor\""), 2u * times.size());
  EXPECT_EQ(count_of(xdmf, "Name=\"void_ratio\""), times.size());
}

TEST(RunWriter, PairIsValidAfterEachFrameBeforeTheWriterCloses) {
  // Arrange
  const fs::path dir = test_directory();
  const fs::path snapshot = dir / "snapshot";
  fs::create_directories(snapshot);
  RunWriter writer((dir / "out").string());
  const Particles particles = make_particles(3, 2.0);
  // Act: one frame, then copy the folder as a run killed now would leave it.
  writer.write_frame(0.5, particles);
  fs::copy(dir / "out", snapshot, fs::copy_options::recursive);
  // Assert: the copy (elsewhere: run.h5 links its frames relative to its own folder) holds the
  // frame, and its XDMF names only datasets that exist.
  ASSERT_EQ(count_frames((snapshot / "run.h5").string()), 1u);
  const Frame copied = read_frame((snapshot / "run.h5").string(), 0);
  EXPECT_EQ(copied.time, 0.5);
  EXPECT_EQ(copied.position[2].x(), particles.position[2].x());
  EXPECT_EQ(check_xdmf_against_h5(snapshot), 16u);
  // The live folder reads too, while the writer goes on.
  const Frame live = read_frame(writer.h5_path(), 0);
  EXPECT_EQ(live.stress[1](0, 1), particles.stress[1](0, 1));
}

TEST(RunWriter, AnEarlierRunsFrameFilesInTheFolderAreRemoved) {
  // Arrange: a run of three frames in the folder.
  const fs::path dir = test_directory();
  {
    RunWriter writer(dir.string());
    for (const double t : {0.0, 0.1, 0.2}) writer.write_frame(t, make_particles(2, t));
  }
  // Act: a second run in the same folder writes one.
  {
    RunWriter writer(dir.string());
    writer.write_frame(0.0, make_particles(2, 5.0));
  }
  // Assert: only its frame is there, in run.h5 and on disk.
  EXPECT_EQ(count_frames((dir / "run.h5").string()), 1u);
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir / "frames")) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "000000.h5");
  }
  EXPECT_EQ(files, 1u);
}

TEST(RunWriter, StateAndParticlesOfAFrameReadBackExactly) {
  // Arrange
  const fs::path dir = test_directory();
  const Particles written = make_particles(4, 0.123456789);
  StateBag state;
  put(state, "driver.time", 0.1 + 0.2);
  put(state, "solver.previous_u", written.velocity);
  put_bits(state, "solver.contact", std::vector<std::uint64_t>{0, 1, ~std::uint64_t{0}});
  put_lists(state, "solver.residual_history", {{1.0, 1e-3, 1e-9}, {}, {0.5}});
  // Act
  {
    RunWriter writer(dir.string());
    writer.write_frame(0.0, written, {}, &state);
  }
  const StateBag read = read_state((dir / "run.h5").string(), 0);
  Particles particles = make_particles(4, 9.0);  // other values, same shapes
  read_particle_state((dir / "run.h5").string(), 0, particles);
  // Assert: every entry and every particle array to the last bit.
  EXPECT_EQ(read, state);
  std::vector<std::uint64_t> bits;
  get_bits(read, "solver.contact", bits);
  EXPECT_EQ(bits.back(), ~std::uint64_t{0});
  std::vector<std::vector<double>> lists;
  get_lists(read, "solver.residual_history", lists);
  EXPECT_EQ(lists, (std::vector<std::vector<double>>{{1.0, 1e-3, 1e-9}, {}, {0.5}}));
  EXPECT_EQ(particles.position, written.position);
  EXPECT_EQ(particles.velocity, written.velocity);
  EXPECT_EQ(particles.displacement, written.displacement);
  EXPECT_EQ(particles.stress, written.stress);
  EXPECT_EQ(particles.strain, written.strain);
  EXPECT_EQ(particles.mass, written.mass);
  EXPECT_EQ(particles.volume, written.volume);
  EXPECT_EQ(particles.density, written.density);
  EXPECT_EQ(particles.body, written.body);
  EXPECT_EQ(particles.material, written.material);
  // A frame without state reads as an empty bag; a particle count that differs is refused.
  {
    RunWriter writer((dir / "plain").string());
    writer.write_frame(0.0, written);
  }
  EXPECT_TRUE(read_state((dir / "plain" / "run.h5").string(), 0).empty());
  Particles fewer = make_particles(3, 0.0);
  EXPECT_THROW(read_particle_state((dir / "run.h5").string(), 0, fewer), std::runtime_error);
}

TEST(RunWriter, ContinuingAfterAFrameKeepsItAndTheFramesBefore) {
  // Arrange: four frames.
  const fs::path dir = test_directory();
  {
    RunWriter writer(dir.string());
    for (const double t : {0.0, 0.1, 0.2, 0.3}) writer.write_frame(t, make_particles(2, t));
  }
  // Act: go on after frame 1 and write one more.
  {
    RunWriter writer(dir.string(), RunWriter::ContinueAfter{1});
    EXPECT_EQ(writer.n_frames(), 2u);
    writer.write_frame(0.15, make_particles(2, 7.0));
  }
  // Assert: frames 0, 1 as they were, 2 the new one, 3 gone from the index and the disk; the
  // XDMF names what exists.
  const std::string h5 = (dir / "run.h5").string();
  ASSERT_EQ(count_frames(h5), 3u);
  EXPECT_EQ(read_frame(h5, 1).time, 0.1);
  EXPECT_EQ(read_frame(h5, 1).position[0].x(), make_particles(2, 0.1).position[0].x());
  EXPECT_EQ(read_frame(h5, 2).time, 0.15);
  EXPECT_FALSE(fs::exists(dir / "frames" / "000003.h5"));
  EXPECT_EQ(check_xdmf_against_h5(dir), 3u * 16u);
}

TEST(RunWriter, FrameAtTheSameTimeReplacesThePreviousOne) {
  // Arrange
  const fs::path dir = test_directory();
  const Particles before = make_particles(3, 0.0);
  const Particles after = make_particles(3, 9.0);
  // Act
  {
    RunWriter writer(dir.string());
    writer.write_frame(0.0, before);
    writer.write_frame(0.2, before);
    writer.write_frame(0.2, after);
    EXPECT_EQ(writer.n_frames(), 2u);
  }
  // Assert
  const std::string h5 = (dir / "run.h5").string();
  EXPECT_EQ(count_frames(h5), 2u);
  EXPECT_EQ(read_frame(h5, 1).position[0].x(), after.position[0].x());
  EXPECT_EQ(check_xdmf_against_h5(dir), 2u * 16u);
}

TEST(RunWriter, SeriesAreRewrittenWithTheirFullLength) {
  // Arrange
  const fs::path dir = test_directory();
  const std::vector<std::string> names = {"time", "runout", "force/wall"};
  std::vector<std::vector<double>> columns = {{0.0, 0.1}, {0.0, 0.01}, {5.0, 6.0}};
  // Act: written at a frame, then again at the end with more samples.
  {
    RunWriter writer(dir.string());
    writer.write_series(names, columns);
    for (std::size_t k = 0; k < 2000; ++k) {  // longer than one chunk
      columns[0].push_back(0.2 + 1e-3 * static_cast<double>(k));
      columns[1].push_back(0.02 + 1e-5 * static_cast<double>(k));
      columns[2].push_back(-static_cast<double>(k));
    }
    writer.write_series(names, columns);
  }
  // Assert
  const std::string h5 = (dir / "run.h5").string();
  EXPECT_EQ(read_series(h5, "time"), columns[0]);
  EXPECT_EQ(read_series(h5, "runout"), columns[1]);
  EXPECT_EQ(read_series(h5, "force/wall"), columns[2]);  // stored as force_wall
}

TEST(RunWriter, SeriesWithMismatchedNamesAndColumnsIsRefused) {
  // Arrange
  const fs::path dir = test_directory();
  RunWriter writer(dir.string());
  // Act / Assert
  EXPECT_THROW(writer.write_series({"time", "runout"}, {{0.0}}), std::runtime_error);
}

TEST(RunWriter, MetadataRoundTrips) {
  // Arrange
  const fs::path dir = test_directory();
  const std::string toml = "name = \"collapse\"\nspacing = 0.002\n[material.sand]\nphi = 30.0\n";
  // Act
  {
    RunWriter writer(dir.string());
    writer.write_metadata("collapse", "sph", toml, "0123abcd", 0.002);
  }
  // Assert
  const RunMetadata m = read_metadata((dir / "run.h5").string());
  EXPECT_EQ(m.scene, "collapse");
  EXPECT_EQ(m.method, "sph");
  EXPECT_EQ(m.scene_toml, toml);
  EXPECT_EQ(m.git_commit, "0123abcd");
  EXPECT_EQ(m.spacing, 0.002);
}

TEST(RunWriter, FailureToCreateTheFileNamesThePath) {
  // Arrange: run.h5 exists as a directory, so HDF5 cannot create the file.
  const fs::path dir = test_directory();
  fs::create_directories(dir / "run.h5");
  // Act / Assert
  try {
    RunWriter writer(dir.string());
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "run.h5").string()), std::string::npos) << e.what();
  }
}

TEST(RunWriter, ReadingAMissingFileNamesThePath) {
  // Arrange
  const fs::path missing = test_directory() / "nothing" / "run.h5";
  // Act / Assert
  try {
    read_frame(missing.string(), 0);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
}

TEST(RunWriter, ReadingAFrameBeyondTheLastIsRefused) {
  // Arrange
  const fs::path dir = test_directory();
  {
    RunWriter writer(dir.string());
    writer.write_frame(0.0, make_particles(2, 0.0));
  }
  // Act / Assert
  EXPECT_THROW(read_frame((dir / "run.h5").string(), 1), std::runtime_error);
}

}  // namespace
}  // namespace duet
