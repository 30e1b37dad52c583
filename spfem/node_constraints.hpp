#pragma once
// Walls and rigid bodies as constraints on the nodes' displacement for the implicit SPFEM
// (issue: "Contact and walls described as constraints: fixed and prescribed dofs, normal
// directions, the active set"). A node touching a boundary (node_contact.hpp decides the touch,
// as for the explicit solver) is
//  - fixed: both components follow the boundary (a no-slip wall, a rough rigid body);
//  - normal: only the component along the boundary's normal follows it (a free-slip wall, a
//    smooth or frictional rigid body: friction is not modelled by the implicit solver), the
//    tangential one is free (a rotated dof, so inclined and curved walls work alike).
// The implicit solver eliminates the constrained components (DofMap): its unknowns are the free
// directions of every node.

#include <cstdint>
#include <vector>

#include "common/tensor.hpp"
#include "spfem/node_contact.hpp"

namespace duet::spfem {

enum class ConstraintKind { fixed, normal };

struct NodeConstraint {
  std::int32_t node = -1;
  std::int32_t boundary = -1;
  ConstraintKind kind = ConstraintKind::fixed;
  Vec2 normal = Vec2::Zero();     // unit, into the soil
  Vec2 increment = Vec2::Zero();  // the boundary's displacement over the increment there (m)
};

/// How a node condition constrains: bonded and rough fix both components, smooth and friction
/// the normal one.
ConstraintKind constraint_kind(NodeCondition condition);

/// Displacement over [t0, t1] of the boundary point that sits at `point` at t0 (m).
Vec2 boundary_displacement(const NodeBoundary& boundary, double t0, double t1, const Vec2& point);

/// The unknowns left after elimination: per node its free directions (none, the tangent of one
/// normal constraint, or both axes) and its prescribed displacement over the increment.
struct DofMap {
  std::vector<std::int32_t> first;        // n_nodes + 1 starts into direction (free dofs of node i)
  std::vector<Vec2> direction;            // per free dof: its unit direction
  std::vector<std::int32_t> node;         // per free dof: its node
  std::vector<Vec2> prescribed;           // per node: displacement of its constrained part (m)
  std::vector<std::uint8_t> constrained;  // per node: 1 when some component is prescribed
  std::size_t n_free() const { return direction.size(); }
};

/// Builds the map of `n_nodes` nodes from `constraints`; nodes flagged in `held` (in no
/// triangle: no stiffness) have no unknowns: they follow the boundaries that touch them (the
/// normal motion only for a normal constraint) and stay put otherwise. Two normal constraints with
/// different normals fix the node (a corner), their prescribed normal motions combined.
DofMap eliminate(std::size_t n_nodes, const std::vector<NodeConstraint>& constraints,
                 const std::vector<std::uint8_t>& held);

}  // namespace duet::spfem
