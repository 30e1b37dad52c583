#pragma once
// `duet srf SCENE --method M`: the factor of safety by strength reduction
// (strength_reduction_search.hpp), each trial a run of the scene at strength_reduction.factor = f
// in OUT/f=<f>/; srf.csv, srf.md, srf.json and srf.png (every trial's largest displacement
// against time, coloured by its verdict) in OUT.

#include <CLI/CLI.hpp>

namespace duet {

void add_srf_command(CLI::App& app, int& exit_code);

}  // namespace duet
