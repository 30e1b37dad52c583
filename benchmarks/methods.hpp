#pragma once
// The methods this build offers, registered explicitly from one place.

#include "common/solver.hpp"

namespace duet {

void register_builtin_methods(MethodRegistry& registry);

/// The registry with every built-in method.
const MethodRegistry& builtin_methods();

}  // namespace duet
