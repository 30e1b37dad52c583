#include "spfem/alpha_mesh.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <utility>

namespace duet::spfem {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::int32_t, Kernel>;
// Face info: the index of the face in AlphaMesh::triangles, -1 when it is not kept.
using FaceBase = CGAL::Triangulation_face_base_with_info_2<std::int32_t, Kernel>;
using DataStructure = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, DataStructure>;
using IndexedPoint = std::pair<Kernel::Point_2, std::int32_t>;
using VertexHandle = Delaunay::Vertex_handle;
using FaceHandle = Delaunay::Face_handle;

// Storage kept between steps so that a mesh rebuilt every step allocates nothing of ours once the
// cloud has stopped growing. The triangulation itself is kept too: the next call moves its
// vertices to the new positions and restores the Delaunay property by edge flips (below), which
// costs no allocation, sort or point location.
struct Scratch {
  std::vector<IndexedPoint> indexed_points;
  std::vector<std::int32_t> fan_offset;          // CSR rows: the triangle corners at each node
  std::vector<std::array<std::int32_t, 2>> fan;  // per corner at node a: (next, previous) node
  std::vector<std::int32_t> parent;              // union-find over nodes
  Delaunay delaunay;                             // of the last call's points and the frame
  std::vector<VertexHandle> vertex_of;           // per node of the last call; null: no vertex
  bool every_node_has_a_vertex = false;
  Vec2 inner_min = Vec2::Zero();  // the frame is at least 2 alpha away from this box
  Vec2 inner_max = Vec2::Zero();
  double alpha = 0.0;                             // alpha of the last call
  std::vector<std::pair<FaceHandle, int>> edges;  // edges still to check for the Delaunay property
};
thread_local Scratch scratch;

double cross(const Vec2& u, const Vec2& v) {
  return u.x() * v.y() - u.y() * v.x();
}

enum class FaceTest { kept, above_alpha, short_edge };

// Alpha criterion on one Delaunay face: circumradius R = a b c / (4 A) < alpha, written without
// division as a^2 b^2 c^2 < 4 alpha^2 (2A)^2. A zero-area face (2A = 0) never passes: it is
// dropped. So is a face with an edge shorter than min_edge: two nodes that near (nodes landed
// side by side on a wall) make a sliver whose nodes' cells have almost no area, so in explicit
// dynamics their strain grows with almost no force back until a remesh hands that stress to a
// full cell.
FaceTest test_face(const Kernel::Point_2& p0, const Kernel::Point_2& p1, const Kernel::Point_2& p2,
                   double alpha_squared, double min_edge_squared) {
  const double ux = p1.x() - p0.x(), uy = p1.y() - p0.y();
  const double vx = p2.x() - p0.x(), vy = p2.y() - p0.y();
  const double wx = p2.x() - p1.x(), wy = p2.y() - p1.y();
  const double twice_area = ux * vy - uy * vx;  // > 0: CGAL's finite faces are counter-clockwise
  const double uu = ux * ux + uy * uy, vv = vx * vx + vy * vy, ww = wx * wx + wy * wy;
  if (!(twice_area > 0.0 && uu * vv * ww < 4.0 * alpha_squared * twice_area * twice_area)) {
    return FaceTest::above_alpha;
  }
  return std::min(uu, std::min(vv, ww)) < min_edge_squared ? FaceTest::short_edge : FaceTest::kept;
}

std::int32_t find_root(std::vector<std::int32_t>& parent, std::int32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];  // path halving
    i = parent[i];
  }
  return i;
}

// Joins the pieces of a and b; the root is the smaller node index, so that a component's root is
// its first node and components come numbered in the order of their first node.
void join(std::vector<std::int32_t>& parent, std::int32_t a, std::int32_t b) {
  const std::int32_t ra = find_root(parent, a), rb = find_root(parent, b);
  if (ra < rb) parent[rb] = ra;
  if (rb < ra) parent[ra] = rb;
}

}  // namespace

namespace {

// Builds the Delaunay triangulation of the finite points and of a frame of four corners (info -1)
// around them. The frame keeps the hull of the triangulation fixed, so that moved points stay
// inside it and only interior edges need flipping (below). Each corner lies more than 2 alpha from
// every point of the box [inner_min, inner_max]; a face with a circumradius below alpha has its
// circumcircle within 2 alpha of its corners, so a corner never lies in it: such a face is in
// the triangulation with the frame exactly when it is in the one without (the empty-circle
// property), and the kept faces are those of the plain Delaunay triangulation.
void rebuild(const std::vector<Vec2>& points, double alpha, Scratch& s) {
  auto& indexed = s.indexed_points;
  indexed.clear();
  Vec2 lower = Vec2::Constant(std::numeric_limits<double>::infinity());
  Vec2 upper = -lower;
  for (std::size_t i = 0; i < points.size(); ++i) {
    // Particles at non-finite positions (a diverged run) are left out of the triangulation and
    // come out isolated, so the failure is reported by the solver's checks rather than inside
    // CGAL.
    if (points[i].allFinite()) {
      indexed.emplace_back(Kernel::Point_2(points[i].x(), points[i].y()),
                           static_cast<std::int32_t>(i));
      lower = lower.cwiseMin(points[i]);
      upper = upper.cwiseMax(points[i]);
    }
  }
  if (indexed.empty()) lower = upper = Vec2::Zero();
  // Room for the points to move (a quarter of the extent) before the next rebuild.
  const double room = 0.25 * (upper - lower).maxCoeff() + 2.0 * alpha;
  s.inner_min = lower - Vec2::Constant(room);
  s.inner_max = upper + Vec2::Constant(room);
  const Vec2 frame_min = s.inner_min - Vec2::Constant(4.0 * alpha);
  const Vec2 frame_max = s.inner_max + Vec2::Constant(4.0 * alpha);
  for (const Vec2& corner : {frame_min, Vec2(frame_max.x(), frame_min.y()), frame_max,
                             Vec2(frame_min.x(), frame_max.y())}) {
    indexed.emplace_back(Kernel::Point_2(corner.x(), corner.y()), -1);
  }
  // Inserting a range of (point, index) pairs spatially sorts it first (Hilbert order). Of two
  // coincident particles only one gets a vertex; the other comes out isolated.
  s.delaunay.clear();
  s.delaunay.insert(indexed.begin(), indexed.end());
  s.vertex_of.assign(points.size(), VertexHandle());
  for (auto v = s.delaunay.finite_vertices_begin(); v != s.delaunay.finite_vertices_end(); ++v) {
    if (v->info() >= 0) s.vertex_of[static_cast<std::size_t>(v->info())] = v;
  }
  s.every_node_has_a_vertex =
      std::none_of(s.vertex_of.begin(), s.vertex_of.end(),
                   [](const VertexHandle& v) { return v == VertexHandle(); });
  s.alpha = alpha;
}

// Moves the vertices of the kept triangulation to `points` and restores the Delaunay property by
// Lawson's edge flips: a triangulation whose every edge is locally Delaunay is the Delaunay
// triangulation (Delaunay's lemma; Lawson 1977 flips), and with CGAL's symbolic perturbation (the
// `true` of side_of_oriented_circle, as its own insertion uses) it is the same one a fresh build
// gives. Valid only while the moved triangulation is still a triangulation: every face
// counter-clockwise (checked; the frame keeps the hull convex) and every point inside the frame's
// box. Returns false (and changes nothing the caller relies on) when a rebuild is needed.
bool move_and_flip(const std::vector<Vec2>& points, double alpha, Scratch& s) {
  if (!s.every_node_has_a_vertex || s.vertex_of.size() != points.size() || alpha != s.alpha) {
    return false;
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec2& x = points[i];
    if (!x.allFinite() || (x.array() < s.inner_min.array()).any() ||
        (x.array() > s.inner_max.array()).any()) {
      return false;
    }
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    s.vertex_of[i]->set_point(Kernel::Point_2(points[i].x(), points[i].y()));
  }
  Delaunay& dt = s.delaunay;
  s.edges.clear();
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    if (CGAL::orientation(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()) !=
        CGAL::LEFT_TURN) {
      return false;  // a face turned over or flat: not a triangulation any more
    }
    for (int i = 0; i < 3; ++i) {
      const FaceHandle n = f->neighbor(i);
      if (&*f < &*n) s.edges.emplace_back(f, i);  // each edge once
    }
  }
  while (!s.edges.empty()) {
    const auto [f, i] = s.edges.back();
    s.edges.pop_back();
    const FaceHandle n = f->neighbor(i);
    if (dt.is_infinite(f) || dt.is_infinite(n)) continue;  // an edge of the frame
    if (dt.side_of_oriented_circle(n, f->vertex(i)->point(), true) != CGAL::ON_POSITIVE_SIDE) {
      continue;  // locally Delaunay
    }
    // Both faces are counter-clockwise and the edge is not locally Delaunay, so their union is a
    // convex quadrilateral and the other diagonal can be taken.
    dt.tds().flip(f, i);
    for (int j = 0; j < 3; ++j) {
      s.edges.emplace_back(f, j);
      s.edges.emplace_back(n, j);
    }
  }
  return true;
}

// label_mesh read off the triangulation: an edge of a kept face is on the surface when the face
// across it is not kept, so no fan of corners is built. Same rules, same numbering.
void label_from_faces(const Delaunay& delaunay, std::size_t n_nodes, AlphaMesh& mesh, Scratch& s) {
  const auto n = static_cast<std::int32_t>(n_nodes);
  mesh.surface.assign(n_nodes, 0);
  mesh.component.assign(n_nodes, -1);  // -1 until the node is seen in a kept face
  s.parent.resize(n_nodes);
  std::iota(s.parent.begin(), s.parent.end(), 0);
  for (auto f = delaunay.finite_faces_begin(); f != delaunay.finite_faces_end(); ++f) {
    if (f->info() < 0) continue;
    for (int i = 0; i < 3; ++i) {
      const std::int32_t a = f->vertex(i)->info();
      mesh.component[a] = 0;
      const FaceHandle across = f->neighbor(i);
      if (delaunay.is_infinite(across) || across->info() < 0) {
        mesh.surface[f->vertex(Delaunay::ccw(i))->info()] = 1;
        mesh.surface[f->vertex(Delaunay::cw(i))->info()] = 1;
      }
    }
    join(s.parent, f->vertex(0)->info(), f->vertex(1)->info());
    join(s.parent, f->vertex(1)->info(), f->vertex(2)->info());
  }
  mesh.n_components = 0;
  for (std::int32_t i = 0; i < n; ++i) {
    if (mesh.component[i] < 0) {
      mesh.surface[i] = 1;  // isolated
      continue;
    }
    const std::int32_t root = find_root(s.parent, i);
    mesh.component[i] = root == i ? mesh.n_components++ : mesh.component[root];
  }
}

}  // namespace

void build_alpha_mesh(const std::vector<Vec2>& points, double alpha, AlphaMesh& mesh, bool fresh,
                      double min_edge) {
  Scratch& s = scratch;
  if (fresh || !move_and_flip(points, alpha, s)) rebuild(points, alpha, s);
  Delaunay& delaunay = s.delaunay;

  mesh.triangles.clear();
  mesh.n_delaunay = 0;
  mesh.n_short_edge = 0;
  const double alpha_squared = alpha * alpha;
  const double min_edge_squared = min_edge * min_edge;
  for (auto f = delaunay.all_faces_begin(); f != delaunay.all_faces_end(); ++f) f->info() = -1;
  for (auto f = delaunay.finite_faces_begin(); f != delaunay.finite_faces_end(); ++f) {
    const auto v0 = f->vertex(0), v1 = f->vertex(1), v2 = f->vertex(2);
    if (v0->info() < 0 || v1->info() < 0 || v2->info() < 0) continue;  // a face on the frame
    ++mesh.n_delaunay;
    const FaceTest test =
        test_face(v0->point(), v1->point(), v2->point(), alpha_squared, min_edge_squared);
    mesh.n_short_edge += test == FaceTest::short_edge ? 1 : 0;
    if (test == FaceTest::kept) {
      f->info() = static_cast<std::int32_t>(mesh.triangles.size());
      mesh.triangles.push_back({v0->info(), v1->info(), v2->info()});  // counter-clockwise
    }
  }
  label_from_faces(delaunay, points.size(), mesh, s);
}

void label_mesh(std::size_t n_nodes, AlphaMesh& mesh) {
  const auto n = static_cast<std::int32_t>(n_nodes);
  Scratch& s = scratch;

  // The fan of each node: its triangle corners, grouped by node (counting sort).
  s.fan_offset.assign(n_nodes + 1, 0);
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++s.fan_offset[t[k] + 1];
  }
  std::partial_sum(s.fan_offset.begin(), s.fan_offset.end(), s.fan_offset.begin());
  s.fan.resize(3 * mesh.triangles.size());
  s.parent.resize(n_nodes);
  std::iota(s.parent.begin(), s.parent.end(), 0);
  // fan_offset[a] serves as the fill cursor of row a and ends at row a+1's start; shifted back
  // below.
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) s.fan[s.fan_offset[t[k]]++] = {t[(k + 1) % 3], t[(k + 2) % 3]};
    // Components: triangles that share a node are one body (also when they share only that node):
    // the node's smoothing cell takes a part of each, so force passes through it.
    join(s.parent, t[0], t[1]);
    join(s.parent, t[1], t[2]);
  }
  std::copy_backward(s.fan_offset.begin(), s.fan_offset.end() - 1, s.fan_offset.end());
  s.fan_offset[0] = 0;

  mesh.surface.assign(n_nodes, 0);
  mesh.component.resize(n_nodes);
  mesh.n_components = 0;

  // A node is on the alpha-shape boundary when one of its edges belongs to one kept triangle only.
  // Edge a -> next of a corner at a has its twin next -> a when next is the previous node of
  // another corner at a. Each directed edge lies in one triangle at most, so the nexts (and the
  // previous nodes) of a fan are distinct, and nexts == previous nodes as sets exactly when every
  // edge at a is shared; checking in the fan of a alone keeps the search in one cached row.
  for (std::int32_t a = 0; a < n; ++a) {
    const auto begin = s.fan.begin() + s.fan_offset[a], end = s.fan.begin() + s.fan_offset[a + 1];
    for (auto corner = begin; corner != end && mesh.surface[a] == 0; ++corner) {
      const std::int32_t next = (*corner)[0];
      const bool shared = std::any_of(begin, end, [next](const auto& c) { return c[1] == next; });
      if (!shared) mesh.surface[a] = 1;
    }
  }

  // An empty fan marks an isolated node. A root is the smallest node of its piece and is labelled
  // before the rest of it.
  for (std::int32_t i = 0; i < n; ++i) {
    if (s.fan_offset[i] == s.fan_offset[i + 1]) {
      mesh.surface[i] = 1;
      mesh.component[i] = -1;
      continue;
    }
    const std::int32_t root = find_root(s.parent, i);
    mesh.component[i] = root == i ? mesh.n_components++ : mesh.component[root];
  }
}

double smallest_angle(const AlphaMesh& mesh, const std::vector<Vec2>& points) {
  // Counter-clockwise triangles: the angle decreases as along / 2A (its cotangent) grows, so the
  // smallest of them takes one atan2 at the end; an inverted one is measured at once.
  double smallest = 180.0;            // no triangle
  double largest_cotangent = -1e300;  // over the counter-clockwise triangles
  double best_twice_area = 0.0, best_along = 0.0;
  for (const Triangle& t : mesh.triangles) {
    const auto [twice_area, along] = smallest_angle_sides(t, points);
    if (twice_area > 0.0) {
      if (along > largest_cotangent * twice_area) {
        largest_cotangent = along / twice_area;
        best_twice_area = twice_area;
        best_along = along;
      }
    } else {
      smallest = std::min(smallest, std::atan2(twice_area, along) * 180.0 / std::numbers::pi);
    }
  }
  if (best_twice_area > 0.0) {
    smallest =
        std::min(smallest, std::atan2(best_twice_area, best_along) * 180.0 / std::numbers::pi);
  }
  return smallest;
}

double mesh_area(const AlphaMesh& mesh, const std::vector<Vec2>& points) {
  // Signed: an inverted (clockwise) triangle counts negative.
  double area = 0.0;
  for (const Triangle& t : mesh.triangles) {
    area += 0.5 * cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]);
  }
  return area;
}

void build_node_triangles(const std::vector<Triangle>& triangles, std::size_t n_nodes,
                          NodeTriangles& rows) {
  rows.offset.assign(n_nodes + 1, 0);
  for (const Triangle& t : triangles) {
    for (const std::int32_t a : t) ++rows.offset[static_cast<std::size_t>(a) + 1];
  }
  for (std::size_t i = 0; i < n_nodes; ++i) rows.offset[i + 1] += rows.offset[i];
  rows.triangle.resize(3 * triangles.size());
  std::vector<std::int32_t> fill(rows.offset.begin(), rows.offset.end() - 1);
  for (std::size_t e = 0; e < triangles.size(); ++e) {
    for (const std::int32_t a : triangles[e]) {
      rows.triangle[static_cast<std::size_t>(fill[static_cast<std::size_t>(a)]++)] =
          static_cast<std::int32_t>(e);
    }
  }
}

}  // namespace duet::spfem
