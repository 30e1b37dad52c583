#pragma once
// The reference the SPFEM alpha-mesh tests check against: the INTERIOR faces of CGAL's
// regularized Alpha_shape_2 at the same alpha, as sets of index-sorted triangles.

#include <CGAL/Alpha_shape_2.h>
#include <CGAL/Alpha_shape_face_base_2.h>
#include <CGAL/Alpha_shape_vertex_base_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include "spfem/alpha_mesh.hpp"

namespace duet::spfem::testing {

using FaceSet = std::set<Triangle>;

inline Triangle sorted(Triangle t) {
  std::sort(t.begin(), t.end());
  return t;
}

/// The faces build_alpha_mesh kept.
inline FaceSet kept_faces(const AlphaMesh& mesh) {
  FaceSet faces;
  for (const Triangle& t : mesh.triangles) faces.insert(sorted(t));
  return faces;
}

/// The INTERIOR faces of CGAL's regularized alpha shape; its alpha is the squared radius.
inline FaceSet alpha_shape_interior_faces(const std::vector<Vec2>& x, double alpha) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using AlphaVertex = CGAL::Alpha_shape_vertex_base_2<
      Kernel, CGAL::Triangulation_vertex_base_with_info_2<std::int32_t, Kernel>>;
  using AlphaFace = CGAL::Alpha_shape_face_base_2<Kernel>;
  using AlphaDelaunay =
      CGAL::Delaunay_triangulation_2<Kernel,
                                     CGAL::Triangulation_data_structure_2<AlphaVertex, AlphaFace>>;
  using AlphaShape = CGAL::Alpha_shape_2<AlphaDelaunay>;
  std::vector<std::pair<Kernel::Point_2, std::int32_t>> indexed;
  for (std::size_t i = 0; i < x.size(); ++i) {
    indexed.emplace_back(Kernel::Point_2(x[i].x(), x[i].y()), static_cast<std::int32_t>(i));
  }
  AlphaDelaunay delaunay(indexed.begin(), indexed.end());
  const AlphaShape shape(delaunay, alpha * alpha, AlphaShape::REGULARIZED);
  FaceSet faces;
  for (auto f = shape.finite_faces_begin(); f != shape.finite_faces_end(); ++f) {
    if (shape.classify(f) == AlphaShape::INTERIOR) {
      faces.insert(sorted({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}));
    }
  }
  return faces;
}

}  // namespace duet::spfem::testing
