#pragma once
// Charts are drawn by matplotlib scripts in benchmarks/plot/, run with a Python that imports
// matplotlib (Debian's /usr/bin/python3 first: it sees python3-matplotlib and python3-h5py).

#include <string>
#include <vector>

namespace duet {

/// `s` as one word for /bin/sh: in single quotes, each ' written as '\''.
std::string shell_quote(const std::string& s);

/// Path of a Python interpreter that imports matplotlib, or "" when none does.
std::string plotting_python();

/// run_plot_script, and a chart that cannot be drawn said on stderr ("duet: chart skipped: why"):
/// a missing chart is never fatal.
void draw_chart(const std::string& script, const std::vector<std::string>& arguments);

/// Runs benchmarks/plot/<script> with `arguments`. Returns false (and sets `why`) when no Python
/// with matplotlib is found or the script fails; a missing chart is reported, never fatal.
bool run_plot_script(const std::string& script, const std::vector<std::string>& arguments,
                     std::string* why = nullptr);

/// The charts of one run (benchmarks/plot/run.py) written beside it: series.png, the curves the
/// scene's measures imply, snapshots_<field>.png. Returns the files written; on failure an empty
/// list and `why`. Throws InputError when `run_dir` holds no run (no metrics.json or run.h5).
std::vector<std::string> plot_run(const std::string& run_dir, const std::string& field,
                                  std::string* why = nullptr);

}  // namespace duet
