#pragma once
// Test meshes for the smoothing tests: a cell-centred lattice, and every finite face of a CGAL
// Delaunay triangulation of a cloud, counter-clockwise, built here (not by build_alpha_mesh) so the
// smoothing is pinned alone.

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "spfem/alpha_mesh.hpp"

namespace duet::spfem::testing {

/// The particles of a W x H rectangle sampled cell-centred, as the scenes do: (i + 1/2) dp, lower
/// left corner at the origin (walls along x = 0 and y = 0 lie dp/2 off the first column and row).
struct Lattice {
  double dp = 0.05;
  int nx = 24;
  int ny = 8;
  double width() const { return nx * dp; }
  double height() const { return ny * dp; }
  std::vector<Vec2> points() const {
    std::vector<Vec2> x;
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) x.emplace_back((i + 0.5) * dp, (j + 0.5) * dp);
    }
    return x;
  }
};

inline double signed_area(const Triangle& t, const std::vector<Vec2>& x) {
  const Vec2 ab = x[t[1]] - x[t[0]];
  const Vec2 ac = x[t[2]] - x[t[0]];
  return 0.5 * (ab.x() * ac.y() - ab.y() * ac.x());
}

/// All finite Delaunay faces of `points`, counter-clockwise (n_delaunay set to their number).
inline AlphaMesh delaunay_mesh(const std::vector<Vec2>& points) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::int32_t, Kernel>;
  using DataStructure =
      CGAL::Triangulation_data_structure_2<VertexBase, CGAL::Triangulation_face_base_2<Kernel>>;
  using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, DataStructure>;
  std::vector<std::pair<Kernel::Point_2, std::int32_t>> input;
  for (std::size_t i = 0; i < points.size(); ++i) {
    input.emplace_back(Kernel::Point_2(points[i].x(), points[i].y()), std::int32_t(i));
  }
  const Delaunay delaunay(input.begin(), input.end());
  AlphaMesh mesh;
  for (auto face = delaunay.finite_faces_begin(); face != delaunay.finite_faces_end(); ++face) {
    Triangle t{face->vertex(0)->info(), face->vertex(1)->info(), face->vertex(2)->info()};
    if (signed_area(t, points) < 0.0) std::swap(t[1], t[2]);
    mesh.triangles.push_back(t);
  }
  mesh.n_delaunay = mesh.triangles.size();
  return mesh;
}

}  // namespace duet::spfem::testing
