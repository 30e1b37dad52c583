#include "benchmarks/listing_commands.hpp"

#include <algorithm>
#include <iostream>
#include <sstream>

#include "benchmarks/methods.hpp"
#include "common/input_error.hpp"
#include "common/scene_keys.hpp"
#include "common/suggest.hpp"
#include "constitutive/registry.hpp"

namespace duet {

namespace {

/// Left-aligned columns, two spaces apart; the last column is not padded.
std::string columns(const std::vector<std::vector<std::string>>& rows, const std::string& indent) {
  std::vector<std::size_t> width;
  for (const auto& row : rows) {
    for (std::size_t c = 0; c + 1 < row.size(); ++c) {
      if (width.size() <= c) width.resize(c + 1, 0);
      width[c] = std::max(width[c], row[c].size());
    }
  }
  std::ostringstream out;
  for (const auto& row : rows) {
    out << indent;
    for (std::size_t c = 0; c < row.size(); ++c) {
      out << row[c];
      if (c + 1 < row.size()) out << std::string(width[c] - row[c].size() + 2, ' ');
    }
    out << '\n';
  }
  return out.str();
}

std::string section_title(const std::string& section) {
  return section.empty() ? std::string("top level") : "[" + section + "]";
}

}  // namespace

std::string keys_listing(const std::string& section) {
  const std::vector<std::string> sections = scene_sections();
  std::vector<std::string> chosen;
  if (section == "all" || section.empty()) {
    chosen = sections;
  } else {
    // "wall" and "wall.<name>" both name the wall tables.
    for (const std::string& s : sections) {
      if (s == section || (!s.empty() && s.substr(0, s.find(".<")) == section &&
                           s.find(".<") != std::string::npos)) {
        chosen.push_back(s);
      }
    }
    if (chosen.empty()) {
      std::vector<std::string> names;
      for (const std::string& s : sections) {
        if (!s.empty()) names.push_back(s.substr(0, s.find(".<")));
      }
      throw InputError("keys " + section + ": no such table" + did_you_mean(section, names) +
                       "; tables: " + join(names));
    }
  }
  std::ostringstream out;
  for (const std::string& s : chosen) {
    out << section_title(s) << '\n';
    std::vector<std::vector<std::string>> rows = {{"key", "type", "unit", "default", "meaning"}};
    for (const SceneKey& k : scene_keys()) {
      if (k.section != s) continue;
      rows.push_back({k.key, k.type, k.unit.empty() ? "-" : k.unit, k.fallback, k.meaning});
    }
    out << columns(rows, "  ") << '\n';
  }
  return out.str();
}

std::string models_listing(const std::string& model) {
  const constitutive::ModelRegistry& registry = constitutive::builtin_models();
  std::vector<const constitutive::ModelInfo*> chosen;
  if (model.empty()) {
    for (const auto& info : registry.models()) chosen.push_back(&info);
  } else {
    chosen.push_back(&registry.find(model, "models"));
  }
  std::ostringstream out;
  for (const constitutive::ModelInfo* info : chosen) {
    out << info->name << ": " << info->summary << '\n';
    std::vector<std::map<std::string, ParameterValue>> forms = {info->example};
    forms.insert(forms.end(), info->other_forms.begin(), info->other_forms.end());
    for (std::size_t f = 0; f < forms.size(); ++f) {
      // The model's constructor reads its parameters: what it read is what it takes.
      constitutive::Parameters parameters("", forms[f]);
      info->make(parameters);
      if (forms.size() > 1) out << "  form " << f + 1 << " of " << forms.size() << ":\n";
      std::vector<std::vector<std::string>> rows = {
          {"parameter", "kind", "range", "unit", "default", "meaning"}};
      for (const constitutive::ParameterSpec& p : parameters.specs()) {
        rows.push_back({p.name, p.kind, p.range.empty() ? "-" : p.range,
                        p.unit.empty() ? "-" : p.unit, p.fallback.empty() ? "-" : p.fallback,
                        p.meaning});
      }
      out << columns(rows, "    ");
    }
    out << "  with: model = \"" << info->name << "\", density (kg/m^3) in [material.<name>]\n\n";
  }
  return out.str();
}

std::string scene_key_unit(const std::string& dotted) {
  const auto segments_of = [](const std::string& text) {
    std::vector<std::string> out;
    std::size_t start = 0;
    for (std::size_t dot; (dot = text.find('.', start)) != std::string::npos; start = dot + 1)
      out.push_back(text.substr(start, dot - start));
    out.push_back(text.substr(start));
    return out;
  };
  const std::vector<std::string> given = segments_of(dotted);
  for (const SceneKey& k : scene_keys()) {
    const std::vector<std::string> pattern =
        segments_of(k.section.empty() ? k.key : k.section + "." + k.key);
    if (pattern.size() != given.size()) continue;
    bool match = true;
    for (std::size_t i = 0; i < pattern.size() && match; ++i) {
      match =
          pattern[i] == given[i] || (pattern[i].starts_with("<") && pattern[i] != "<parameter>");
    }
    if (match) return k.unit;
  }
  // A model parameter: the unit the model that reads it gives.
  if (given.size() == 3 && given[0] == "material") {
    for (const auto& info : constitutive::builtin_models().models()) {
      std::vector<std::map<std::string, ParameterValue>> forms = {info.example};
      forms.insert(forms.end(), info.other_forms.begin(), info.other_forms.end());
      for (const auto& form : forms) {
        constitutive::Parameters parameters("", form);
        info.make(parameters);
        for (const auto& spec : parameters.specs()) {
          if (spec.name == given[2] && !spec.unit.empty()) return spec.unit;
        }
      }
    }
  }
  return "";
}

std::string methods_listing() {
  std::ostringstream out;
  std::vector<std::vector<std::string>> rows = {{"method", "kind", "options", "summary"}};
  for (const std::string& name : builtin_methods().names()) {
    const MethodInfo& m = builtin_methods().find(name);
    std::string sections;
    for (const std::string& s : m.option_sections)
      sections += (sections.empty() ? "" : " ") + ("[" + s + "]");
    rows.push_back({m.name, m.dynamic ? "dynamic" : "quasi-static", sections, m.summary});
  }
  out << columns(rows, "");
  out << "\nduet keys SECTION lists a method's options; duet run SCENE --method M runs one.\n";
  return out.str();
}

void add_listing_commands(CLI::App& app, int& exit_code) {
  auto section = std::make_shared<std::string>();
  CLI::App* keys = app.add_subcommand(
      "keys",
      "every scene key with its type, unit, default and meaning (from the loader's schema)");
  keys->add_option("section", *section,
                   "one table: time, domain, initial_stress, material, body, wall, rigid_body, "
                   "load, measure, reference, sph, spfem, spfem.implicit, strength_reduction, "
                   "checks (default: all)");
  keys->callback([section, &exit_code] {
    std::cout << keys_listing(*section);
    exit_code = 0;
  });

  auto model = std::make_shared<std::string>();
  CLI::App* models = app.add_subcommand(
      "models", "every constitutive model with its parameters, ranges, units and defaults");
  models->add_option("model", *model, "one model (default: all)");
  models->callback([model, &exit_code] {
    std::cout << models_listing(*model);
    exit_code = 0;
  });

  CLI::App* methods = app.add_subcommand("methods", "the registered methods and their options");
  methods->callback([&exit_code] {
    std::cout << methods_listing();
    exit_code = 0;
  });
}

}  // namespace duet
