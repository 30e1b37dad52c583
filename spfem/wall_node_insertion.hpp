#pragma once
// Node insertion along a wall (espfem, spfem.wall_node_gap). A wall that stretches the soil
// along it, as the expanding cavity does, draws the row of nodes on it apart (a/a0 times their
// spacing on the cavity wall, the ring being incompressible) while the rows behind it close up;
// the triangle between two such nodes and one of the next row flattens until the alpha test drops
// it, and that node, exposed, is driven at the wall (benchmarks/RESULTS.md, the espfem cavity).
// Particle finite element codes keep their nodes evenly spaced by adding nodes where they have
// drawn too far apart (Cremonesi et al. 2020, "A state of the art review of the particle finite
// element method", Arch. Comput. Methods Eng. 27); here only on walls, the one place the spacing
// grows without bound in a body that stays whole.
//
// The new node sits between its two parents at their mean distance from the wall and takes a
// quarter of each parent's mass and volume (each parent's cell loses half of its half-gap), so
// mass and volume are kept; velocity, displacement, stress, strain and internal variables are the
// parents' mass-weighted means, so momentum is kept too. Nothing here knows of time integration.

#include <cstdint>
#include <vector>

#include "common/particles.hpp"
#include "spfem/node_contact.hpp"

namespace duet::spfem {

/// The two nodes a new node came from.
struct InsertedNode {
  std::int32_t node;  // its index (appended)
  std::int32_t parents[2];
};

/// Share of each parent's mass and volume the new node takes.
inline constexpr double kInsertedShare = 0.25;

/// For every wall (not rigid body) of `boundaries`, placed as `geometry`: the nodes touching it
/// (node_contact's test, within dp/2 of it), ordered along it. Two neighbours in that order, of
/// the same body and material, get a node between them, appended to `particles`, once they are
/// more than `gap_factor` x max(dp, their distance apart at the start, x - u) apart and less than
/// twice that (further is soil that parted, not a stretched row). `spacing` is dp (m). Returns
/// the nodes added, in index order.
std::vector<InsertedNode> insert_wall_nodes(const std::vector<NodeBoundary>& boundaries,
                                            const std::vector<BoundaryGeometry>& geometry,
                                            double spacing, double gap_factor,
                                            Particles& particles);

/// Position along an open polyline (m from its first point) of the point of it nearest `x`.
double arc_position(const std::vector<Vec2>& polyline, const Vec2& x);

}  // namespace duet::spfem
