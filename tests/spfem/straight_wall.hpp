#pragma once
// A straight wall for the SPFEM tests that put walls beside a lattice (wall strips, the
// increment operator's wall-strip tangent).

#include "common/tensor.hpp"
#include "spfem/node_contact.hpp"

namespace duet::spfem::testing {

/// The wall from a to b with `condition`.
inline NodeBoundary straight_wall(const char* name, const Vec2& a, const Vec2& b,
                                  NodeCondition condition) {
  NodeBoundary wall;
  wall.name = name;
  wall.polyline = {a, b};
  wall.condition = condition;
  return wall;
}

}  // namespace duet::spfem::testing
