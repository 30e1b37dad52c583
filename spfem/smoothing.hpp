#pragma once
// Node-based strain smoothing (Zhang 2018 slides, "Strain smoothing technique"; Liu et al. 2009
// NS-FEM): node k's smoothing cell collects a third of each triangle around it,
//   A_k = sum_e A_e / 3,   b_kl = (1 / A_k) sum_e (A_e / 3) grad N_l^e,
// so the smoothed velocity gradient at a node is L_k = sum_l v_l (x) b_kl and the internal force
// is F_int,l = sum_k B_kl^T sigma_k A_k (plane strain, per metre of thickness). Stress and internal
// variables stay on the nodes (the particles): nothing is mapped between meshes.

#include <array>
#include <cstdint>
#include <vector>

#include "common/tensor.hpp"
#include "spfem/alpha_mesh.hpp"
#include "spfem/wall_strip.hpp"

namespace duet::spfem {

/// What linear triangle e adds to the rows of its corners, computed once per step:
/// A_e (signed) and (A_e / 3) grad N_l^e for its corners l = t[0], t[1], t[2].
struct TriangleTerms {
  double area = 0.0;                      // A_e (m^2)
  std::array<Vec2, 3> weighted_gradient;  // (A_e / 3) grad N_corner^e (m)
};

/// Smoothed gradients in compressed rows: row k lists the nodes l that share a triangle with k
/// (k itself included) and b_kl = smoothed dN_l/dx at node k.
struct SmoothingCells {
  std::vector<double> area;  // A_k (m^2); 0 for a node in no triangle
  // Axisymmetric scenes: the ring 2 pi r_k of each node, so that the cell's volume is
  // V_k = 2 pi r_k A_k (NodalDiscretisation fills it); empty in plane strain (V_k = A_k, per
  // metre).
  std::vector<double> ring;
  // Axisymmetric scenes: the smoothed hoop strain's row, h_kl (1/m) per entry, so that node k's
  // hoop strain is eps_tt,k = sum_l u_r,l h_kl (fill_axisymmetric_terms); empty in plane strain.
  std::vector<double> hoop;
  std::vector<std::int32_t> offset;     // n_nodes + 1 row starts
  std::vector<std::int32_t> column;     // node l of each entry
  std::vector<Vec2> gradient;           // b_kl (1/m)
  std::vector<std::int32_t> transpose;  // for entry (k, l): the index of entry (l, k)
  // Wall strips (spfem/wall_strip.hpp): row k also holds c_kw for wall points w, which move with
  // their wall: L_k = sum_l v_l (x) b_kl + sum_w v_w (x) c_kw. Empty rows without strips.
  std::vector<std::int32_t> wall_offset;  // n_nodes + 1 row starts (empty: no wall terms)
  std::vector<std::int32_t> wall_column;  // wall point w of each entry
  std::vector<Vec2> wall_gradient;        // c_kw (1/m)
  std::vector<Vec2> wall_velocity;        // v_w (m/s) per wall point, copied from the strips
  // Node -> triangles adjacency (CSR), built first and kept so its storage is reused each step;
  // the explicit solver's per-triangle gathers read it too.
  NodeTriangles node_triangles;
  // Per entry r of node_triangles (triangle e around node k): the entries of e's corners
  // t[0], t[1], t[2] in row k, so that a refill adds without searching the row.
  std::vector<std::array<std::int32_t, 3>> corner_entry;
  std::vector<TriangleTerms> triangle_terms;  // per triangle of the mesh, at the last fill
  // Per entry r of node_triangles (triangle e around node k): the weight w_ke with which e's
  // element gradients enter row k, A_k b_kl = sum_e w_ke grad N_l^e (+ wall-strip terms): A_e / 3,
  // plus the boundary-layer strips and wedge e carries at k. The implicit solver's geometric
  // stiffness reads it.
  std::vector<double> triangle_weight;
  // The boundary layer's discrete choices at the last fill that was not frozen: per entry r of
  // node_triangles, whether e counts as well shaped at k; per node, the wedge's branches.
  // frozen_branches = true makes a refill keep them (the implicit solver within an increment,
  // where a switch would make F_int jump between Newton iterates).
  std::vector<std::uint8_t> well_shaped;
  std::vector<std::uint8_t> wedge_branch;
  bool frozen_branches = false;
  std::vector<std::int32_t> row_scratch;  // the build's rows before packing
};

/// V_k: the volume node k's cell stands for, A_k per metre in plane strain, 2 pi r_k A_k in an
/// axisymmetric scene.
inline double cell_volume(const SmoothingCells& cells, std::size_t k) {
  return cells.ring.empty() ? cells.area[k] : cells.ring[k] * cells.area[k];
}

/// Position of `node` among the `length` entries of `row` (a row's columns hold each node once),
/// `length` when absent. No early exit: rows are short (about seven entries) and a data-dependent
/// exit is a mispredicted branch.
inline std::int32_t find_in_row(const std::int32_t* row, std::int32_t length, std::int32_t node) {
  std::int32_t found = length;
  for (std::int32_t j = 0; j < length; ++j) found = row[j] == node ? j : found;
  return found;
}

/// Builds the cells of `mesh` at the current `points`. Reuses the storage of `cells`.
/// `layer_depth` (m) > 0 adds the boundary layer: each surface edge (a, b) (an edge of exactly one
/// kept triangle e) owns a strip of that depth outside it, area |ab| depth, half to each of a and
/// b, and the strip's gradient is grad N^e (the linear field of e extended into the strip); the
/// mitred wedge between the strips at a surface node turning by theta, depth^2 tan(theta / 2)
/// (|tan| capped at 1), goes to that node. The particles are cell-centred, so the mesh through
/// them lies dp/2 inside the material on every face: depth dp/2 gives the cells of a lattice
/// rectangle exactly the body's area while the nodes carry the full particle mass. 0 = the
/// slides' plain cells.
/// `walls` (with layer_depth > 0): the surface edges in `walls->edges` own a wall strip instead
/// of their layer strip.
void build_smoothing_cells(const AlphaMesh& mesh, const std::vector<Vec2>& points,
                           SmoothingCells& cells, double layer_depth = 0.0,
                           const WallStrips* walls = nullptr);

/// Recomputes areas and gradients of cells built by build_smoothing_cells from this same `mesh`
/// (same triangles) at new `points`: the row structure and the transpose map are kept.
/// The wall strips may differ from the build's (they only add to rows that hold their nodes).
void refill_smoothing_cells(const AlphaMesh& mesh, const std::vector<Vec2>& points,
                            SmoothingCells& cells, double layer_depth = 0.0,
                            const WallStrips* walls = nullptr);

/// d(A_k b_kl) / dx_m for every entry l and every entry m of row k (row k's terms depend only on
/// the nodes of its row): out[(l * len + m) * 2 + c] = d(A_k b_kl) / d(x_m)_c, len the row's
/// length, by central differences of step `h` (m) of the row's own construction (boundary layer,
/// wedge and wall strips included; a free-slip strip's wall points move with their nodes, a
/// no-slip strip's stay). `cells` must have been filled from `mesh` at `points`; `points` and the
/// strips' wall points are perturbed and restored, and row k is refilled at the end (bitwise as
/// before). Serial: it writes the triangle terms shared with the neighbouring rows. With
/// `hoop_out` (an axisymmetric row, cells.hoop set), also (*hoop_out)[l * len + m] =
/// d(A_k h_kl) / dx_m by the same differences (the hoop force's geometric part).
void row_position_derivative(const AlphaMesh& mesh, std::vector<Vec2>& points, std::size_t k,
                             double layer_depth, WallStrips* walls, double h, SmoothingCells& cells,
                             std::vector<Vec2>& out, std::vector<Vec2>* hoop_out = nullptr);

/// Axisymmetric scenes: ring_k = 2 pi r_k and the smoothed hoop strain's rows at `points` (the
/// cells filled from `mesh` there). The hoop strain is the cell's mean of each triangle's u_r / r
/// at its centroid c_e (one-point quadrature of the ring volume, Pappus), weighted as the triangle
/// enters the in-plane row:
///   A_k h_kl = sum_{e at k, l in e} w_ke / (3 r_c,e) + delta_kl (A_k - sum_e w_ke) / r_k,
/// w_ke = triangle_weight (A_e / 3 plus the layer strips e carries); the wall strips' area takes
/// the node's own u_r,k / r_k. It is exact for u_r = a r (patch test), and with V_k = 2 pi r_k A_k
/// the internal force of a uniform stress vanishes at every interior node exactly:
/// sum_k r_k (A_e / 3) over e's corners is A_e r_c,e = int_e r dA, so sum_k V_k (sigma_rr b_kl,r
/// + sigma_tt h_kl) sums int_e (r dN_l/dr + N_l) dA = int d(r N_l)/dr dA = 0 over l's triangles.
/// A cell's volumetric strain is then the mean of one linear field's, as in plane strain (a nodal
/// u_r,k / r_k beside the smoothed in-plane strain mixes a cell mean with a point value and locks
/// near nu = 1/2: tests/spfem/axisymmetric_benchmark_test.cpp at nu 0.497).
void fill_axisymmetric_terms(const AlphaMesh& mesh, const std::vector<Vec2>& points,
                             SmoothingCells& cells);

/// eps_tt,k rate (or increment) = sum_l v_r,l h_kl of an axisymmetric row (cells.hoop set).
inline double smoothed_hoop_rate(const SmoothingCells& cells, const std::vector<Vec2>& velocity,
                                 std::size_t k) {
  double rate = 0.0;
  for (std::int32_t e = cells.offset[k]; e < cells.offset[k + 1]; ++e) {
    rate += cells.hoop[std::size_t(e)] * velocity[std::size_t(cells.column[std::size_t(e)])].x();
  }
  return rate;
}

/// L_k(i, j) = dv_i/dx_j = sum_l v_l,i b_kl,j (+ sum_w v_w,i c_kw,j: wall strips) at every node
/// (zero for a node in no triangle).
void smoothed_velocity_gradients(const SmoothingCells& cells, const std::vector<Vec2>& velocity,
                                 std::vector<Mat2>& gradient);

/// F_int,l = sum_k V_k sigma_k b_kl (in-plane part of sigma), gathered per node l without races;
/// the equation of motion is m a = F_ext - F_int. Axisymmetric (cells.ring and cells.hoop set),
/// the virtual work sum_k V_k sigma_k : delta eps_k with the smoothed hoop strain
/// delta eps_tt,k = sum_l delta u_r,l h_kl adds the hoop force sum_k V_k sigma_tt,k h_kl to node
/// l's radial (x) component (fill_axisymmetric_terms; tests/spfem/axisymmetric_test.cpp).
void internal_forces(const SmoothingCells& cells, const std::vector<Mat3>& stress,
                     std::vector<Vec2>& force);

}  // namespace duet::spfem
