#include "benchmarks/methods.hpp"

#include "spfem/method.hpp"
#include "sph/method.hpp"

namespace duet {

void register_builtin_methods(MethodRegistry& registry) {
  // One line per method.
  sph::register_sph(registry);
  spfem::register_espfem(registry);
  spfem::register_ispfem(registry);
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
