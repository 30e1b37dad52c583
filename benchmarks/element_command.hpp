#pragma once
// `duet element MODEL --test oedometer|triaxial|simple-shear [--set NAME=VALUE]... [--out DIR]`:
// one material point through an element test (constitutive/element_test.hpp), writing
// element.csv, element.json and element.png. Also the writers the demo table reuses.

#include <CLI/CLI.hpp>
#include <map>
#include <string>
#include <vector>

#include "constitutive/element_test.hpp"
#include "constitutive/parameters.hpp"

namespace duet {

/// Registers the `element` subcommand. Bad input sets exit_code 2 (message on stderr), a test
/// that fails numerically exit_code 3 (rows so far are still written), success 0.
void add_element_command(CLI::App& app, int& exit_code);

/// The element.csv header, in order.
const std::vector<std::string>& element_csv_columns();

/// element.csv: the header, then one row per increment (the start first); NaN written as "nan".
void write_element_csv(const std::string& path, const std::vector<constitutive::ElementRow>& rows);

/// element.json: model, resolved parameters (derived included), the test, status, final state.
/// `failure` is empty for a completed test.
void write_element_json(const std::string& path, const std::string& model,
                        const std::map<std::string, constitutive::ParameterValue>& parameters,
                        const constitutive::ElementTest& test,
                        const std::vector<constitutive::ElementRow>& rows,
                        const std::string& failure);

/// element.png through benchmarks/plot/element.py; a missing matplotlib is reported on stderr,
/// never fatal. Returns whether the chart was drawn.
bool plot_element(const std::string& csv, const std::string& png, const std::string& title);

}  // namespace duet
