#include "spfem/smoothing.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <numbers>

namespace duet::spfem {
namespace {

using Index = std::int32_t;

// Below this many nodes a loop runs on one thread: a parallel region costs more than the work,
// and far more when the cores are shared (as in spfem/explicit_solver.cpp).
constexpr std::ptrdiff_t kParallelMin = 2048;

// In-plane vector turned a quarter turn counter-clockwise: (x, y) -> (-y, x).
Vec2 quarter_turn(const Vec2& a) {
  return Vec2(-a.y(), a.x());
}

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Linear triangle (a, b, c) counter-clockwise, signed area A_e = (x_b - x_a) x (x_c - x_a) / 2.
// N_a = [x_b y_c - x_c y_b + (y_b - y_c) x + (x_c - x_b) y] / (2 A_e) (zero on edge bc, one at a),
// so grad N_a = (y_b - y_c, x_c - x_b) / (2 A_e): the opposite edge x_c - x_b turned a quarter
// turn counter-clockwise, over 2 A_e (it points from edge bc towards a, length 1 / height).
// What a triangle adds to b_kl A_k is (A_e / 3) grad N_l^e = quarter_turn(opposite edge of l) / 6:
// the area cancels.
TriangleTerms triangle_terms(const Triangle& t, const std::vector<Vec2>& points) {
  const Vec2& a = points[t[0]];
  const Vec2& b = points[t[1]];
  const Vec2& c = points[t[2]];
  TriangleTerms terms;
  terms.area = 0.5 * cross(b - a, c - a);
  // Zhang 2018 slides, "Strain smoothing technique": (1/3) A_e^j N_l,h^j for l = a, b, c
  terms.weighted_gradient = {quarter_turn(c - b) / 6.0, quarter_turn(a - c) / 6.0,
                             quarter_turn(b - a) / 6.0};
  return terms;
}

// True when `node` is a corner of exactly one triangle around k: then the edge (k, node) belongs
// to that triangle only and lies on the surface of the mesh.
bool is_surface_edge(const SmoothingCells& cells, const std::vector<Triangle>& triangles,
                     std::size_t k, Index node) {
  int count = 0;
  for (Index i = cells.node_triangles.offset[k]; i < cells.node_triangles.offset[k + 1]; ++i) {
    const Triangle& t = triangles[cells.node_triangles.triangle[i]];
    if (t[0] == node || t[1] == node || t[2] == node) ++count;
  }
  return count == 1;
}

double longest_edge(const Triangle& t, const std::vector<Vec2>& points) {
  const Vec2& a = points[t[0]];
  const Vec2& b = points[t[1]];
  const Vec2& c = points[t[2]];
  return std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
}

// Adds factor x (A_e / 3) grad N_l^e for the three corners l of a triangle to their entries of
// one row (SmoothingCells::corner_entry).
void add_terms(const TriangleTerms& terms, double factor, const std::array<Index, 3>& entries,
               SmoothingCells& cells) {
  for (int corner = 0; corner < 3; ++corner) {
    cells.gradient[entries[corner]] += factor * terms.weighted_gradient[corner];
  }
}

// Row k's columns (k, then its neighbours in the order the triangles around k first meet them)
// into `row` (room for 2 + 2 x its triangles: one past the longest row) and, per triangle around k,
// the positions of its corners in the row: what add_terms needs, set once per mesh. Returns the
// row's length (0 for a node in no triangle).
Index collect_row(const std::vector<Triangle>& triangles, std::size_t k, Index* row,
                  SmoothingCells& cells) {
  const Index first = cells.node_triangles.offset[k];
  const Index last = cells.node_triangles.offset[k + 1];
  if (first == last) return 0;
  Index length = 1;
  row[0] = Index(k);
  for (Index i = first; i < last; ++i) {
    const Triangle& t = triangles[cells.node_triangles.triangle[i]];
    for (int corner = 0; corner < 3; ++corner) {
      const Index found = find_in_row(row, length, t[corner]);
      row[length] = t[corner];  // kept only when new
      length += found == length ? 1 : 0;
      cells.corner_entry[i][corner] = found;
    }
  }
  return length;
}

// Row k: b_kl A_k = sum over the triangles e around k of (A_e / 3) grad N_l^e, then A_k and b_kl.
// Boundary layer (depth > 0): the particles are cell-centred, so the mesh through them lies dp/2
// inside the material on every face. Each surface edge (k, m) of a triangle e owns a strip of that
// depth outside it; k gets half, s = |km| depth / 2, on A_k and s grad N_l^e on A_k b_kl (the
// linear field of e extended into the strip). A thin triangle (smallest altitude below the depth,
// e.g. an alpha-shape sliver) would extrapolate its gradient, of order 1 / altitude, far beyond
// itself and stiffen the node without bound (the time step from sqrt(A_k) would not see it): its
// strip is spread over the node's well-shaped triangles in proportion to A_e instead, and dropped
// (A_k loses it) where the node has none. At a surface node with one incoming and one outgoing
// surface edge turning by theta, the mitred wedge between their strips, depth^2 tan(theta / 2)
// (negative where the strips overlap at a concave corner; |tan| capped at 1, the square of a
// right-angled corner), is spread the same way. Every term is an exact element gradient times a
// weight, so a linear velocity is still reproduced exactly (patch test) and
// F_int = sum_k A_k B_k^T sigma_k keeps its virtual power.
// A wall edge (spfem/wall_strip.hpp) owns a wall strip instead of its layer strip.
void fill_row(const std::vector<Triangle>& triangles, const std::vector<Vec2>& points,
              std::size_t k, double layer_depth, bool on_surface, const WallStrips* walls,
              SmoothingCells& cells) {
  const Index row_begin = cells.offset[k];
  const Index row_end = cells.offset[k + 1];
  for (Index entry = row_begin; entry < row_end; ++entry) cells.gradient[entry].setZero();
  const double depth = layer_depth;
  double area = 0.0;
  double plain_area = 0.0;       // sum_e A_e / 3, the slides' cell
  double well_area = 0.0;        // sum_e A_e / 3 over the well-shaped triangles at k
  double spread = 0.0;           // layer area spread over them
  Vec2 incoming = Vec2::Zero();  // surface edges at k, counter-clockwise (material on the left)
  Vec2 outgoing = Vec2::Zero();
  int n_incoming = 0;
  int n_outgoing = 0;
  int n_walled = 0;         // surface edges at k that own a wall strip
  double wall_wedge = 0.0;  // wedge carried by the wall strips at k
  for (Index i = cells.node_triangles.offset[k]; i < cells.node_triangles.offset[k + 1]; ++i) {
    const Triangle& t = triangles[cells.node_triangles.triangle[i]];
    const TriangleTerms& terms = cells.triangle_terms[cells.node_triangles.triangle[i]];
    plain_area += terms.area / 3.0;  // Zhang 2018 slides: A^(k) = (1/3) sum A_e^j
    // Weight of grad N^e in this row: A_e / 3, plus the strips of e's surface edges at k
    // (weighted_gradient holds (A_e / 3) grad N^e, so the strips enter as a factor on it).
    double factor = 1.0;
    bool well_shaped =
        depth > 0.0 && on_surface && 2.0 * terms.area >= depth * longest_edge(t, points);
    // Frozen branches (the implicit solver, within an increment): the shape test as at the
    // increment's start, so that F_int stays smooth in the nodes' positions
    if (cells.frozen_branches) {
      well_shaped = cells.well_shaped[i] != 0;
    } else {
      cells.well_shaped[i] = well_shaped ? 1 : 0;
    }
    if (well_shaped) well_area += terms.area / 3.0;
    if (depth > 0.0 && on_surface) {
      const int at = t[0] == Index(k) ? 0 : (t[1] == Index(k) ? 1 : 2);
      const Index next = t[(at + 1) % 3];
      const Index previous = t[(at + 2) % 3];
      for (const Index m : {next, previous}) {
        if (!is_surface_edge(cells, triangles, k, m)) continue;
        const Vec2 edge = m == next ? points[next] - points[k] : points[k] - points[previous];
        const double length = edge.norm();
        const bool walled = walls != nullptr && (m == next ? is_wall_edge(*walls, k, Index(k), m)
                                                           : is_wall_edge(*walls, k, m, Index(k)));
        if (walled) ++n_walled;
        const double strip = walled ? 0.0 : 0.5 * length * depth;  // this node's half
        area += strip;
        if (well_shaped) {
          factor += strip / (terms.area / 3.0);  // strip x grad N^e
        } else {
          spread += strip;
        }
        if (m == next) {
          outgoing = edge;
          ++n_outgoing;
        } else {
          incoming = edge;
          ++n_incoming;
        }
      }
    }
    add_terms(terms, factor, cells.corner_entry[i], cells);
    cells.triangle_weight[i] = factor * terms.area / 3.0;
  }
  if (n_incoming == 1 && n_outgoing == 1) {
    const double turn = std::atan2(cross(incoming, outgoing), incoming.dot(outgoing));
    // A strip along an edge shorter than the depth makes the turn between the edges arbitrary
    // (two surface nodes nearly together): the wedge is held within depth x the shorter edge.
    const double shorter = std::min(incoming.norm(), outgoing.norm());
    const double slope = std::tan(0.5 * turn);
    // Branches: bit 0, the wedge held within depth x the shorter edge; bits 1-2, |tan| capped
    // at 1 from above (2) or below (4). Frozen: as at the increment's start.
    std::uint8_t branch = 0;
    if (cells.frozen_branches) {
      branch = cells.wedge_branch[k];
    } else {
      branch =
          std::uint8_t((shorter < depth ? 1 : 0) | (slope > 1.0 ? 2 : 0) | (slope < -1.0 ? 4 : 0));
      cells.wedge_branch[k] = branch;
    }
    const double reach = (branch & 1) != 0 ? shorter : depth;
    const double capped = (branch & 2) != 0 ? 1.0 : ((branch & 4) != 0 ? -1.0 : slope);
    const double wedge = depth * reach * capped;
    if (n_walled > 0) {
      wall_wedge = wedge;  // the corner against the wall: the wall strip's gradient
    } else {
      area += wedge;
      spread += wedge;
    }
  }
  if (spread != 0.0 && well_area > 0.0) {
    // spread x the gradient smoothed over the well-shaped triangles:
    // sum_e (spread / well_area) (A_e / 3) grad N^e
    for (Index i = cells.node_triangles.offset[k]; i < cells.node_triangles.offset[k + 1]; ++i) {
      const TriangleTerms& terms = cells.triangle_terms[cells.node_triangles.triangle[i]];
      if (cells.well_shaped[i] != 0) {  // the first pass's test (or the frozen one)
        add_terms(terms, spread / well_area, cells.corner_entry[i], cells);
        cells.triangle_weight[i] += spread / well_area * terms.area / 3.0;
      }
    }
  } else {
    area -= spread;  // no well-shaped triangle to carry it: the node gets no layer there
  }
  area += plain_area;
  if (walls != nullptr) {
    area += add_wall_strip_terms(*walls, points, k, row_begin, row_end, wall_wedge, cells);
  }
  assert((row_end == row_begin || area > 0.0) && "a smoothing-cell area is not positive");
  cells.area[k] = area;
  if (area != 0.0) {  // signed areas: an inverted triangle still counts consistently
    // Zhang 2018 slides, "Strain smoothing": b_lh(x_k) = (1/A^(k)) sum_j (1/3) A_e^j N_l,h^j
    for (Index entry = row_begin; entry < row_end; ++entry) cells.gradient[entry] /= area;
    for (Index entry = cells.wall_offset[k]; entry < cells.wall_offset[k + 1]; ++entry) {
      cells.wall_gradient[entry] /= area;
    }
  }
}

// Row k of the axisymmetric hoop strain (smoothing.hpp fill_axisymmetric_terms) from the row's
// triangle weights at `points`; a row's first entry is the node itself (collect_row).
void fill_hoop_row(const std::vector<Triangle>& triangles, const std::vector<Vec2>& points,
                   std::size_t k, SmoothingCells& cells) {
  const Index begin = cells.offset[k];
  const Index end = cells.offset[k + 1];
  for (Index entry = begin; entry < end; ++entry) cells.hoop[entry] = 0.0;
  const double area = cells.area[k];
  if (begin == end || area == 0.0) return;
  assert(cells.column[begin] == Index(k));
  double carried = 0.0;  // sum_e w_ke
  for (Index i = cells.node_triangles.offset[k]; i < cells.node_triangles.offset[k + 1]; ++i) {
    const Triangle& t = triangles[cells.node_triangles.triangle[i]];
    const double w = cells.triangle_weight[i];
    // Each corner's shape function has the mean 1/3 at the centroid, where u_r / r is taken
    const double r_c = (points[t[0]].x() + points[t[1]].x() + points[t[2]].x()) / 3.0;
    for (const Index entry : cells.corner_entry[i]) cells.hoop[entry] += w / (3.0 * r_c);
    carried += w;
  }
  cells.hoop[begin] += (area - carried) / points[k].x();  // the wall strips' area
  for (Index entry = begin; entry < end; ++entry) cells.hoop[entry] /= area;
}

}  // namespace

void fill_axisymmetric_terms(const AlphaMesh& mesh, const std::vector<Vec2>& points,
                             SmoothingCells& cells) {
  const std::size_t n_nodes = points.size();
  const std::ptrdiff_t n = std::ptrdiff_t(n_nodes);
  cells.ring.resize(n_nodes);
  cells.hoop.resize(cells.gradient.size());
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    cells.ring[std::size_t(k)] = 2.0 * std::numbers::pi * points[std::size_t(k)].x();
    fill_hoop_row(mesh.triangles, points, std::size_t(k), cells);
  }
}

void build_smoothing_cells(const AlphaMesh& mesh, const std::vector<Vec2>& points,
                           SmoothingCells& cells, double layer_depth, const WallStrips* walls) {
  const std::size_t n_nodes = points.size();
  const std::vector<Triangle>& triangles = mesh.triangles;
  build_node_triangles(triangles, n_nodes, cells.node_triangles);

  // Row k holds k and its distinct neighbours (none for a node in no triangle), at most
  // 1 + 2 x its triangles: collected per node into scratch, then packed.
  const std::ptrdiff_t n = std::ptrdiff_t(n_nodes);
  const NodeTriangles& around = cells.node_triangles;
  cells.offset.resize(n_nodes + 1);
  cells.offset[0] = 0;
  cells.corner_entry.resize(around.triangle.size());
  // 2 + 2 x its triangles: collect_row writes one past the row's length before it knows
  // whether the node is new
  cells.row_scratch.resize(2 * n_nodes + 2 * around.triangle.size());
  const auto scratch_row = [&](std::ptrdiff_t k) {
    return cells.row_scratch.data() + 2 * k + 2 * std::ptrdiff_t(around.offset[std::size_t(k)]);
  };
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    cells.offset[k + 1] = collect_row(triangles, std::size_t(k), scratch_row(k), cells);
  }
  for (std::size_t k = 1; k <= n_nodes; ++k) cells.offset[k] += cells.offset[k - 1];

  const std::size_t n_entries = std::size_t(cells.offset[n_nodes]);
  cells.area.resize(n_nodes);
  cells.column.resize(n_entries);
  cells.gradient.resize(n_entries);
  cells.transpose.resize(n_entries);
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    const Index begin = cells.offset[k];
    std::copy(scratch_row(k), scratch_row(k) + (cells.offset[k + 1] - begin),
              cells.column.begin() + begin);
    for (Index i = around.offset[k]; i < around.offset[k + 1]; ++i) {
      for (Index& entry : cells.corner_entry[i]) entry += begin;
    }
  }
  refill_smoothing_cells(mesh, points, cells, layer_depth, walls);

  // Transpose: the row of the smaller node of each pair {k, l} finds (l, k) in row l (rows are
  // short, about seven entries) and sets both slots; every slot has exactly one writer.
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    for (Index entry = cells.offset[k]; entry < cells.offset[k + 1]; ++entry) {
      const Index l = cells.column[entry];
      if (l < Index(k)) continue;  // set from row l
      const Index mirror =         // (k, l) shares a triangle: present
          cells.offset[l] + find_in_row(&cells.column[cells.offset[l]],
                                        cells.offset[l + 1] - cells.offset[l], Index(k));
      assert(mirror < cells.offset[l + 1]);
      cells.transpose[entry] = mirror;
      cells.transpose[mirror] = entry;
    }
  }
}

void smoothed_velocity_gradients(const SmoothingCells& cells, const std::vector<Vec2>& velocity,
                                 std::vector<Mat2>& gradient) {
  const std::ptrdiff_t n = std::ptrdiff_t(cells.offset.size()) - 1;
  gradient.resize(std::size_t(n));
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    Mat2 l_k = Mat2::Zero();
    for (Index entry = cells.offset[k]; entry < cells.offset[k + 1]; ++entry) {
      // L_k(i, j) = sum_l v_l,i b_kl,j (Zhang 2018 slides: smoothed B on the nodal velocities)
      l_k.noalias() += velocity[cells.column[entry]] * cells.gradient[entry].transpose();
    }
    if (!cells.wall_offset.empty()) {
      for (Index entry = cells.wall_offset[k]; entry < cells.wall_offset[k + 1]; ++entry) {
        // + sum_w v_w c_kw: the wall strip's vertices move with their wall
        l_k.noalias() +=
            cells.wall_velocity[cells.wall_column[entry]] * cells.wall_gradient[entry].transpose();
      }
    }
    gradient[k] = l_k;
  }
}

void internal_forces(const SmoothingCells& cells, const std::vector<Mat3>& stress,
                     std::vector<Vec2>& force) {
  const std::ptrdiff_t n = std::ptrdiff_t(cells.offset.size()) - 1;
  force.resize(std::size_t(n));
  const bool hoop = !cells.hoop.empty();
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::ptrdiff_t l = 0; l < n; ++l) {
    Vec2 f = Vec2::Zero();
    // Row l lists every k whose cell sees node l; b_kl is entry (k, l), read through transpose.
    for (Index entry = cells.offset[l]; entry < cells.offset[l + 1]; ++entry) {
      const Index k = cells.column[entry];
      const Vec2& b_kl = cells.gradient[cells.transpose[entry]];
      // Zhang 2018 slides, "Strain smoothing technique": F_int = sum_k B_L^(k)T sigma_k A^(k)
      f.noalias() += cell_volume(cells, std::size_t(k)) * (stress[k].topLeftCorner<2, 2>() * b_kl);
      // Axisymmetric: the hoop stress's share, V_k sigma_tt,k h_kl
      if (hoop) {
        f.x() += cell_volume(cells, std::size_t(k)) * stress[k](2, 2) *
                 cells.hoop[cells.transpose[entry]];
      }
    }
    force[l] = f;
  }
}

void row_position_derivative(const AlphaMesh& mesh, std::vector<Vec2>& points, std::size_t k,
                             double layer_depth, WallStrips* walls, double h, SmoothingCells& cells,
                             std::vector<Vec2>& out, std::vector<Vec2>* hoop_out) {
  const std::vector<Triangle>& triangles = mesh.triangles;
  const bool on_surface = mesh.surface.size() != points.size() || mesh.surface[k] != 0;
  const WallStrips* strips =
      layer_depth > 0.0 && walls != nullptr && !walls->edges.empty() ? walls : nullptr;
  const Index begin = cells.offset[k];
  const Index length = cells.offset[k + 1] - begin;
  out.assign(std::size_t(length * length * 2), Vec2::Zero());
  if (hoop_out != nullptr) hoop_out->assign(std::size_t(length * length), Vec2::Zero());
  const auto retriangulate = [&] {
    for (Index i = cells.node_triangles.offset[k]; i < cells.node_triangles.offset[k + 1]; ++i) {
      const Index e = cells.node_triangles.triangle[i];
      cells.triangle_terms[e] = triangle_terms(triangles[e], points);
    }
  };
  // Moves node m (and the free-slip wall points that move with it) by d
  const auto move = [&](Index m, const Vec2& d) {
    points[m] += d;
    if (strips == nullptr) return;
    for (Index j = walls->edge_offset[m]; j < walls->edge_offset[m + 1]; ++j) {  // m's edges
      WallEdge& e = walls->edges[walls->node_edges[j]];
      if (!e.free_slip) continue;
      if (e.a == m) e.a_wall += d;
      if (e.b == m) e.b_wall += d;
    }
  };
  // The row's terms at the current points: fill_row, then the hoop row where asked
  const auto refill_row = [&] {
    retriangulate();
    fill_row(triangles, points, k, layer_depth, on_surface, strips, cells);
    if (hoop_out != nullptr) fill_hoop_row(triangles, points, k, cells);
  };
  std::vector<Vec2> forward(static_cast<std::size_t>(length));
  std::vector<double> forward_hoop(hoop_out != nullptr ? std::size_t(length) : 0);
  for (Index jm = 0; jm < length; ++jm) {
    const Index m = cells.column[begin + jm];
    for (int c = 0; c < 2; ++c) {
      Vec2 d = Vec2::Zero();
      d[c] = h;
      move(m, d);
      refill_row();
      for (Index jl = 0; jl < length; ++jl)
        forward[jl] = cells.area[k] * cells.gradient[begin + jl];
      for (std::size_t jl = 0; jl < forward_hoop.size(); ++jl)
        forward_hoop[jl] = cells.area[k] * cells.hoop[std::size_t(begin) + jl];
      move(m, -2.0 * d);
      refill_row();
      for (Index jl = 0; jl < length; ++jl) {
        out[std::size_t((jl * length + jm) * 2 + c)] =
            (forward[jl] - cells.area[k] * cells.gradient[begin + jl]) / (2.0 * h);
      }
      for (std::size_t jl = 0; jl < forward_hoop.size(); ++jl) {
        (*hoop_out)[jl * std::size_t(length) + std::size_t(jm)][c] =
            (forward_hoop[jl] - cells.area[k] * cells.hoop[std::size_t(begin) + jl]) / (2.0 * h);
      }
      move(m, d);
    }
  }
  refill_row();
}

void refill_smoothing_cells(const AlphaMesh& mesh, const std::vector<Vec2>& points,
                            SmoothingCells& cells, double layer_depth, const WallStrips* walls) {
  // Fill pass: each row written by one thread only, into the entries the build laid out for
  // these triangles (offsets, columns, corner entries and the transpose map stay valid). Only a
  // surface node (flagged by the alpha mesh; every node when the flags are absent, e.g. a mesh
  // built by hand) can own a strip.
  const std::size_t n_nodes = points.size();
  const bool know_surface = mesh.surface.size() == n_nodes;
  const std::ptrdiff_t n = std::ptrdiff_t(n_nodes);
  const WallStrips* strips = layer_depth > 0.0 && walls != nullptr && !walls->edges.empty()
                                 ? walls
                                 : nullptr;  // wall strips replace layer strips only
  size_wall_entries(strips, n_nodes, cells);
  // Each triangle's terms once (a triangle sits in three rows)
  const std::vector<Triangle>& triangles = mesh.triangles;
  const std::ptrdiff_t n_triangles = std::ptrdiff_t(triangles.size());
  cells.triangle_terms.resize(triangles.size());
  cells.triangle_weight.resize(cells.node_triangles.triangle.size());
  cells.well_shaped.resize(cells.node_triangles.triangle.size());
  cells.wedge_branch.resize(n_nodes);
#pragma omp parallel for schedule(static) if (n_triangles > kParallelMin)
  for (std::ptrdiff_t e = 0; e < n_triangles; ++e) {
    cells.triangle_terms[std::size_t(e)] = triangle_terms(triangles[std::size_t(e)], points);
  }
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    fill_row(mesh.triangles, points, std::size_t(k), layer_depth,
             !know_surface || mesh.surface[std::size_t(k)] != 0, strips, cells);
  }
}

}  // namespace duet::spfem
