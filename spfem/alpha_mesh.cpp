#include "spfem/alpha_mesh.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <utility>

namespace duet::spfem {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::int32_t, Kernel>;
using DataStructure =
    CGAL::Triangulation_data_structure_2<VertexBase, CGAL::Triangulation_face_base_2<Kernel>>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, DataStructure>;
using IndexedPoint = std::pair<Kernel::Point_2, std::int32_t>;

// Storage kept between steps so that a mesh rebuilt every step allocates nothing of ours once the
// cloud has stopped growing (CGAL's triangulation allocates its own).
struct Scratch {
  std::vector<IndexedPoint> indexed_points;
  std::vector<std::int32_t> fan_offset;          // CSR rows: the triangle corners at each node
  std::vector<std::array<std::int32_t, 2>> fan;  // per corner at node a: (next, previous) node
  std::vector<std::int32_t> parent;              // union-find over nodes
};
thread_local Scratch scratch;

double cross(const Vec2& u, const Vec2& v) {
  return u.x() * v.y() - u.y() * v.x();
}

// Alpha criterion on one Delaunay face: circumradius R = a b c / (4 A) < alpha, written without
// division as a^2 b^2 c^2 < 4 alpha^2 (2A)^2. A zero-area face (2A = 0) never passes: it is
// dropped.
bool below_alpha(const Kernel::Point_2& p0, const Kernel::Point_2& p1, const Kernel::Point_2& p2,
                 double alpha_squared) {
  const double ux = p1.x() - p0.x(), uy = p1.y() - p0.y();
  const double vx = p2.x() - p0.x(), vy = p2.y() - p0.y();
  const double wx = p2.x() - p1.x(), wy = p2.y() - p1.y();
  const double twice_area = ux * vy - uy * vx;  // > 0: CGAL's finite faces are counter-clockwise
  const double product = (ux * ux + uy * uy) * (vx * vx + vy * vy) * (wx * wx + wy * wy);
  return twice_area > 0.0 && product < 4.0 * alpha_squared * twice_area * twice_area;
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

void build_alpha_mesh(const std::vector<Vec2>& points, double alpha, AlphaMesh& mesh) {
  // Particles at non-finite positions (a diverged run) are left out of the triangulation and come
  // out isolated, so the failure is reported by the solver's checks rather than inside CGAL.
  auto& indexed = scratch.indexed_points;
  indexed.clear();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].allFinite()) {
      indexed.emplace_back(Kernel::Point_2(points[i].x(), points[i].y()),
                           static_cast<std::int32_t>(i));
    }
  }
  // Inserting a range of (point, index) pairs spatially sorts it first (Hilbert order). Of two
  // coincident particles only one gets a vertex; the other comes out isolated.
  const Delaunay delaunay(indexed.begin(), indexed.end());

  mesh.triangles.clear();
  mesh.n_delaunay = delaunay.number_of_faces();
  const double alpha_squared = alpha * alpha;
  for (auto f = delaunay.finite_faces_begin(); f != delaunay.finite_faces_end(); ++f) {
    const auto v0 = f->vertex(0), v1 = f->vertex(1), v2 = f->vertex(2);
    if (below_alpha(v0->point(), v1->point(), v2->point(), alpha_squared)) {
      mesh.triangles.push_back({v0->info(), v1->info(), v2->info()});  // counter-clockwise
    }
  }
  label_mesh(points.size(), mesh);
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
  // Signed interior angle at a vertex: atan2(2A, e_next . e_prev), with 2A the same for all three
  // vertices. Counter-clockwise: the smallest angle is opposite the shortest edge; clockwise
  // (inverted, 2A < 0): all angles are negative, the smallest is opposite the longest edge.
  double smallest = 180.0;  // no triangle
  for (const Triangle& t : mesh.triangles) {
    const Vec2 p[3] = {points[t[0]], points[t[1]], points[t[2]]};
    const double twice_area = cross(p[1] - p[0], p[2] - p[0]);
    const double opposite[3] = {(p[2] - p[1]).squaredNorm(), (p[0] - p[2]).squaredNorm(),
                                (p[1] - p[0]).squaredNorm()};
    const auto pick = twice_area >= 0.0 ? std::min_element(opposite, opposite + 3)
                                        : std::max_element(opposite, opposite + 3);
    const int k = static_cast<int>(pick - opposite);
    const double along = (p[(k + 1) % 3] - p[k]).dot(p[(k + 2) % 3] - p[k]);
    smallest = std::min(smallest, std::atan2(twice_area, along) * 180.0 / std::numbers::pi);
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

}  // namespace duet::spfem
