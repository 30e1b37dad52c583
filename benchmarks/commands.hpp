#pragma once
// The subcommands of the duet program, each registered on the CLI11 app. A subcommand sets
// `exit_code` (0 success, 2 bad input, 3 a run that failed numerically); bad input is thrown as
// InputError and turned into exit 2 by main.

#include <CLI/CLI.hpp>

namespace duet {

void add_run_command(CLI::App& app, int& exit_code);
void add_compare_command(CLI::App& app, int& exit_code);
void add_stability_command(CLI::App& app, int& exit_code);
void add_demo_command(CLI::App& app, int& exit_code);
void add_plot_command(CLI::App& app, int& exit_code);
void add_collect_command(CLI::App& app, int& exit_code);
void add_summary_command(CLI::App& app, int& exit_code);

}  // namespace duet
