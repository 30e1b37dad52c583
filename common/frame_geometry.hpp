#pragma once
// What a frame shows besides the particles: the walls and rigid bodies as polylines at the
// frame's time, and for the SPFEM methods the triangle mesh in use with its surface edges
// (common/h5_writer.hpp writes them, common/xdmf.hpp describes them to ParaView).

#include <array>
#include <cstdint>
#include <vector>

#include "common/scene.hpp"
#include "common/tensor.hpp"

namespace duet {

using MeshTriangle = std::array<std::int32_t, 3>;
using MeshEdge = std::array<std::int32_t, 2>;

/// Every wall and rigid body of a scene as line segments, in the scene's order (walls first, then
/// rigid bodies: the order of the reactions). A rigid body's outline is closed.
struct BoundaryLines {
  std::vector<Vec2> points;
  std::vector<MeshEdge> segments;   // pairs of rows of `points`
  std::vector<std::int32_t> owner;  // per segment: index of the wall (then rigid body)
};

/// The walls and rigid bodies at time t (t < 0: as at 0), moved by their schedules.
BoundaryLines boundary_lines_at(const Scene& scene, double t);

/// The edges that belong to exactly one triangle (the mesh's boundary: free surface, walls,
/// holes), each once, oriented as in its triangle; sorted.
std::vector<MeshEdge> surface_edges(const std::vector<MeshTriangle>& triangles);

/// What the writer adds to a particle frame. `triangles` index the particle rows; null or empty
/// when the method has no mesh (SPH).
struct FrameGeometry {
  BoundaryLines boundaries;
  const std::vector<MeshTriangle>* triangles = nullptr;
};

}  // namespace duet
