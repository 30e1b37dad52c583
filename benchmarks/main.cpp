// The duet command line program. It holds no physics: each subcommand lives in its own file.
// Exit status: 0 success, 1 internal error, 2 bad input, 3 a run that failed numerically,
// 128 + N a run interrupted by signal N (130 SIGINT, 143 SIGTERM).

#include <CLI/CLI.hpp>
#include <iostream>

#include "benchmarks/check_command.hpp"
#include "benchmarks/commands.hpp"
#include "benchmarks/element_command.hpp"
#include "benchmarks/git_commit.hpp"
#include "benchmarks/listing_commands.hpp"
#include "benchmarks/srf_command.hpp"
#include "common/h5_writer.hpp"
#include "common/input_error.hpp"
#include "common/interrupt.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "duet: run one geomechanics scene through SPH and SPFEM and score accuracy against cost"};
  app.set_version_flag(
      "--version", std::string("duet ") + DUET_VERSION + " (commit " + duet::source_commit() + ")");
  app.require_subcommand(1);
  int exit_code = 0;
  duet::keep_hdf5_out_of_exit();
  duet::install_interrupt_handlers();
  duet::add_run_command(app, exit_code);
  duet::add_compare_command(app, exit_code);
  duet::add_stability_command(app, exit_code);
  duet::add_element_command(app, exit_code);
  duet::add_check_command(app, exit_code);
  duet::add_demo_command(app, exit_code);
  duet::add_plot_command(app, exit_code);
  duet::add_collect_command(app, exit_code);
  duet::add_summary_command(app, exit_code);
  duet::add_srf_command(app, exit_code);
  duet::add_listing_commands(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int status = app.exit(e);
    return status == 0 ? 0 : 2;
  } catch (const duet::InputError& e) {
    std::cerr << "duet: " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "duet: error: " << e.what() << '\n';
    return 1;
  }
  return exit_code;
}
