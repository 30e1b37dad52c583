#include "spfem/wall_strip.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <tuple>

#include "spfem/smoothing.hpp"

namespace duet::spfem {

namespace {

using Index = std::int32_t;

constexpr std::size_t kMaxStripBoundaries = 64;  // bits of the per-node masks

Vec2 quarter_turn(const Vec2& a) {
  return Vec2(-a.y(), a.x());
}

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

bool is_no_slip_wall(const NodeBoundary& b) {
  return b.condition == NodeCondition::bonded && !b.rigid_body;
}

bool is_free_slip_wall(const NodeBoundary& b) {
  return (b.condition == NodeCondition::smooth || b.condition == NodeCondition::symmetry) &&
         !b.rigid_body;
}

// Entry of node `column` in the row between row_begin and row_end (present: the strip's real nodes
// share the edge's triangle with k).
Index find_entry(const SmoothingCells& cells, Index row_begin, Index row_end, Index column) {
  const Index entry =
      row_begin + find_in_row(&cells.column[row_begin], row_end - row_begin, column);
  assert(entry < row_end && "a wall strip node is missing from the row");
  return entry;
}

}  // namespace

void index_wall_edges(std::size_t n_nodes, WallStrips& strips) {
  std::vector<Index>& start = strips.edge_offset;
  start.assign(n_nodes + 1, 0);
  strips.held.assign(n_nodes, 0);
  for (const WallEdge& e : strips.edges) {
    ++start[std::size_t(e.a) + 1];
    ++start[std::size_t(e.b) + 1];
    if (e.free_slip) continue;  // its nodes stay in contact with the wall
    const std::uint64_t bit = std::uint64_t{1} << e.boundary;
    strips.held[std::size_t(e.a)] |= bit;
    strips.held[std::size_t(e.b)] |= bit;
  }
  for (std::size_t k = 0; k < n_nodes; ++k) start[k + 1] += start[k];
  strips.node_edges.resize(2 * strips.edges.size());
  std::vector<Index> fill(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < strips.edges.size(); ++i) {
    strips.node_edges[std::size_t(fill[std::size_t(strips.edges[i].a)]++)] = Index(i);
    strips.node_edges[std::size_t(fill[std::size_t(strips.edges[i].b)]++)] = Index(i);
  }
}

void find_wall_strips(const AlphaMesh& mesh, const std::vector<Vec2>& points,
                      std::span<const NodeBoundary> boundaries,
                      std::span<const BoundaryGeometry> geometry, double spacing,
                      double layer_depth, WallStrips& strips) {
  const std::size_t n = points.size();
  // Nodes added since (spfem.wall_node_gap, appended) start unattached; the rest keep theirs.
  if (strips.attached.size() != n) strips.attached.resize(n, 0);
  strips.touching.assign(n, 0);
  strips.edges.clear();
  const bool know_surface = mesh.surface.size() == n;
  // node_contact's bonded contact: within dp/2 (1 + 1e-6) on the soil side, or crossed by < dp
  const double reach = 0.5 * spacing * (1.0 + 1e-6);
  const double depth = spacing;
  const double release = kReleaseDistance * spacing;
  std::vector<NodeContact> found;
  NodeContact projection;
  bool any_wall = false;
  for (std::size_t b = 0; b < boundaries.size() && b < kMaxStripBoundaries; ++b) {
    const bool free_slip = is_free_slip_wall(boundaries[b]);
    if (!is_no_slip_wall(boundaries[b]) && !free_slip) continue;
    any_wall = true;
    const std::uint64_t bit = std::uint64_t{1} << b;
    for (std::size_t i = 0; i < n; ++i) {
      if (know_surface && mesh.surface[i] == 0) continue;  // only surface edges own strips
      if (free_slip) {
        // node_contact's smooth contact, this step only
        found.clear();
        find_contacts(geometry[b], false, Index(i), Index(b), points[i], reach, depth, found);
        if (!found.empty()) strips.touching[i] |= bit;
      } else if (strips.attached[i] & bit) {
        // Attached: kept while it still projects onto the wall, within the release distance.
        if (!project_on_boundary(geometry[b], Index(i), Index(b), points[i], depth, release,
                                 projection)) {
          strips.attached[i] &= ~bit;
        }
      } else {
        found.clear();
        find_contacts(geometry[b], false, Index(i), Index(b), points[i], reach, depth, found);
        if (!found.empty()) strips.attached[i] |= bit;
      }
    }
  }
  if (any_wall) {
    // Directed edges a -> b of the kept triangles (counter-clockwise: the soil on the left) whose
    // nodes share a wall; an edge is on the surface when its reverse is in no triangle.
    std::vector<std::tuple<Index, Index, std::uint64_t>> candidates;
    for (const Triangle& t : mesh.triangles) {
      for (int c = 0; c < 3; ++c) {
        const Index a = t[c];
        const Index b = t[(c + 1) % 3];
        const std::uint64_t common =
            (strips.attached[std::size_t(a)] | strips.touching[std::size_t(a)]) &
            (strips.attached[std::size_t(b)] | strips.touching[std::size_t(b)]);
        if (common != 0) candidates.emplace_back(a, b, common);
      }
    }
    std::sort(candidates.begin(), candidates.end());
    NodeContact at_a;
    NodeContact at_b;
    const double thinnest = 0.5 * layer_depth;
    for (const auto& [a, b, common] : candidates) {
      const auto reverse = std::lower_bound(candidates.begin(), candidates.end(),
                                            std::make_tuple(b, a, std::uint64_t{0}));
      if (reverse != candidates.end() && std::get<0>(*reverse) == b && std::get<1>(*reverse) == a) {
        continue;  // interior edge
      }
      for (std::size_t w = 0; w < kMaxStripBoundaries; ++w) {
        if (!((common >> w) & 1U)) continue;
        // One strip per edge: the first wall both nodes stand off by at least half the layer.
        if (!project_on_boundary(geometry[w], a, Index(w), points[std::size_t(a)], depth, release,
                                 at_a) ||
            !project_on_boundary(geometry[w], b, Index(w), points[std::size_t(b)], depth, release,
                                 at_b) ||
            at_a.distance < thinnest || at_b.distance < thinnest) {
          continue;
        }
        strips.edges.push_back({a, b, Index(w), at_a.point, at_b.point, at_a.boundary_velocity,
                                at_b.boundary_velocity, is_free_slip_wall(boundaries[w])});
        break;
      }
    }
  }
  index_wall_edges(n, strips);
}

bool held_by_wall_strip(const WallStrips& strips, const NodeContact& contact) {
  const auto node = std::size_t(contact.node);
  const auto boundary = std::size_t(contact.boundary);
  return contact.distance >= 0.0 && boundary < kMaxStripBoundaries && node < strips.held.size() &&
         ((strips.held[node] >> boundary) & 1U);
}

bool is_wall_edge(const WallStrips& strips, std::size_t k, std::int32_t a, std::int32_t b) {
  if (k + 1 >= strips.edge_offset.size()) return false;
  for (Index j = strips.edge_offset[k]; j < strips.edge_offset[k + 1]; ++j) {
    const WallEdge& e = strips.edges[std::size_t(strips.node_edges[std::size_t(j)])];
    if (e.a == a && e.b == b) return true;
  }
  return false;
}

double add_wall_strip_terms(const WallStrips& strips, const std::vector<Vec2>& points,
                            std::size_t k, std::int32_t row_begin, std::int32_t row_end,
                            double wedge, SmoothingCells& cells) {
  if (k + 1 >= strips.edge_offset.size()) return 0.0;
  // The quad (a, a', b', b) is counter-clockwise (the wall lies right of a -> b). Both of its
  // diagonals, each at half weight, so that neither end of the edge is favoured: triangles
  // (a, a', b'), (a, b', b) and (a, a', b), (a', b', b); local vertices 0 = a, 1 = b, 2 = a',
  // 3 = b'. Each real node of a triangle takes its own third and an equal share of the wall
  // vertices' thirds: weight A_tri / n_real, halved for the two diagonals.
  static constexpr std::array<std::array<int, 3>, 4> kTriangles = {
      {{0, 2, 3}, {0, 3, 1}, {0, 2, 1}, {2, 3, 1}}};
  struct Term {
    std::array<Vec2, 3> weighted;  // share x (A_tri / 3) grad N_v
    double area = 0.0;             // share x A_tri / 3, what node k takes
    bool solo = false;             // k is the triangle's only real node
  };
  const auto term = [&](const WallEdge& e, const std::array<int, 3>& t, Term& out) {
    const std::array<Vec2, 4> x = {points[std::size_t(e.a)], points[std::size_t(e.b)], e.a_wall,
                                   e.b_wall};
    const std::array<Index, 2> node = {e.a, e.b};
    int n_real = 0;
    bool has_k = false;
    for (const int v : t) {
      if (v < 2) {
        ++n_real;
        has_k = has_k || node[std::size_t(v)] == Index(k);
      }
    }
    if (!has_k) return false;
    out.solo = n_real == 1;
    const Vec2& x0 = x[std::size_t(t[0])];
    const Vec2& x1 = x[std::size_t(t[1])];
    const Vec2& x2 = x[std::size_t(t[2])];
    const double share = 0.5 * 3.0 / n_real;
    out.area = share * 0.5 * cross(x1 - x0, x2 - x0) / 3.0;
    // (A_tri / 3) grad N_v = quarter_turn(opposite edge) / 6, as smoothing.cpp triangle_terms
    out.weighted = {share * quarter_turn(x2 - x1) / 6.0, share * quarter_turn(x0 - x2) / 6.0,
                    share * quarter_turn(x1 - x0) / 6.0};
    return true;
  };
  const Index first = strips.edge_offset[k];
  const Index last = strips.edge_offset[k + 1];
  // The strips' own area at k, then the wedge, spread in proportion over k's strip triangles. At
  // a corner between a free-slip wall and a no-slip one (the oedometer's) only over the no-slip
  // triangles that hold k alone (k, k's wall point, the other wall point): those fields involve k
  // and the wall only. The corner node is pushed along the free-slip wall by the end of its
  // strip, sigma_tt dp / 2, and the wedge, whose field then stretches between the node and the
  // no-slip wall, carries exactly that into the wall's points, as the corner square of the body
  // bears on that wall. (Spread over every strip triangle, the wedge pushed the corners of a
  // uniformly stressed confined sample into their walls and the nodes beside them off them;
  // spread over the solo triangles at a no-slip wall's free end, the cantilever's clamp, it
  // threw the corner node out at P L^2/EI = 2.)
  double strip_area = 0.0;
  double solo_area = 0.0;
  bool at_free_slip_wall = false;
  Term t;
  for (Index j = first; j < last; ++j) {
    const WallEdge& e = strips.edges[std::size_t(strips.node_edges[std::size_t(j)])];
    at_free_slip_wall = at_free_slip_wall || e.free_slip;
    for (const std::array<int, 3>& tri : kTriangles) {
      if (!term(e, tri, t)) continue;
      strip_area += t.area;
      if (t.solo && !e.free_slip) solo_area += t.area;
    }
  }
  const bool to_solo = at_free_slip_wall && solo_area > 0.0;
  const double carrying = to_solo ? solo_area : strip_area;
  // A strip squeezed to nothing (an edge standing square on the wall: both wall points at one
  // place) cannot carry the wedge: spread over it, wedge / carrying grew without bound (a front
  // node of collapse-bui took |b_kk| = 3e14 1/m and the step 6e-17 s). Beyond four times the
  // carrying area the wedge is dropped, as fill_row drops a layer with no well-shaped triangle.
  const bool carried = carrying > 0.0 && std::abs(wedge) <= 4.0 * carrying;
  const double wedge_factor = carried ? wedge / carrying : 0.0;
  Index wall_entry = cells.wall_offset[k];
  for (Index j = first; j < last; ++j, wall_entry += 2) {
    const WallEdge& e = strips.edges[std::size_t(strips.node_edges[std::size_t(j)])];
    const std::array<Index, 2> node = {e.a, e.b};
    cells.wall_gradient[wall_entry].setZero();
    cells.wall_gradient[wall_entry + 1].setZero();
    for (const std::array<int, 3>& tri : kTriangles) {
      if (!term(e, tri, t)) continue;
      const bool carries = !to_solo || (t.solo && !e.free_slip);
      const double scale = carries ? 1.0 + wedge_factor : 1.0;
      for (std::size_t c = 0; c < 3; ++c) {
        const int v = tri[c];
        if (v < 2 || e.free_slip) {
          // A free-slip strip's wall point moves with its node: its term folds into the node's.
          cells.gradient[find_entry(cells, row_begin, row_end, node[std::size_t(v % 2)])] +=
              scale * t.weighted[c];
        } else {
          cells.wall_gradient[wall_entry + (v - 2)] += scale * t.weighted[c];
        }
      }
    }
  }
  return strip_area > 0.0 ? strip_area + (carried ? wedge : 0.0) : 0.0;
}

void size_wall_entries(const WallStrips* strips, std::size_t n_nodes, SmoothingCells& cells) {
  cells.wall_offset.assign(n_nodes + 1, 0);
  if (strips == nullptr || strips->edges.empty()) {
    cells.wall_column.clear();
    cells.wall_gradient.clear();
    cells.wall_velocity.clear();
    return;
  }
  assert(strips->edge_offset.size() == n_nodes + 1);
  // Two wall points (a', b') per strip at the node, in the order of its node_edges row.
  for (std::size_t k = 0; k <= n_nodes; ++k) cells.wall_offset[k] = 2 * strips->edge_offset[k];
  const std::size_t n_entries = std::size_t(cells.wall_offset[n_nodes]);
  cells.wall_column.resize(n_entries);
  cells.wall_gradient.resize(n_entries);
  for (std::size_t j = 0; j < strips->node_edges.size(); ++j) {
    cells.wall_column[2 * j] = 2 * strips->node_edges[j];
    cells.wall_column[2 * j + 1] = 2 * strips->node_edges[j] + 1;
  }
  cells.wall_velocity.resize(2 * strips->edges.size());
  for (std::size_t i = 0; i < strips->edges.size(); ++i) {
    cells.wall_velocity[2 * i] = strips->edges[i].a_wall_velocity;
    cells.wall_velocity[2 * i + 1] = strips->edges[i].b_wall_velocity;
  }
}

void wall_point_forces(const SmoothingCells& cells, const std::vector<Mat3>& stress,
                       std::vector<Vec2>& force) {
  force.assign(cells.wall_velocity.size(), Vec2::Zero());
  if (cells.wall_offset.empty()) return;
  const std::size_t n = cells.wall_offset.size() - 1;
  for (std::size_t k = 0; k < n; ++k) {
    for (Index entry = cells.wall_offset[k]; entry < cells.wall_offset[k + 1]; ++entry) {
      // F_w = sum_k V_k sigma_k c_kw, as F_int,l = sum_k V_k sigma_k b_kl
      force[std::size_t(cells.wall_column[entry])] +=
          cell_volume(cells, k) * (stress[k].topLeftCorner<2, 2>() * cells.wall_gradient[entry]);
    }
  }
}

void add_wall_strip_reactions(const WallStrips& strips, const SmoothingCells& cells,
                              const std::vector<Mat3>& stress, std::vector<Vec2>& boundary_force) {
  if (strips.edges.empty() || cells.wall_velocity.size() != 2 * strips.edges.size()) return;
  std::vector<Vec2> force;
  wall_point_forces(cells, stress, force);
  for (std::size_t i = 0; i < strips.edges.size(); ++i) {
    // m a = F_ext - F_int on a node: the soil pushes a wall point with -F_w
    boundary_force[std::size_t(strips.edges[i].boundary)] -= force[2 * i] + force[2 * i + 1];
  }
}

}  // namespace duet::spfem
