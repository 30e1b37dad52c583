#include "common/solver.hpp"

#include "common/input_error.hpp"
#include "common/suggest.hpp"

namespace duet {

const MethodInfo& MethodRegistry::find(const std::string& name) const {
  for (const auto& m : methods_) {
    if (m.name == name) return m;
  }
  if (methods_.empty()) {
    throw InputError("--method " + name +
                     ": no solver is registered in this build yet (planned: sph, espfem, ispfem)");
  }
  throw InputError("--method " + name + ": unknown method" + did_you_mean(name, names()) +
                   "; registered methods: " + join(names()));
}

std::vector<std::string> MethodRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& m : methods_) out.push_back(m.name);
  return out;
}

}  // namespace duet
