#pragma once
// Remeshing on angle (spfem.remesh = "angle"): the mesh keeps its triangles while they stay well
// shaped, and a new Delaunay / alpha mesh is built once one of them has degraded. Triangle e asks
// for a new mesh when its smallest interior angle falls below its limit,
//   theta_limit,e = remesh_angle                                   (remesh_angle_fraction = 0)
//   theta_limit,e = min(remesh_angle, fraction x theta_e at the last remesh)   (fraction > 0),
// or when it turns clockwise (inverted). The first rule is the plain threshold on the smallest
// angle of the mesh; a fresh Delaunay mesh of a moving cloud nearly always holds a triangle just
// above any threshold (and alpha-shape surface slivers below it), so the plain rule remeshes
// every step or two. The second counts only the loss of shape since the last remesh: a triangle
// born at 40 deg may fall to remesh_angle, one born at 16 deg to 8 deg.
// The test is on cot(theta) = (e1 . e2) / 2A at the smallest angle, so a step takes no
// trigonometric call per triangle.

#include <vector>

#include "common/tensor.hpp"
#include "spfem/alpha_mesh.hpp"

namespace duet::spfem {

struct RemeshTrigger {
  std::vector<double> cot_limit;  // per triangle: cot(theta_limit,e); +inf: inversion only
};

/// Sets the limits of the triangles of a newly built `mesh` at `points` (angle_deg in degrees,
/// fraction as above) and returns the smallest angle of the mesh (deg; 180 without triangles).
double arm_remesh_trigger(const AlphaMesh& mesh, const std::vector<Vec2>& points, double angle_deg,
                          double fraction, RemeshTrigger& trigger);

/// True when a triangle of `mesh` at `points` has fallen below its limit or turned inverted.
/// `smallest` gets the smallest angle (deg) of the mesh, negative when a triangle is inverted.
bool remesh_due(const AlphaMesh& mesh, const std::vector<Vec2>& points,
                const RemeshTrigger& trigger, double& smallest);

}  // namespace duet::spfem
