#include "benchmarks/reports.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "common/suggest.hpp"

namespace duet {

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string format_number(double value) {
  if (std::isnan(value)) return "";
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

namespace {

std::ofstream open_for_writing(const std::string& path) {
  std::ofstream file(path);
  if (!file) throw std::runtime_error("cannot write " + path);
  return file;
}

struct Columns {
  std::set<std::string> measures, scored, timing;
};

Columns columns_of(const std::vector<RunSummary>& runs) {
  Columns c;
  for (const auto& r : runs) {
    for (const auto& [name, v] : r.measures) c.measures.insert(name);
    for (const auto& [name, a] : r.accuracy) c.scored.insert(name);
    for (const auto& [name, t] : r.timing) c.timing.insert(name);
  }
  return c;
}

template <typename Map>
std::string lookup(const Map& map, const std::string& key) {
  const auto it = map.find(key);
  return it == map.end() ? std::string() : format_number(it->second);
}

}  // namespace

void write_compare_csv(const std::string& path, const std::vector<RunSummary>& runs) {
  const Columns c = columns_of(runs);
  auto file = open_for_writing(path);
  file << "scene,method,spacing,particles,steps,wall_seconds,status,failure_reason,failure_time,"
          "max_rel_error";
  for (const auto& m : c.measures) file << ",measure." << m;
  for (const auto& s : c.scored) {
    file << ",accuracy." << s << ".value,accuracy." << s << ".reference,accuracy." << s
         << ".rel_error";
  }
  for (const auto& t : c.timing) file << ",timing." << t;
  file << ",max_signed_error,warnings,warning_messages\n";
  for (const auto& r : runs) {
    file << csv_field(r.scene) << ',' << r.method << ',' << format_number(r.spacing) << ','
         << r.particles << ',' << r.steps << ',' << format_number(r.wall_seconds) << ',' << r.status
         << ',' << csv_field(r.failure_reason) << ','
         << (r.completed() ? "" : format_number(r.failure_time)) << ','
         << format_number(r.max_rel_error());
    for (const auto& m : c.measures) file << ',' << lookup(r.measures, m);
    for (const auto& s : c.scored) {
      const auto it = r.accuracy.find(s);
      if (it == r.accuracy.end()) {
        file << ",,,";
      } else {
        file << ',' << format_number(it->second.value) << ',' << format_number(it->second.reference)
             << ',' << format_number(it->second.rel_error);
      }
    }
    for (const auto& t : c.timing) file << ',' << lookup(r.timing, t);
    // The worst measure's sign, and the warnings in one field of one line (" | " between them)
    const Accuracy* worst = r.worst_accuracy();
    file << ',' << format_number(worst ? worst->signed_error : std::nan("")) << ','
         << r.warnings.size() << ',' << csv_field(join(r.warnings, " | ")) << '\n';
  }
}

std::string compare_markdown(const std::vector<RunSummary>& runs, double target,
                             bool list_warnings) {
  const Columns c = columns_of(runs);
  std::ostringstream md;
  // Every measure: the scored ones with their error, then the others (a run's value at its end,
  // or the last value recorded for a series).
  std::vector<std::string> unscored;
  for (const auto& m : c.measures) {
    if (!c.scored.count(m)) unscored.push_back(m);
  }
  md << "| method | spacing (m) | particles | steps | wall (s) | status |";
  for (const auto& s : c.scored) md << ' ' << s << " | " << s << " error |";
  for (const auto& m : unscored) md << ' ' << m << " |";
  md << "\n|---|---|---|---|---|---|";
  for (std::size_t k = 0; k < c.scored.size(); ++k) md << "---|---|";
  for (std::size_t k = 0; k < unscored.size(); ++k) md << "---|";
  md << '\n';
  for (const auto& r : runs) {
    md << "| " << r.method << " | " << format_number(r.spacing) << " | " << r.particles << " | "
       << r.steps << " | " << format_number(std::round(r.wall_seconds * 100) / 100) << " | "
       << (r.completed() ? r.status : r.status + ": " + r.failure_reason)
       << (r.warnings.empty() ? "" : " (warned: " + std::to_string(r.warnings.size()) + ")")
       << " |";
    for (const auto& s : c.scored) {
      const auto it = r.accuracy.find(s);
      if (it == r.accuracy.end()) {
        md << "  |  |";
      } else {
        // Signed where the run recorded the sign (over- and under-prediction told apart), and
        // for a curve where along it the largest error is
        const Accuracy& a = it->second;
        char error[64];
        if (std::isfinite(a.signed_error) && std::isfinite(a.worst_at)) {
          std::snprintf(error, sizeof error, "%+.1f %% at %.3g", 100.0 * a.signed_error,
                        a.worst_at);
        } else if (std::isfinite(a.signed_error)) {
          std::snprintf(error, sizeof error, "%+.1f %%", 100.0 * a.signed_error);
        } else {
          std::snprintf(error, sizeof error, "%.1f %%", 100.0 * a.rel_error);
        }
        char value[64];
        std::snprintf(value, sizeof value, "%.4g (ref %.4g)", it->second.value,
                      it->second.reference);
        md << ' ' << value << " | " << error << " |";
      }
    }
    for (const auto& m : unscored) {
      const auto it = r.measures.find(m);
      char value[32] = "";
      if (it != r.measures.end() && std::isfinite(it->second)) {
        std::snprintf(value, sizeof value, "%.4g", it->second);
      }
      md << ' ' << value << " |";
    }
    md << '\n';
  }
  // What each run doubts about its own result, under the table it qualifies
  bool any_warned = false;
  for (const auto& r : runs) {
    if (!list_warnings) break;
    for (const std::string& w : r.warnings) {
      if (!any_warned) md << "\nWarnings (metrics.json's `warnings`):\n\n";
      any_warned = true;
      md << "- " << r.method << " at spacing " << format_number(r.spacing) << " m: " << w << '\n';
    }
  }
  if (target > 0.0) {
    md << "\nCoarsest spacing with every scored error below " << 100.0 * target << " %:\n\n";
    for (const auto& choice : choose_for_target(runs, target)) {
      if (choice.run) {
        char line[200];
        std::snprintf(line, sizeof line,
                      "spacing %g m, %ld particles, %.3g s wall, worst error %.3g %%",
                      choice.run->spacing, choice.run->particles, choice.run->wall_seconds,
                      100.0 * choice.run->max_rel_error());
        md << "- " << choice.method << ": " << line << "\n";
      } else {
        md << "- " << choice.method << ": no spacing tried meets the target\n";
      }
    }
  }
  return md.str();
}

void write_compare_markdown(const std::string& path, const std::vector<RunSummary>& runs,
                            double target) {
  auto file = open_for_writing(path);
  if (!runs.empty()) file << "# " << runs.front().scene << ": methods against cost\n\n";
  file << compare_markdown(runs, target);
}

void write_stability_csv(const std::string& path, const std::vector<StabilityCell>& cells) {
  auto file = open_for_writing(path);
  if (cells.empty()) return;
  for (const auto& [key, value] : cells.front().settings) file << csv_field(key) << ',';
  file << "status,failure_reason,failure_time,steps,wall_seconds,max_rel_error\n";
  for (const auto& cell : cells) {
    for (const auto& [key, value] : cell.settings) file << csv_field(value) << ',';
    const RunSummary& r = cell.run;
    file << r.status << ',' << csv_field(r.failure_reason) << ','
         << (r.completed() ? "" : format_number(r.failure_time)) << ',' << r.steps << ','
         << format_number(r.wall_seconds) << ',' << format_number(r.max_rel_error()) << '\n';
  }
}

}  // namespace duet
