#pragma once
// The mesh of the smoothed particle finite element method (Zhang 2018 slides, "PFEM steps";
// Yuan et al. 2019; Zhang et al. 2018): a CGAL Delaunay triangulation of the particles (EPICK
// kernel, built from a spatially sorted range), then the alpha criterion: a triangle is kept when
// its circumradius is below alpha (alpha = alpha_factor x spacing). The kept triangles are the
// interior faces of CGAL::Alpha_shape_2 at the same alpha (checked in the tests), found at a
// fraction of its cost. Free surfaces, separation and re-contact appear and vanish as the cloud
// moves. The nodes are the particles; nothing here knows of materials or stresses.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/tensor.hpp"

namespace duet::spfem {

/// Three node (particle) indices, counter-clockwise.
using Triangle = std::array<std::int32_t, 3>;

struct AlphaMesh {
  std::vector<Triangle> triangles;      // kept faces, counter-clockwise
  std::vector<std::uint8_t> surface;    // per node: 1 on the alpha-shape boundary (or isolated)
  std::vector<std::int32_t> component;  // per node: connected piece of the kept mesh; -1 isolated
  std::int32_t n_components = 0;        // pieces (bodies) of the kept mesh
  std::size_t n_delaunay = 0;           // Delaunay faces before the alpha test
  std::size_t n_short_edge = 0;  // faces the alpha test kept and the shortest-edge test refused
};

/// Triangulates `points` and keeps the faces whose circumradius is below `alpha` (m) and whose
/// every edge is at least `min_edge` (m) long; fills surface nodes and connected components.
/// Reuses the storage of `mesh`. The triangulation of the last call is moved and flipped when it
/// can be (the same triangles, listed in an order that depends on the triangulation's history);
/// `fresh` builds it anew (an order of the points alone).
void build_alpha_mesh(const std::vector<Vec2>& points, double alpha, AlphaMesh& mesh,
                      bool fresh = false, double min_edge = 0.0);

/// Recomputes `surface`, `component` and `n_components` of `mesh` from its triangles (for a mesh
/// kept across steps, or one built by hand in a test). `n_nodes` is the number of points.
void label_mesh(std::size_t n_nodes, AlphaMesh& mesh);

/// The smallest interior angle of one triangle as its two sides, theta = atan2(twice_area, along):
/// twice the signed area (the same at every corner) and the dot product of the two edges at that
/// corner. Counter-clockwise, the smallest angle has the largest cotangent along / 2A, so the
/// largest of the three dot products; clockwise (inverted, 2A < 0) every angle is negative and the
/// smallest is the one nearest -180 deg, the smallest dot product.
struct AngleSides {
  double twice_area;
  double along;
};

inline AngleSides smallest_angle_sides(const Triangle& t, const std::vector<Vec2>& points) {
  const Vec2& a = points[static_cast<std::size_t>(t[0])];
  const Vec2& b = points[static_cast<std::size_t>(t[1])];
  const Vec2& c = points[static_cast<std::size_t>(t[2])];
  const Vec2 ab = b - a, bc = c - b, ca = a - c;
  const double twice_area = ca.x() * ab.y() - ca.y() * ab.x();  // (b - a) x (c - a)
  const double at_a = -ab.dot(ca);
  const double at_b = -bc.dot(ab);
  const double at_c = -ca.dot(bc);
  const double along = twice_area >= 0.0 ? std::max(at_a, std::max(at_b, at_c))
                                         : std::min(at_a, std::min(at_b, at_c));
  return {twice_area, along};
}

/// Smallest interior angle (degrees) over the triangles at the current `points`; a triangle that
/// has turned clockwise (inverted) gives a negative value. The remesh-on-angle trigger reads it.
double smallest_angle(const AlphaMesh& mesh, const std::vector<Vec2>& points);

/// Sum of the triangle areas at `points` (m^2).
double mesh_area(const AlphaMesh& mesh, const std::vector<Vec2>& points);

/// Node -> triangles in compressed rows: triangle[offset[k] .. offset[k + 1]) are the triangles
/// around node k, in increasing order.
struct NodeTriangles {
  std::vector<std::int32_t> offset;    // n_nodes + 1
  std::vector<std::int32_t> triangle;  // 3 n_triangles
};

/// Builds the rows of `triangles` over `n_nodes` nodes (counting sort; reuses the storage).
void build_node_triangles(const std::vector<Triangle>& triangles, std::size_t n_nodes,
                          NodeTriangles& rows);

}  // namespace duet::spfem
