#include "spfem/nodal_discretisation.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "common/input_error.hpp"
#include "common/solver.hpp"

namespace duet::spfem {

NodalDiscretisation::NodalDiscretisation(const duet::SpfemOptions& options, double spacing,
                                         std::vector<NodeBoundary> boundaries, bool axisymmetric)
    : options_(options),
      axisymmetric_(axisymmetric),
      spacing_(spacing),
      boundaries_(std::move(boundaries)) {
  if (!(spacing_ > 0.0)) throw InputError("spfem: particle spacing must be > 0 m");
  if (!(options_.alpha_factor > 0.0)) throw InputError("spfem.alpha_factor must be > 0");
}

void NodalDiscretisation::initialise(const std::vector<Vec2>& positions) {
  geometry_.clear();
  for (const NodeBoundary& b : boundaries_) {
    geometry_.push_back(orient_boundary(b, positions, 2.0 * spacing_));
  }
  have_mesh_ = false;
  wall_strips_ = WallStrips{};
  counters_ = MeshCounters{};
}

void NodalDiscretisation::place_boundaries(double t, bool held) {
  for (std::size_t b = 0; b < boundaries_.size(); ++b) {
    update_geometry(boundaries_[b], std::max(t, 0.0), geometry_[b]);
    if (held) {
      std::fill(geometry_[b].point_velocity.begin(), geometry_[b].point_velocity.end(),
                Vec2::Zero());
    }
  }
}

bool NodalDiscretisation::update(const std::vector<Vec2>& x) {
  const duet::SpfemOptions& o = options_;
  bool remesh = !have_mesh_ || o.remesh == Remesh::every_step;
  double angle = 180.0;  // smallest angle of the kept mesh at x (when it was measured)
  if (!remesh) {
    // Remesh on angle (spfem/remesh_trigger.hpp): keep the connectivity while every triangle
    // stays above its limit; an inverted triangle always forces a new mesh.
    remesh = remesh_due(mesh_, x, remesh_trigger_, angle);
    if (remesh && angle <= 0.0) ++counters_.forced_remeshes;
  }
  if (remesh) {
    build_alpha_mesh(x, o.alpha_factor * spacing_, mesh_, fresh_next_,
                     o.min_edge_factor * spacing_);
    fresh_next_ = false;
    have_mesh_ = true;
    ++counters_.remeshes;
    counters_.triangles = mesh_.triangles.size();
    counters_.components = mesh_.n_components;
    counters_.surface_nodes = static_cast<std::size_t>(
        std::count(mesh_.surface.begin(), mesh_.surface.end(), std::uint8_t{1}));
    counters_.isolated_nodes_max = std::max(
        counters_.isolated_nodes_max,
        static_cast<std::size_t>(std::count(mesh_.component.begin(), mesh_.component.end(), -1)));
    counters_.short_edge_triangles_max =
        std::max(counters_.short_edge_triangles_max, mesh_.n_short_edge);
  }
  // A restart point keeping its mesh: the labels from the triangles alone and the cells built
  // anew, as a run resumed from it does (spfem.remesh = angle).
  const bool from_scratch = remesh || cells_from_scratch_;
  if (!remesh && cells_from_scratch_) label_mesh(x.size(), mesh_);
  cells_from_scratch_ = false;
  // Zhang 2018 slides, smoothing: A_k = sum_j A_e^j / 3, b_lh(x_k) = (1/A_k) sum_j A_e^j N_l,h^j
  // / 3. The particles are cell-centred (the particle at (i + 1/2) dp carries dp^2), so the mesh
  // through them lies dp/2 inside the material on every face: the boundary layer of depth dp/2
  // gives the surface cells the skin the mesh misses, so stiffness and the nodes' (particle) mass
  // agree.
  cells_.frozen_branches = false;
  const double layer = layer_depth();
  // No-slip walls as wall strips (with the layer): the edges at a wall own the strip to it.
  const WallStrips* strips = nullptr;
  if (layer > 0.0) {
    find_wall_strips(mesh_, x, boundaries_, geometry_, spacing_, layer, wall_strips_);
    strips = &wall_strips_;
  }
  if (from_scratch) {
    build_smoothing_cells(mesh_, x, cells_, layer, strips);
  } else {
    refill_smoothing_cells(mesh_, x, cells_, layer, strips);  // same triangles: same rows
  }
  fill_ring(x);
  if (remesh && o.remesh == Remesh::angle) {
    angle = arm_remesh_trigger(mesh_, x, o.remesh_angle, o.remesh_angle_fraction, remesh_trigger_);
  } else if (remesh && !mesh_.triangles.empty()) {
    angle = smallest_angle(mesh_, x);
  }
  counters_.smallest_angle = std::min(counters_.smallest_angle, angle);
  return remesh;
}

void NodalDiscretisation::refill(const std::vector<Vec2>& x) {
  const double layer = layer_depth();
  refill_smoothing_cells(mesh_, x, cells_, layer, layer > 0.0 ? &wall_strips_ : nullptr);
  fill_ring(x);
}

void NodalDiscretisation::fill_ring(const std::vector<Vec2>& x) {
  if (!axisymmetric_) {
    cells_.ring.clear();
    cells_.hoop.clear();
    return;
  }
  for (std::size_t k = 0; k < x.size(); ++k) {
    // A node's ring 2 pi r; one on or across the axis has none (the symmetry wall on x = 0 holds
    // the nodes dp / 2 off it)
    if (!(x[k].x() > 0.0)) {
      throw NumericalFailure("spfem: node " + std::to_string(k) +
                             " reached the axis (r = " + std::to_string(x[k].x()) +
                             " m): an axisymmetric scene needs a "
                             "symmetry wall along x = 0 that holds its nodes off it");
    }
  }
  fill_axisymmetric_terms(mesh_, x, cells_);
}

}  // namespace duet::spfem

namespace duet::spfem {

void NodalDiscretisation::save_state(StateBag& state, const std::string& key) const {
  const MeshCounters& c = counters_;
  put(state, key,
      std::vector<double>{double(c.remeshes), double(c.forced_remeshes), double(c.triangles),
                          double(c.surface_nodes), double(c.components),
                          double(c.isolated_nodes_max), c.smallest_angle,
                          double(c.short_edge_triangles_max)});
  put_bits(state, key + ".attached", wall_strips_.attached);
  if (options_.remesh == Remesh::angle) {
    std::vector<double> triangles;
    triangles.reserve(3 * mesh_.triangles.size());
    for (const Triangle& t : mesh_.triangles) triangles.insert(triangles.end(), t.begin(), t.end());
    put(state, key + ".triangles", triangles);
    put(state, key + ".have_mesh", have_mesh_ ? 1.0 : 0.0);
    put(state, key + ".cot_limit", remesh_trigger_.cot_limit);
  }
}

void NodalDiscretisation::restore_state(const StateBag& state, const std::string& key,
                                        std::size_t nodes) {
  const std::vector<double>& v = entry(state, key);
  // 7 entries: saved before the shortest-edge count (none refused then)
  if (v.size() != 7 && v.size() != 8) {
    throw std::runtime_error("the saved state's '" + key + "' has another size");
  }
  counters_.remeshes = static_cast<long>(v[0]);
  counters_.forced_remeshes = static_cast<long>(v[1]);
  counters_.triangles = static_cast<std::size_t>(v[2]);
  counters_.surface_nodes = static_cast<std::size_t>(v[3]);
  counters_.components = static_cast<int>(v[4]);
  counters_.isolated_nodes_max = static_cast<std::size_t>(v[5]);
  counters_.smallest_angle = v[6];
  counters_.short_edge_triangles_max = v.size() > 7 ? static_cast<std::size_t>(v[7]) : 0;
  get_bits(state, key + ".attached", wall_strips_.attached);
  if (options_.remesh == Remesh::angle) {
    // The mesh the run kept, in the order it listed its triangles (the frame's own), and their
    // limits; labels and cells follow at the next update (restart_point).
    const std::vector<double>& t = entry(state, key + ".triangles");
    if (t.size() % 3 != 0) throw_bad_entry(key + ".triangles", "is not a list of triangles");
    mesh_.triangles.resize(t.size() / 3);
    for (std::size_t e = 0; e < mesh_.triangles.size(); ++e) {
      for (int k = 0; k < 3; ++k) {
        const double node = t[3 * e + std::size_t(k)];
        if (!(node >= 0.0 && node < double(nodes)))
          throw_bad_entry(key + ".triangles", "names no node");
        mesh_.triangles[e][std::size_t(k)] = static_cast<std::int32_t>(node);
      }
    }
    label_mesh(nodes, mesh_);
    have_mesh_ = scalar(state, key + ".have_mesh") != 0.0;
    get(state, key + ".cot_limit", remesh_trigger_.cot_limit);
    if (remesh_trigger_.cot_limit.size() != mesh_.triangles.size()) {
      throw_bad_entry(key + ".cot_limit", "is not one limit per triangle");
    }
  }
}

}  // namespace duet::spfem
