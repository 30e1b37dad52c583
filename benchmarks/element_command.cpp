#include "benchmarks/element_command.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "benchmarks/git_commit.hpp"
#include "benchmarks/plotting.hpp"
#include "common/input_error.hpp"
#include "common/json.hpp"
#include "constitutive/registry.hpp"

namespace duet {

namespace {

using constitutive::ElementRow;
using constitutive::ElementTest;
using constitutive::ElementTestKind;
using constitutive::Parameters;
using constitutive::ParameterValue;
using constitutive::Range;

constexpr const char* test_keys[] = {"initial_stress", "strain", "increments", "unload_to"};

bool is_test_key(const std::string& name) {
  for (const char* key : test_keys)
    if (name == key) return true;
  return false;
}

std::string text(double v) {
  std::ostringstream out;
  out << std::setprecision(12) << v;
  return out.str();
}

std::string text(const ParameterValue& v) {
  if (const double* d = std::get_if<double>(&v)) return text(*d);
  return std::get<std::string>(v);
}

/// "NAME=VALUE" -> (NAME, number or word).
std::pair<std::string, ParameterValue> parse_set(const std::string& set) {
  const auto eq = set.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == set.size()) {
    throw InputError("--set " + set + ": expected NAME=VALUE (e.g. --set nu=0.3)");
  }
  const std::string name = set.substr(0, eq);
  const std::string value = set.substr(eq + 1);
  char* end = nullptr;
  const double number = std::strtod(value.c_str(), &end);
  if (end == value.c_str() + value.size()) return {name, number};
  return {name, value};
}

double default_strain(ElementTestKind kind) {
  switch (kind) {
    case ElementTestKind::oedometer:
      return -0.05;
    case ElementTestKind::triaxial:
      return -0.1;
    case ElementTestKind::simple_shear:
      return 0.1;
  }
  return -0.1;
}

/// The test keys, with ranges and units; what the test resolves to is recorded in `resolved`.
ElementTest read_test(ElementTestKind kind, std::map<std::string, ParameterValue> values) {
  Parameters p("element", std::move(values));
  ElementTest test;
  test.kind = kind;
  test.initial_stress = p.optional("initial_stress", -100e3, Range{-1e308, 0.0, false, false}, "Pa",
                                   "isotropic initial stress (negative in compression)");
  test.strain = p.optional("strain", default_strain(kind), Range::any(), "-",
                           kind == ElementTestKind::simple_shear
                               ? "final engineering shear strain gamma_xy"
                               : "final axial strain (compression negative)");
  const double increments = p.optional("increments", 100, Range::closed(1, 1e7), "-",
                                       "number of equal strain increments");
  if (increments != std::floor(increments)) {
    throw InputError("element.increments = " + text(increments) +
                     ": number of equal strain increments must be a whole number in [1, 1e+07] "
                     "(unit -)");
  }
  test.increments = static_cast<int>(increments);
  if (p.has("unload_to")) {
    test.unload_to = p.require("unload_to", Range::any(), "-",
                               "axial strain to unload to after loading (oedometer)");
  }
  p.finish();
  constitutive::validate(test);
  return test;
}

struct ElementArgs {
  std::string model;
  std::string test;
  std::vector<std::string> sets;
  std::string out;
};

void print_resolved(std::ostream& out, const std::string& model,
                    const std::map<std::string, ParameterValue>& parameters,
                    const ElementTest& test) {
  out << "model " << model << ", resolved parameters:\n";
  for (const auto& [name, value] : parameters) out << "  " << name << " = " << text(value) << '\n';
  out << "test " << constitutive::element_test_name(test.kind) << ":\n"
      << "  initial_stress = " << text(test.initial_stress) << " Pa\n"
      << "  strain = " << text(test.strain) << '\n'
      << "  increments = " << test.increments << '\n';
  if (test.unload_to) out << "  unload_to = " << text(*test.unload_to) << '\n';
}

void print_summary(std::ostream& out, const ElementTest& test,
                   const std::vector<ElementRow>& rows) {
  const ElementRow& end = rows.back();
  out << "final state after " << rows.size() - 1 << " increments:\n"
      << "  axial strain " << text(end.axial_strain) << ", lateral strain "
      << text(end.lateral_strain) << ", volumetric strain " << text(end.volumetric_strain)
      << ", shear strain " << text(end.shear_strain) << '\n'
      << "  axial stress " << text(end.axial_stress) << " Pa, lateral stress "
      << text(end.lateral_stress) << " Pa, shear stress " << text(end.shear_stress) << " Pa\n"
      << "  p " << text(end.p) << " Pa, q " << text(end.q) << " Pa";
  if (test.kind == ElementTestKind::oedometer) {
    const ElementRow& loaded = rows[test.increments];
    out << ", K0 at end of loading " << text(loaded.lateral_stress / loaded.axial_stress);
  }
  if (std::isfinite(end.void_ratio)) out << ", void ratio " << text(end.void_ratio);
  out << '\n';
}

Json row_json(const ElementRow& row) {
  Json j = Json::object();
  j["axial_strain"] = row.axial_strain;
  j["lateral_strain"] = row.lateral_strain;
  j["volumetric_strain"] = row.volumetric_strain;
  j["shear_strain"] = row.shear_strain;
  j["axial_stress"] = row.axial_stress;
  j["lateral_stress"] = row.lateral_stress;
  j["out_of_plane_stress"] = row.out_of_plane_stress;
  j["shear_stress"] = row.shear_stress;
  j["p"] = row.p;
  j["q"] = row.q;
  j["void_ratio"] = row.void_ratio;  // null when the model has none
  j["corrections"] = row.corrections;
  return j;
}

void run_element(const ElementArgs& args, int& exit_code) {
  std::map<std::string, ParameterValue> model_values, test_values;
  for (const auto& set : args.sets) {
    auto [name, value] = parse_set(set);
    (is_test_key(name) ? test_values : model_values)[name] = value;
  }
  std::map<std::string, ParameterValue> resolved;
  const auto model = constitutive::make_model(args.model, model_values, "element", &resolved);
  const ElementTest test =
      read_test(constitutive::parse_element_test_kind(args.test), std::move(test_values));
  print_resolved(std::cout, args.model, resolved, test);

  const std::string out =
      args.out.empty() ? "runs/element-" + args.model + "-" + args.test : args.out;
  std::filesystem::create_directories(out);
  std::vector<ElementRow> rows;
  std::string failure;
  try {
    rows = constitutive::run_element_test(*model, test);
  } catch (const constitutive::ElementTestFailure& e) {
    rows = e.rows();
    failure = e.what();
  }
  write_element_csv(out + "/element.csv", rows);
  write_element_json(out + "/element.json", args.model, resolved, test, rows, failure);
  if (failure.empty()) print_summary(std::cout, test, rows);
  plot_element(out + "/element.csv", out + "/element.png",
               args.model + " " + constitutive::element_test_name(test.kind));
  std::cout << "results: " << out << '\n';
  if (!failure.empty()) {
    std::cerr << "duet element: test failed: " << failure << '\n';
    exit_code = 3;
    return;
  }
  exit_code = 0;
}

}  // namespace

const std::vector<std::string>& element_csv_columns() {
  static const std::vector<std::string> columns = {"axial_strain",
                                                   "lateral_strain",
                                                   "volumetric_strain",
                                                   "shear_strain",
                                                   "axial_stress",
                                                   "lateral_stress",
                                                   "out_of_plane_stress",
                                                   "shear_stress",
                                                   "p",
                                                   "q",
                                                   "void_ratio",
                                                   "corrections"};
  return columns;
}

void write_element_csv(const std::string& path, const std::vector<ElementRow>& rows) {
  std::ofstream file(path);
  if (!file) throw std::runtime_error("cannot write " + path);
  const auto& columns = element_csv_columns();
  for (std::size_t i = 0; i < columns.size(); ++i) file << (i ? "," : "") << columns[i];
  file << '\n';
  file << std::setprecision(12);
  for (const auto& r : rows) {
    const double values[] = {r.axial_strain,
                             r.lateral_strain,
                             r.volumetric_strain,
                             r.shear_strain,
                             r.axial_stress,
                             r.lateral_stress,
                             r.out_of_plane_stress,
                             r.shear_stress,
                             r.p,
                             r.q,
                             r.void_ratio,
                             r.corrections};
    for (std::size_t i = 0; i < std::size(values); ++i) {
      file << (i ? "," : "");
      if (std::isnan(values[i]))
        file << "nan";
      else
        file << values[i] + 0.0;  // + 0.0 writes -0 as 0
    }
    file << '\n';
  }
}

void write_element_json(const std::string& path, const std::string& model,
                        const std::map<std::string, ParameterValue>& parameters,
                        const ElementTest& test, const std::vector<ElementRow>& rows,
                        const std::string& failure) {
  Json j = Json::object();
  j["model"] = model;
  Json& p = j["parameters"];
  p = Json::object();
  for (const auto& [name, value] : parameters) {
    if (const double* d = std::get_if<double>(&value))
      p[name] = *d;
    else
      p[name] = std::get<std::string>(value);
  }
  Json& t = j["test"];
  t = Json::object();
  t["kind"] = constitutive::element_test_name(test.kind);
  t["initial_stress"] = test.initial_stress;
  t["strain"] = test.strain;
  t["increments"] = test.increments;
  t["unload_to"] = test.unload_to ? Json(*test.unload_to) : Json();
  j["status"] = failure.empty() ? "completed" : "failed";
  if (!failure.empty()) j["failure"] = failure;
  j["rows"] = rows.size();
  if (!rows.empty()) j["final"] = row_json(rows.back());
  if (test.kind == ElementTestKind::oedometer && rows.size() > std::size_t(test.increments)) {
    const ElementRow& loaded = rows[test.increments];
    j["k0_end_of_loading"] = loaded.lateral_stress / loaded.axial_stress;
  }
  j["commit"] = source_commit();
  write_json(path, j);
}

bool plot_element(const std::string& csv, const std::string& png, const std::string& title) {
  std::string why;
  if (run_plot_script("element.py", {csv, png, title}, &why)) return true;
  std::cerr << "duet element: chart skipped: " << why << '\n';
  return false;
}

void add_element_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ElementArgs>();
  CLI::App* cmd = app.add_subcommand(
      "element",
      "one material point, strain controlled: oedometer, drained triaxial, simple shear");
  cmd->add_option("model", args->model, "soil model (linear-elastic, drucker-prager, ...)")
      ->required();
  cmd->add_option("--test", args->test, "oedometer | triaxial | simple-shear")->required();
  cmd->add_option("--set", args->sets,
                  "NAME=VALUE (repeatable): model parameters (SI, angles in degrees) and the test "
                  "keys initial_stress, strain, increments, unload_to")
      ->allow_extra_args(false);  // one NAME=VALUE per --set, so MODEL is never swallowed
  cmd->add_option("--out", args->out, "output folder (default runs/element-<model>-<test>)");
  cmd->callback([args, &exit_code] {
    try {
      run_element(*args, exit_code);
    } catch (const InputError& e) {
      std::cerr << "duet element: " << e.what() << '\n';
      exit_code = 2;
    }
  });
}

}  // namespace duet
