#pragma once
// The SPH method as the driver sees it: a Solver built from a Scene (walls, rigid bodies, loads,
// [sph] options), registered under the name "sph".

#include "common/solver.hpp"

namespace duet::sph {

/// Adds {"sph", ..., make} to the registry.
void register_sph(MethodRegistry& registry);

}  // namespace duet::sph

namespace duet {
using sph::register_sph;
}  // namespace duet
