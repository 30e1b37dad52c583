#pragma once
// Charts are drawn by matplotlib scripts in benchmarks/plot/, run with a Python that imports
// matplotlib (Debian's /usr/bin/python3 first: it sees python3-matplotlib and python3-h5py).

#include <string>
#include <vector>

namespace duet {

/// Path of a Python interpreter that imports matplotlib, or "" when none does.
std::string plotting_python();

/// Runs benchmarks/plot/<script> with `arguments`. Returns false (and sets `why`) when no Python
/// with matplotlib is found or the script fails; a missing chart is reported, never fatal.
bool run_plot_script(const std::string& script, const std::vector<std::string>& arguments,
                     std::string* why = nullptr);

}  // namespace duet
