// run.xdmf as ParaView reads it: each method's footing run (walls, a rigid footing pushed down,
// and for SPFEM the mesh), and the circular footing's axisymmetric run, opened with ParaView's own
// XDMF reader by pvbatch, every time step checked against run.h5 and the footing's schedule
// (tests/benchmarks/paraview_read_check.py).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/benchmarks/child_run.hpp"

namespace duet {
namespace {

namespace fs = std::filesystem;

struct Case {
  const char* method;
  const char* kind;   // what the check expects: "sph" (no mesh) or "spfem"
  const char* scene;  // a benchmark scene with four boundaries and a rigid footing
  const char* name;   // the test's name
};

class XdmfInParaView : public testing::TestWithParam<Case> {};

TEST_P(XdmfInParaView, ShowsParticlesBoundariesAndMeshAtEveryFrame) {
  const Case c = GetParam();
  const fs::path out = fs::temp_directory_path() / ("duet-xdmf-" + std::string(c.name));
  fs::remove_all(out);
  const std::string scene = std::string(DUET_SOURCE_DIR) + "/benchmarks/scenes/" + c.scene;
  const test::DuetResult run = test::run_duet(
      "run '" + scene + "' --method " + c.method +
      " --spacing 0.25 --set time.end_time=0.2 --set time.output_interval=0.05 --quiet --out '" +
      out.string() + "'");
  ASSERT_EQ(run.status, 0) << run.output;
  const std::string script =
      std::string(DUET_SOURCE_DIR) + "/tests/benchmarks/paraview_read_check.py";
  // pvbatch: ParaView's batch Python, installed by `./duet test`.
  const std::string command = "pvbatch '" + script + "' '" + out.string() + "' " + c.kind;
  const test::DuetResult check = test::run_command(command);
  const std::string& output = check.output;
  EXPECT_EQ(check.status, 0) << command << "\n" << output;
  EXPECT_NE(output.find("ok: 5 time steps, 4 boundaries"), std::string::npos) << output;
  fs::remove_all(out);
}

INSTANTIATE_TEST_SUITE_P(
    Methods, XdmfInParaView,
    testing::Values(Case{"sph", "sph", "footing.toml", "sph"},
                    Case{"espfem", "spfem", "footing.toml", "espfem"},
                    Case{"ispfem", "spfem", "footing.toml", "ispfem"},
                    // the r-z plane of an axisymmetric run
                    Case{"ispfem", "spfem", "footing-circular.toml", "ispfem_axisymmetric"}),
    [](const testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace duet
