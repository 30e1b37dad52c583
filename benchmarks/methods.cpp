#include "benchmarks/methods.hpp"

namespace duet {

void register_builtin_methods(MethodRegistry& registry) {
  // One line per method: register_sph(registry); register_espfem(registry); ...
  (void)registry;
}

const MethodRegistry& builtin_methods() {
  static const MethodRegistry registry = [] {
    MethodRegistry r;
    register_builtin_methods(r);
    return r;
  }();
  return registry;
}

}  // namespace duet
