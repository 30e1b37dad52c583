#pragma once
// The XDMF 2 description of a run's frames, so that ParaView (its "XDMF Reader") opens run.xdmf
// directly. Up to four temporal collections, each a block in ParaView, whose DataItems point at
// the datasets of the frames' own files, "frames/NNNNNN.h5:/<dataset>":
//   particles   Polyvertex grid of the particles with every field
//   boundaries  Polyline grid of the walls and rigid bodies at the frame's time (cell field
//               `boundary`: index of the wall, then rigid body, in the scene's order)
//   mesh        Triangle grid of the SPFEM mesh in use, on the particles' points and fields
//   surface     Polyline grid of the mesh's surface edges (edges of one triangle)
// A collection lists only the frames that have its grid (no walls: no boundaries; SPH: no mesh).

#include <cstddef>
#include <string>
#include <vector>

namespace duet {

/// One point field of a frame (an HDF5 dataset of n rows and `components` columns).
struct XdmfField {
  std::string name;            // dataset name inside the frame group
  std::string attribute_type;  // "Scalar" (1 column), "Vector" (3) or "Tensor" (9, row-major)
  int components = 1;
  std::string number_type = "Float";  // XDMF NumberType: "Float" or "Int"
  int precision = 8;                  // bytes
};

struct XdmfFrame {
  double time = 0.0;
  std::string file;  // HDF5 file of the frame relative to the .xdmf: "frames/000003.h5"
  std::string name;  // "000003": names the frame's grids
  std::size_t n_points = 0;
  std::string geometry = "position";  // n x 3 dataset at the file's root
  std::string vertices = "vertices";  // n int32 dataset 0 .. n-1: one vertex cell per particle
  std::vector<XdmfField> fields;
  std::size_t n_boundary_points = 0;    // dataset boundary_points, n x 3
  std::size_t n_boundary_segments = 0;  // boundary_segments (n x 2 int32), boundary (n int32)
  std::size_t n_triangles = 0;          // triangles, n x 3 int32 (particle rows)
  std::size_t n_surface_edges = 0;      // surface_edges, n x 2 int32 (particle rows)
};

/// The whole document for `frames`.
std::string xdmf_document(const std::vector<XdmfFrame>& frames);

/// Writes the document to `path` through a temporary file and a rename, so a reader (or a run
/// that stops) never sees a half-written file. Throws std::runtime_error naming the path.
void write_xdmf(const std::string& path, const std::vector<XdmfFrame>& frames);

}  // namespace duet
