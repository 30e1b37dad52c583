#pragma once
// `duet check SCENE [--method M] [--spacing DP] [--set key=value]...`: validates a scene without
// running it and prints what a run would be (particles per body, boundaries, measures and
// references, and per method the time step, the number of steps or increments and the memory),
// refusing with exit 2 what would not fit in the machine's memory unless --force.

#include <CLI/CLI.hpp>

namespace duet {

void add_check_command(CLI::App& app, int& exit_code);

}  // namespace duet
