#pragma once
// No-slip walls as wall strips of the node-based smoothing (issue #6). The particles are
// cell-centred, so the mesh through them lies dp/2 inside the material and a no-slip wall sits
// dp/2 outside its first row of nodes. Holding those nodes at the wall's velocity (bonded) makes
// the strip between them and the wall rigid: a clamped bar then vibrates over L - dp/2. Instead,
// a surface edge (a, b) of the mesh whose two nodes are attached to the same no-slip wall owns
// the quad (a, a', b', b) between the edge and the wall (a', b' the projections of a, b on the
// wall), in place of its boundary-layer strip. The quad is cut into linear triangles whose wall
// vertices move with the wall; every triangle gives each of its real nodes k the weight
// A_tri / n_real (its own third plus an equal share of the wall vertices' thirds), so
//   A_k L_k = sum_l A_k b_kl v_l + sum_w A_k c_kw v_w
// with exact element gradients: a linear velocity field (walls moving with it) is reproduced
// exactly, the cells still sum to the body's area, and the internal force at a wall point,
// F_w = sum_k A_k sigma_k c_kw, closes the virtual power: F.v + F_w.v_w = sum_k A_k sigma_k : L_k.
// The force of the soil on the wall is -sum_w F_w. The strip's stress is node k's own stress.
//
// Attachment: a node is attached to a no-slip wall when it touches it as node_contact decides for
// the bonded condition (within dp/2 (1 + 1e-6) on the soil side, or crossed by less than dp), and
// stays attached while it moves away (a clamp carries tension: bar, cantilever); it is let go only
// where it no longer projects onto the wall or lies farther than `kReleaseDistance` spacings from
// it (the strip would overlap other material). Nodes of a strip move freely, held by the strip's
// stiffness; an attached node in no strip (an isolated contact) stays bonded.
//
// Free-slip walls get strips too. Without one, the boundary-layer strip of a surface edge against
// the wall extends the linear field of the edge's triangle e into the strip, and so couples the
// node opposite the edge: under a uniform stress sigma it pushes that interior node with
// |sigma| dp / 2 towards the wall, which nothing balances (a confined sample - the oedometer -
// starts moving at t = 0 and a hypoplastic one relaxes). A free-slip strip is the same quad, with
// its wall points moving with their nodes: the wall's contact holds the nodes' normal velocity
// (the nodes stay in contact: it is not skipped as for a no-slip strip), the tangential velocity
// is free, so the strip's velocity gradient is (v_b - v_a) (x) t / |ab|, of a and b alone. A
// node touches a free-slip wall step by step (no attachment: it leaves when it moves away).

#include <cstdint>
#include <span>
#include <vector>

#include "common/tensor.hpp"
#include "spfem/alpha_mesh.hpp"
#include "spfem/node_contact.hpp"

namespace duet::spfem {

struct SmoothingCells;

/// Beyond this many spacings from its wall an attached node is let go.
constexpr double kReleaseDistance = 2.0;

/// One wall strip: the surface edge a -> b (counter-clockwise in its triangle, so the soil lies on
/// its left and the wall on its right), the projections of a and b on the wall and the wall's
/// velocity there. Wall point 2 i is a_wall of edges[i], 2 i + 1 its b_wall.
struct WallEdge {
  std::int32_t a = -1;
  std::int32_t b = -1;
  std::int32_t boundary = -1;
  Vec2 a_wall = Vec2::Zero();
  Vec2 b_wall = Vec2::Zero();
  Vec2 a_wall_velocity = Vec2::Zero();
  Vec2 b_wall_velocity = Vec2::Zero();
  // A free-slip wall's strip: its wall points move with their nodes (a' with a, b' with b), whose
  // normal velocity the wall's contact holds, so the strip only stretches along the edge.
  bool free_slip = false;
};

/// The strips of one step plus the nodes' attachments, which persist from step to step.
struct WallStrips {
  std::vector<WallEdge> edges;
  std::vector<std::int32_t> edge_offset;  // n_nodes + 1 starts into node_edges
  std::vector<std::int32_t> node_edges;   // indices into edges, per node
  std::vector<std::uint64_t> attached;    // per node: bit b = attached to boundary b (persistent)
  std::vector<std::uint64_t> held;        // per node: bit b = in a no-slip strip of boundary b
  std::vector<std::uint64_t> touching;    // per node: bit b = touching free-slip wall b this step
};

/// Builds the node -> edges rows of `strips.edges` and the `held` bits (for edges set by hand).
void index_wall_edges(std::size_t n_nodes, WallStrips& strips);

/// The strips of this step: attaches the surface nodes touching a no-slip wall (a bonded,
/// non-rigid boundary among the first 64), lets go of those that left it, marks those touching a
/// free-slip wall (smooth, non-rigid), and keeps every surface edge of `mesh` whose two nodes are
/// attached to (touch) the same wall and lie at least `layer_depth` / 2 off it (a thinner strip
/// would be far stiffer than the node's cell: the node stays bonded, or in plain contact).
void find_wall_strips(const AlphaMesh& mesh, const std::vector<Vec2>& points,
                      std::span<const NodeBoundary> boundaries,
                      std::span<const BoundaryGeometry> geometry, double spacing,
                      double layer_depth, WallStrips& strips);

/// True when `contact` is with a wall whose strip holds the node this step (not crossed): the
/// strip carries the node, so the bonded constraint is skipped.
bool held_by_wall_strip(const WallStrips& strips, const NodeContact& contact);

/// True when a -> b is a wall edge at node k (k is a or b).
bool is_wall_edge(const WallStrips& strips, std::size_t k, std::int32_t a, std::int32_t b);

/// Adds the wall-strip triangles at node k to row k of `cells` (entries of real nodes between
/// row_begin and row_end, wall entries at cells.wall_offset[k]), not yet divided by A_k; returns
/// the area they add to A_k. `wedge` (m^2): the node's corner wedge against the wall (the mitred
/// corner of the boundary layer), carried with the gradient of its strips in proportion.
double add_wall_strip_terms(const WallStrips& strips, const std::vector<Vec2>& points,
                            std::size_t k, std::int32_t row_begin, std::int32_t row_end,
                            double wedge, SmoothingCells& cells);

/// Sizes the wall entries of `cells` for `strips` (nullptr or no edges: none) and copies the wall
/// points' velocities.
void size_wall_entries(const WallStrips* strips, std::size_t n_nodes, SmoothingCells& cells);

/// Internal force at each wall point, F_w = sum_k A_k sigma_k c_kw (in-plane part of sigma).
void wall_point_forces(const SmoothingCells& cells, const std::vector<Mat3>& stress,
                       std::vector<Vec2>& force);

/// Adds the force of the soil on each wall through its strips, -sum_w F_w, to `boundary_force`.
void add_wall_strip_reactions(const WallStrips& strips, const SmoothingCells& cells,
                              const std::vector<Mat3>& stress, std::vector<Vec2>& boundary_force);

}  // namespace duet::spfem
