#pragma once
// The nodal discretisation both SPFEM solvers compose (Zhang 2018 slides, "PFEM steps", "Strain
// smoothing technique"): the walls and rigid bodies at time t, the alpha mesh of the nodes (with
// the remesh trigger), the wall strips and the node-based smoothing cells with their boundary
// layer, and the mesh counters. The explicit solver (explicit_solver.hpp) updates it once per
// step; the implicit solver (implicit_solver.hpp) once per increment on the configuration at its
// start, then refills the same cells at each Newton iterate. Nothing here knows of stresses,
// masses or time integration.

#include <cstddef>
#include <string>
#include <vector>

#include "common/scene.hpp"
#include "common/state_bag.hpp"
#include "common/tensor.hpp"
#include "spfem/alpha_mesh.hpp"
#include "spfem/node_contact.hpp"
#include "spfem/remesh_trigger.hpp"
#include "spfem/smoothing.hpp"
#include "spfem/wall_strip.hpp"

namespace duet::spfem {

struct MeshCounters {
  long remeshes = 0;
  long forced_remeshes = 0;  // angle trigger found an inverted triangle
  std::size_t triangles = 0;
  std::size_t surface_nodes = 0;
  int components = 0;
  std::size_t isolated_nodes_max = 0;
  std::size_t short_edge_triangles_max = 0;  // refused for an edge below min_edge_factor x dp
  double smallest_angle = 180.0;             // deg, smallest seen on a mesh in use
};

class NodalDiscretisation {
 public:
  /// `options`: the scene's [spfem] (alpha_factor, remesh, remesh_angle(_fraction),
  /// boundary_layer); `spacing` dp (m); walls then rigid bodies.
  /// `axisymmetric`: x = r about the axis x = 0; the cells carry their rings 2 pi r_k and hoop
  /// rows (SmoothingCells::ring, hoop).
  NodalDiscretisation(const duet::SpfemOptions& options, double spacing,
                      std::vector<NodeBoundary> boundaries, bool axisymmetric = false);

  /// Orients the boundaries on the initial node positions; forgets any mesh and attachment.
  void initialise(const std::vector<Vec2>& positions);

  /// The boundaries' points, normals and velocities at time t (t < 0: as at 0); `held` zeroes
  /// their velocities (gravity loading holds the walls still).
  void place_boundaries(double t, bool held);

  /// Mesh at `x` (a new Delaunay / alpha mesh when due: every call, or on the angle trigger), the
  /// wall strips of the boundaries as last placed, and the smoothing cells. Returns true when it
  /// remeshed.
  bool update(const std::vector<Vec2>& x);

  /// Recomputes the cells on the kept mesh and wall strips at new positions `x` (same rows).
  void refill(const std::vector<Vec2>& x);

  /// Keeps the boundary layer's discrete choices of the last update in later refills (true)
  /// or lets every fill choose again (false, the default; update() always chooses again).
  void freeze_layer_branches(bool frozen) { cells_.frozen_branches = frozen; }

  /// True when row k carries boundary-layer or wall-strip terms (a surface node, layer on).
  bool has_layer_terms(std::size_t k) const {
    return layer_depth() > 0.0 && (mesh_.surface.size() != cells_.area.size() || mesh_.surface[k]);
  }

  /// d(A_k b_kl)/dx_m over row k at `x` (the positions of the last refill), by central
  /// differences of step h (smoothing.hpp row_position_derivative); with `hoop_out` also
  /// d(A_k h_kl)/dx_m (axisymmetric).
  void row_derivative(std::vector<Vec2>& x, std::size_t k, double h, std::vector<Vec2>& out,
                      std::vector<Vec2>* hoop_out = nullptr) {
    row_position_derivative(mesh_, x, k, layer_depth(), &wall_strips_, h, cells_, out, hoop_out);
  }

  const duet::SpfemOptions& options() const { return options_; }
  bool axisymmetric() const { return axisymmetric_; }
  double spacing() const { return spacing_; }
  /// Depth of the boundary layer (dp / 2 with spfem.boundary_layer, else 0), m.
  double layer_depth() const { return options_.boundary_layer ? 0.5 * spacing_ : 0.0; }
  const std::vector<NodeBoundary>& boundaries() const { return boundaries_; }
  const std::vector<BoundaryGeometry>& geometry() const { return geometry_; }
  const AlphaMesh& mesh() const { return mesh_; }
  const SmoothingCells& cells() const { return cells_; }
  const WallStrips& wall_strips() const { return wall_strips_; }
  WallStrips& wall_strips() { return wall_strips_; }
  const MeshCounters& counters() const { return counters_; }
  /// What a resumed run needs of it, into / from a frame's state under `key`: the mesh counters,
  /// the nodes the no-slip walls hold (wall_strips().attached, kept from step to step) and, with
  /// spfem.remesh = angle, the kept mesh's triangles and their remesh limits.
  void save_state(StateBag& state, const std::string& key) const;
  void restore_state(const StateBag& state, const std::string& key, std::size_t nodes);
  /// A frame from which a run may be resumed: the next update builds from scratch what a resumed
  /// run cannot have kept (a fresh triangulation at the next remesh instead of a moved and
  /// flipped one; the kept mesh's labels and smoothing cells), so both runs go on alike.
  void restart_point() {
    fresh_next_ = true;
    cells_from_scratch_ = true;
  }

 private:
  /// Axisymmetric: cells_.ring = 2 pi x_k and the hoop rows at `x` (smoothing.hpp
  /// fill_axisymmetric_terms; throws NumericalFailure for a node at x <= 0).
  void fill_ring(const std::vector<Vec2>& x);

  duet::SpfemOptions options_;
  bool axisymmetric_ = false;
  double spacing_ = 0.0;
  std::vector<NodeBoundary> boundaries_;
  std::vector<BoundaryGeometry> geometry_;
  AlphaMesh mesh_;
  SmoothingCells cells_;
  RemeshTrigger remesh_trigger_;  // remesh = angle: the limits of the kept triangles
  WallStrips wall_strips_;        // no-slip (and free-slip) walls as strips of the smoothing
  bool have_mesh_ = false;
  bool fresh_next_ = false;          // restart_point: the next remesh builds anew
  bool cells_from_scratch_ = false;  // restart_point: the next update labels and builds cells
  MeshCounters counters_;
};

}  // namespace duet::spfem
