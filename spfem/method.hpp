#pragma once
// The explicit and the implicit SPFEM as the driver sees them: Solvers built from a Scene (walls,
// rigid bodies, loads, [spfem] and [spfem.implicit] options), registered under the names "espfem"
// and "ispfem".

#include "common/solver.hpp"

namespace duet::spfem {

/// Adds {"espfem", ..., make} to the registry.
void register_espfem(MethodRegistry& registry);

/// Adds {"ispfem", ..., make} to the registry: the implicit SPFEM (spfem/implicit_solver.hpp).
void register_ispfem(MethodRegistry& registry);

}  // namespace duet::spfem

namespace duet {
using spfem::register_espfem;
using spfem::register_ispfem;
}  // namespace duet
