#include "spfem/stiffness_stabilisation.hpp"

#include <algorithm>
#include <cassert>

namespace duet::spfem {

namespace {

// Below this many nodes (or triangles) a loop runs on one thread (as in explicit_solver.cpp).
constexpr std::size_t kParallelMin = 2048;

// A reference triangle with 2 A0 below this fraction of its longest edge squared is left out
// (a right isosceles lattice triangle has 0.5).
constexpr double kMinReferenceShape = 1e-2;

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// The per-triangle terms (F_e, G_a^e, A0_e, s A0_e M_e / 3) and the per-node ones (Abar_k,
/// Fbar_k, Q_k); returns W.
double node_terms(const std::vector<Triangle>& triangles, const NodeTriangles& rows,
                  const std::vector<Vec2>& reference, const std::vector<Vec2>& position,
                  const std::vector<double>& modulus, double s,
                  StiffnessStabilisationScratch& scratch) {
  const std::size_t n_triangles = triangles.size();
  const std::size_t n = position.size();
  assert(reference.size() == n && modulus.size() == n && rows.offset.size() == n + 1);
  scratch.deformation_gradient.resize(n_triangles);
  scratch.reference_gradient.resize(n_triangles);
  scratch.reference_area.resize(n_triangles);
  scratch.stiffness.resize(n_triangles);
  scratch.mean_gradient.resize(n);
  scratch.node_stress.resize(n);
  scratch.node_area.resize(n);
#pragma omp parallel for schedule(static) if (n_triangles > kParallelMin)
  for (std::size_t e = 0; e < n_triangles; ++e) {
    const Triangle& t = triangles[e];
    const Vec2& x0 = reference[static_cast<std::size_t>(t[0])];
    const Vec2& x1 = reference[static_cast<std::size_t>(t[1])];
    const Vec2& x2 = reference[static_cast<std::size_t>(t[2])];
    const double twice = cross(x1 - x0, x2 - x0);
    const double longest =
        std::max({(x1 - x0).squaredNorm(), (x2 - x1).squaredNorm(), (x0 - x2).squaredNorm()});
    if (!(twice > kMinReferenceShape * longest)) {
      scratch.reference_area[e] = 0.0;
      scratch.stiffness[e] = 0.0;
      scratch.deformation_gradient[e] = Mat2::Zero();
      scratch.reference_gradient[e] = {Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};
      continue;
    }
    // grad_X N_i = (Y_j - Y_k, X_k - X_j) / (2 A0) for (i, j, k) cyclic
    std::array<Vec2, 3>& g = scratch.reference_gradient[e];
    g = {Vec2(x1.y() - x2.y(), x2.x() - x1.x()) / twice,
         Vec2(x2.y() - x0.y(), x0.x() - x2.x()) / twice,
         Vec2(x0.y() - x1.y(), x1.x() - x0.x()) / twice};
    Mat2 f = Mat2::Zero();
    double m = 0.0;
    for (std::size_t i = 0; i < 3; ++i) {
      const auto a = static_cast<std::size_t>(t[i]);
      f += position[a] * g[i].transpose();  // F = sum_a x_a (x) G_a
      m += modulus[a] / 3.0;
    }
    scratch.deformation_gradient[e] = f;
    scratch.reference_area[e] = 0.5 * twice;
    scratch.stiffness[e] = s * 0.5 * twice * m / 3.0;
  }
  double energy = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : energy) if (n > kParallelMin)
  for (std::size_t k = 0; k < n; ++k) {
    double area = 0.0;
    Mat2 mean = Mat2::Zero();
    for (std::int32_t r = rows.offset[k]; r < rows.offset[k + 1]; ++r) {
      const auto e = static_cast<std::size_t>(rows.triangle[static_cast<std::size_t>(r)]);
      area += scratch.reference_area[e];
      mean += scratch.reference_area[e] * scratch.deformation_gradient[e];
    }
    Mat2 q = Mat2::Zero();
    if (area > 0.0) {
      mean /= area;
      for (std::int32_t r = rows.offset[k]; r < rows.offset[k + 1]; ++r) {
        const auto e = static_cast<std::size_t>(rows.triangle[static_cast<std::size_t>(r)]);
        const Mat2 jump = scratch.deformation_gradient[e] - mean;
        // 1/2 (A0_e / 3) s M_e |F_e - Fbar_k|^2 and its conjugate (s A0_e M_e / 3)(F_e - Fbar_k)
        energy += 0.5 * scratch.stiffness[e] * jump.squaredNorm();
        q += scratch.stiffness[e] * jump;
      }
    }
    scratch.node_area[k] = area;
    scratch.mean_gradient[k] = mean;
    scratch.node_stress[k] = q;
  }
  return energy;
}

}  // namespace

double stiffness_stabilisation_energy(const std::vector<Triangle>& triangles,
                                      const NodeTriangles& rows, const std::vector<Vec2>& reference,
                                      const std::vector<Vec2>& position,
                                      const std::vector<double>& modulus, double s,
                                      StiffnessStabilisationScratch& scratch) {
  return node_terms(triangles, rows, reference, position, modulus, s, scratch);
}

double stiffness_stabilisation_forces(const std::vector<Triangle>& triangles,
                                      const NodeTriangles& rows, const std::vector<Vec2>& reference,
                                      const std::vector<Vec2>& position,
                                      const std::vector<double>& modulus, double s,
                                      StiffnessStabilisationScratch& scratch,
                                      std::vector<Vec2>& force) {
  const double energy = node_terms(triangles, rows, reference, position, modulus, s, scratch);
  const std::size_t n_triangles = triangles.size();
  const std::size_t n = position.size();
  scratch.triangle_stress.resize(n_triangles);
  // P_e = sum_{k in e} [ (s A0_e M_e / 3)(F_e - Fbar_k) - (A0_e / Abar_k) Q_k ]: the first term
  // from dF_e/dx, the second from dFbar_k/dx (the full derivative)
#pragma omp parallel for schedule(static) if (n_triangles > kParallelMin)
  for (std::size_t e = 0; e < n_triangles; ++e) {
    Mat2 p = Mat2::Zero();
    if (scratch.reference_area[e] > 0.0) {
      for (const std::int32_t node : triangles[e]) {
        const auto k = static_cast<std::size_t>(node);
        p += scratch.stiffness[e] * (scratch.deformation_gradient[e] - scratch.mean_gradient[k]) -
             (scratch.reference_area[e] / scratch.node_area[k]) * scratch.node_stress[k];
      }
    }
    scratch.triangle_stress[e] = p;
  }
  // f_a = -dW/dx_a = -sum_{e at a} P_e G_a^e, gathered per node
  force.resize(n);
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::size_t a = 0; a < n; ++a) {
    Vec2 f = Vec2::Zero();
    for (std::int32_t r = rows.offset[a]; r < rows.offset[a + 1]; ++r) {
      const auto e = static_cast<std::size_t>(rows.triangle[static_cast<std::size_t>(r)]);
      const Triangle& t = triangles[e];
      const std::size_t i = t[0] == static_cast<std::int32_t>(a)   ? 0
                            : t[1] == static_cast<std::int32_t>(a) ? 1
                                                                   : 2;
      f -= scratch.triangle_stress[e] * scratch.reference_gradient[e][i];
    }
    force[a] = f;
  }
  return energy;
}

void stiffness_stabilisation_hessian(const std::vector<Triangle>& triangles,
                                     const NodeTriangles& rows,
                                     const StiffnessStabilisationScratch& scratch, std::size_t k,
                                     const std::int32_t* row, std::int32_t length,
                                     std::vector<double>& out) {
  out.assign(std::size_t(length * length), 0.0);
  const double area = scratch.node_area[k];
  if (!(area > 0.0)) return;
  const auto local = [&](std::int32_t node) {
    std::int32_t found = length;
    for (std::int32_t j = 0; j < length; ++j) found = row[j] == node ? j : found;
    return found;
  };
  // The mean part: sum_{e' at k} (A0_e' / Abar_k) G_a^e' per row node
  std::vector<Vec2> mean(static_cast<std::size_t>(length), Vec2::Zero());
  for (std::int32_t r = rows.offset[k]; r < rows.offset[k + 1]; ++r) {
    const auto e = std::size_t(rows.triangle[std::size_t(r)]);
    const double weight = scratch.reference_area[e] / area;
    for (std::size_t c = 0; c < 3; ++c) {
      const std::int32_t j = local(triangles[e][c]);
      if (j < length) mean[std::size_t(j)] += weight * scratch.reference_gradient[e][c];
    }
  }
  std::vector<Vec2> h(static_cast<std::size_t>(length));
  for (std::int32_t r = rows.offset[k]; r < rows.offset[k + 1]; ++r) {
    const auto e = std::size_t(rows.triangle[std::size_t(r)]);
    const double c_e = scratch.stiffness[e];
    if (c_e == 0.0) continue;
    for (std::int32_t j = 0; j < length; ++j) h[std::size_t(j)] = -mean[std::size_t(j)];
    for (std::size_t c = 0; c < 3; ++c) {
      const std::int32_t j = local(triangles[e][c]);
      if (j < length) h[std::size_t(j)] += scratch.reference_gradient[e][c];
    }
    for (std::int32_t i = 0; i < length; ++i) {
      for (std::int32_t j = 0; j < length; ++j) {
        out[std::size_t(i * length + j)] += c_e * h[std::size_t(i)].dot(h[std::size_t(j)]);
      }
    }
  }
}

}  // namespace duet::spfem
