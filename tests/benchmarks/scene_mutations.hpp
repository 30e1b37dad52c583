#pragma once
// The scene fuzzer's mutations (issue 17), shared by the test that loads every mutation
// (scene_fuzz_test.cpp) and the one that runs a sample of those that load
// (scene_fuzz_run_benchmark_test.cpp): deleted and duplicated lines, every value replaced by a
// wrong type, an out-of-range or a non-finite number, huge and tiny spacings, empty and binary
// files, unicode names, deep nesting, degenerate polygons. Deterministic for a given generator.

#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace duet::test {

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

inline std::string join_lines(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

inline const std::vector<std::string> kBadValues = {
    "\"text\"", "[1, 2, 3]", "true", "{ a = 1 }", "-1.0",         "0",    "1e308", "-1e308",
    "nan",      "inf",       "-inf", "1e-300",    "[[0.0, 0.0]]", "\"\"", "[]"};

/// The mutations of one scene, each with a label saying what was done.
inline std::vector<std::pair<std::string, std::string>> mutations(const std::string& text,
                                                                  std::mt19937& random) {
  std::vector<std::pair<std::string, std::string>> out;
  const std::vector<std::string> lines = lines_of(text);
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (lines[k].empty() || lines[k][0] == '#') continue;
    auto deleted = lines;
    deleted.erase(deleted.begin() + static_cast<long>(k));
    out.emplace_back("delete line " + std::to_string(k + 1), join_lines(deleted));
    auto duplicated = lines;
    duplicated.insert(duplicated.begin() + static_cast<long>(k), lines[k]);
    out.emplace_back("duplicate line " + std::to_string(k + 1), join_lines(duplicated));
    const auto eq = lines[k].find('=');
    if (eq != std::string::npos && lines[k][0] != '[') {
      for (const std::string& value : kBadValues) {
        auto changed = lines;
        changed[k] = lines[k].substr(0, eq + 1) + " " + value;
        out.emplace_back("line " + std::to_string(k + 1) + " = " + value, join_lines(changed));
      }
    }
    if (lines[k][0] == '[' && lines[k].find('.') != std::string::npos) {
      auto renamed = lines;
      renamed[k].insert(renamed[k].find('.') + 1, "s\xc3\xa4ule_\xf0\x9f\xaa\xa8_");
      out.emplace_back("unicode table name at line " + std::to_string(k + 1), join_lines(renamed));
      // Quoted, a unicode name is legal TOML: [body."säule_🪨column"].
      auto quoted = lines;
      const auto dot = quoted[k].find('.');
      const auto close = quoted[k].find(']');
      if (close != std::string::npos && close > dot) {
        quoted[k] = quoted[k].substr(0, dot + 1) + "\"s\xc3\xa4ule_\xf0\x9f\xaa\xa8" +
                    quoted[k].substr(dot + 1, close - dot - 1) + "\"" + quoted[k].substr(close);
        out.emplace_back("quoted unicode name at line " + std::to_string(k + 1),
                         join_lines(quoted));
      }
    }
  }
  for (const char* spacing : {"1e-9", "1e-300", "1e9", "0.0", "-0.1"}) {
    out.emplace_back(std::string("spacing = ") + spacing, text + "\n" + std::string("# mutated\n"));
    auto spaced = lines;
    for (std::string& l : spaced) {
      if (l.rfind("spacing", 0) == 0) l = std::string("spacing = ") + spacing;
    }
    out.back().second = join_lines(spaced);
  }
  out.emplace_back("empty file", "");
  std::string junk(512, '\0');
  for (char& c : junk) c = static_cast<char>(random() & 0xff);
  out.emplace_back("binary junk", junk);
  out.emplace_back("binary junk after the scene", text + junk);
  out.emplace_back("deep array",
                   text + "\nx = " + std::string(100000, '[') + std::string(100000, ']') + "\n");
  std::string tables = text + "\n";
  for (int d = 0; d < 2000; ++d) tables += "[z" + std::to_string(d % 3) + "]\n";
  out.emplace_back("many tables", tables);
  std::string inline_tables = text + "\ny = ";
  for (int d = 0; d < 5000; ++d) inline_tables += "{ a = ";
  inline_tables += "1";
  for (int d = 0; d < 5000; ++d) inline_tables += " }";
  out.emplace_back("deep inline tables", inline_tables + "\n");
  // Degenerate polygons: every body and rigid body outline, every wall.
  const std::vector<std::pair<std::string, std::string>> outlines = {
      {"self-intersecting", "[[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]]"},
      {"zero area", "[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]"},
      {"clockwise", "[[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]]"},
      {"one point", "[[0.0, 0.0]]"},
      {"repeated points", "[[0.0, 0.0], [0.0, 0.0], [0.0, 0.0]]"},
      {"non-finite point", "[[0.0, 0.0], [nan, 1.0], [1.0, 1.0]]"}};
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const bool polygon = lines[k].rfind("vertices", 0) == 0 || lines[k].rfind("points", 0) == 0;
    if (!polygon) continue;
    const std::string key = lines[k].substr(0, lines[k].find('='));
    for (const auto& [what, value] : outlines) {
      auto changed = lines;
      changed[k] = key + "= " + value;
      out.emplace_back(what + " outline at line " + std::to_string(k + 1), join_lines(changed));
    }
  }
  return out;
}

}  // namespace duet::test
