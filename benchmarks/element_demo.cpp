#include "benchmarks/element_demo.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <vector>

#include "benchmarks/element_command.hpp"
#include "common/input_error.hpp"
#include "constitutive/element_test.hpp"
#include "constitutive/registry.hpp"

namespace duet {

namespace {

using constitutive::ElementRow;
using constitutive::ElementTest;
using constitutive::ElementTestKind;
using constitutive::ParameterValue;

constexpr double demo_initial_stress = -100e3;  // Pa, isotropic start of both tests
constexpr double triaxial_strain = -0.10;       // axial strain at the end of the triaxial test
constexpr double oedometer_strain = -0.05;      // axial strain at the end of the oedometer test
constexpr int demo_increments = 100;

struct DemoLine {
  std::string model;
  double peak_q = NAN;          // Pa, triaxial
  double end_q = NAN;           // Pa, triaxial
  double end_volumetric = NAN;  // -, triaxial
  double k0 = NAN;              // sigma_lateral / sigma_axial at end of oedometer loading
  std::string problem;          // empty when both tests completed
  int status = 0;               // 0, 2 (refused parameters) or 3 (numerical failure)
};

ElementTest demo_test(ElementTestKind kind, double strain) {
  ElementTest t;
  t.kind = kind;
  t.initial_stress = demo_initial_stress;
  t.strain = strain;
  t.increments = demo_increments;
  return t;
}

/// Runs one test and writes its files under out_dir/<model>-<test>/; the rows, or empty with
/// `problem` set on numerical failure (rows so far are still written).
std::vector<ElementRow> run_one(const constitutive::Model& model, const std::string& name,
                                const std::map<std::string, ParameterValue>& resolved,
                                const ElementTest& test, const std::string& out_dir,
                                std::string& problem) {
  const std::string test_name = constitutive::element_test_name(test.kind);
  const std::string dir = out_dir + "/" + name + "-" + test_name;
  std::filesystem::create_directories(dir);
  std::vector<ElementRow> rows;
  std::string failure;
  try {
    rows = constitutive::run_element_test(model, test);
  } catch (const constitutive::ElementTestFailure& e) {
    rows = e.rows();
    failure = e.what();
  }
  write_element_csv(dir + "/element.csv", rows);
  write_element_json(dir + "/element.json", name, resolved, test, rows, failure);
  plot_element(dir + "/element.csv", dir + "/element.png", name + " " + test_name);
  if (!failure.empty()) {
    problem += (problem.empty() ? "" : "; ") + failure;
    return {};
  }
  return rows;
}

DemoLine run_model(const constitutive::ModelInfo& info, const std::string& out_dir) {
  DemoLine line;
  line.model = info.name;
  std::map<std::string, ParameterValue> resolved;
  std::unique_ptr<constitutive::Model> model;
  try {
    model = constitutive::make_model(info.name, info.example, "demo." + info.name, &resolved);
  } catch (const InputError& e) {
    line.problem = std::string("example parameters refused: ") + e.what();
    line.status = 2;
    return line;
  }
  const auto triaxial =
      run_one(*model, info.name, resolved, demo_test(ElementTestKind::triaxial, triaxial_strain),
              out_dir, line.problem);
  if (!triaxial.empty()) {
    for (const auto& row : triaxial)
      line.peak_q = std::isnan(line.peak_q) ? row.q : std::max(line.peak_q, row.q);
    line.end_q = triaxial.back().q;
    line.end_volumetric = triaxial.back().volumetric_strain;
  }
  const auto oedometer =
      run_one(*model, info.name, resolved, demo_test(ElementTestKind::oedometer, oedometer_strain),
              out_dir, line.problem);
  if (!oedometer.empty()) {
    const ElementRow& loaded = oedometer[demo_increments];
    line.k0 =
        loaded.lateral_stress / loaded.axial_stress;  // Peng 2015 sec 5.1: K0 = sigma_3/sigma_1
  }
  if (!line.problem.empty()) line.status = 3;
  return line;
}

std::string cell(double v, double scale, int precision) {
  if (std::isnan(v)) return "failed";
  std::ostringstream out;
  out << std::fixed << std::setprecision(precision) << v / scale;
  return out.str();
}

std::string table(const std::vector<DemoLine>& lines) {
  std::ostringstream out;
  out << "| model | peak q (kPa) | q at end (kPa) | volumetric strain at end | K0 (oedometer) |\n"
      << "|---|---:|---:|---:|---:|\n";
  for (const auto& l : lines) {
    out << "| " << l.model << " | " << cell(l.peak_q, 1e3, 1) << " | " << cell(l.end_q, 1e3, 1)
        << " | " << cell(l.end_volumetric, 1.0, 5) << " | " << cell(l.k0, 1.0, 4) << " |\n";
  }
  out << "\nDrained triaxial from " << demo_initial_stress / 1e3 << " kPa to "
      << triaxial_strain * 100 << " % axial strain; oedometer to " << oedometer_strain * 100
      << " %; " << demo_increments << " increments each; volumetric strain negative in "
      << "compaction; K0 = lateral / axial stress at the end of oedometer loading.\n";
  for (const auto& l : lines) {
    if (!l.problem.empty()) out << "\n" << l.model << ": " << l.problem << '\n';
  }
  return out.str();
}

}  // namespace

int run_element_demo(const std::string& out_dir) {
  std::filesystem::create_directories(out_dir);
  std::vector<DemoLine> lines;
  for (const auto& info : constitutive::builtin_models().models()) {
    lines.push_back(run_model(info, out_dir));
  }
  const std::string text = table(lines);
  std::ofstream(out_dir + "/element_demo.md") << text;
  std::cout << text << "results: " << out_dir << '\n';
  int status = 0;
  for (const auto& l : lines) status = std::max(status, l.status);
  return status;
}

}  // namespace duet
