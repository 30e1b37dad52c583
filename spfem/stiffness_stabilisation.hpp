#pragma once
// Stiffness (hourglass-type) stabilisation of node-based strain smoothing (NS-FEM), total
// Lagrangian and objective, in the spirit of the stabilised nodal integration of Puso & Solberg
// 2006 and Puso, Chen, Zywicz & Elmer 2008 (neither paper is at hand, so no equation
// numbers are cited here). Nodal integration sees only the smoothed deformation Fbar_k of each
// node; a mode whose element gradients differ from their nodes' means (hourglass, checkerboard)
// costs it no energy, which leaves the body soft in bending. This adds the energy of that
// difference:
//
//   F_e    = sum_{a in e} x_a (x) G_a^e     deformation gradient of the linear triangle e,
//            G_a^e the gradients of its shape functions on the reference (initial) triangle
//   Fbar_k = sum_{e at k} A0_e F_e / sum_{e at k} A0_e      (reference-area-weighted mean)
//   W      = sum_e sum_{k in e} 1/2 (A0_e / 3) s M_e |F_e - Fbar_k|^2     (Frobenius norm)
//   f_a    = -dW/dx_a                                   (differentiated fully, Fbar_k too)
//
// with s the coefficient (spfem.stiffness_stabilisation) and M_e the mean of the triangle's nodes'
// P-wave moduli (K + 4G/3 or the model's tangent bound, the explicit solver's time-step modulus),
// held fixed in the derivative. W is a function of the current positions that does not change
// under a rigid rotation of them, so the forces are objective and conserve linear and angular
// momentum; W and the forces vanish for every affine deformation (F_e = Fbar_k = F: patch test).
// The full derivative is dW/dx_a = sum_{e at a} P_e G_a^e with
//   P_e = sum_{k in e} [ (s A0_e M_e / 3) (F_e - Fbar_k) - (A0_e / Abar_k) Q_k ],
//   Q_k = sum_{e at k} (s A0_e M_e / 3) (F_e - Fbar_k),   Abar_k = sum_{e at k} A0_e;
// Q_k vanishes where M is the same over k's triangles (Fbar_k minimises sum_e A0_e |F_e - F|^2), so
// "Fbar_k held fixed" would give the same force there. All loops gather per triangle or per node,
// so they are free of races under OpenMP.

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "common/tensor.hpp"
#include "constitutive/model.hpp"
#include "spfem/alpha_mesh.hpp"

namespace duet::spfem {

/// M (constitutive::block_modulus): the explicit solver's time step (ExplicitSolver::time_step)
/// and both solvers' stiffness stabilisation (M_e) read it.
using constitutive::block_modulus;

/// Per-triangle and per-node terms, kept between calls so their storage is reused.
struct StiffnessStabilisationScratch {
  std::vector<Mat2> deformation_gradient;               // F_e
  std::vector<std::array<Vec2, 3>> reference_gradient;  // G_a^e (1/m)
  std::vector<double> reference_area;                   // A0_e (m^2); 0: left out (degenerate)
  std::vector<double> stiffness;                        // s A0_e M_e / 3 (N/m per metre)
  std::vector<Mat2> triangle_stress;                    // P_e (N/m per metre)
  std::vector<Mat2> mean_gradient;                      // Fbar_k
  std::vector<Mat2> node_stress;                        // Q_k
  std::vector<double> node_area;                        // Abar_k (m^2)
};

/// W (J/m) of the mesh `triangles` (counter-clockwise at `position`) with the nodes' `reference`
/// (initial) positions, per-node P-wave moduli `modulus` (Pa) and coefficient `s` (-). A
/// triangle whose reference triangle is degenerate or inverted (twice its signed area below 1e-2
/// of its longest reference edge squared: a remeshed node pair that were never neighbours) is left
/// out of W and of every Fbar_k.
double stiffness_stabilisation_energy(const std::vector<Triangle>& triangles,
                                      const NodeTriangles& rows, const std::vector<Vec2>& reference,
                                      const std::vector<Vec2>& position,
                                      const std::vector<double>& modulus, double s,
                                      StiffnessStabilisationScratch& scratch);

/// force[a] = -dW/dx_a (N/m) for every node (zero for a node in no triangle); `force` is resized
/// to the number of nodes. Returns W (J/m).
double stiffness_stabilisation_forces(const std::vector<Triangle>& triangles,
                                      const NodeTriangles& rows, const std::vector<Vec2>& reference,
                                      const std::vector<Vec2>& position,
                                      const std::vector<double>& modulus, double s,
                                      StiffnessStabilisationScratch& scratch,
                                      std::vector<Vec2>& force);

/// The Hessian of W for node k's terms: W is quadratic in the positions with M_e held fixed, so
///   d^2 W_k / dx_a dx_b = sum_{e at k} (s A0_e M_e / 3) (h_a . h_b) I_2,
///   h_a = G_a^e [a in e] - sum_{e' at k} (A0_e' / Abar_k) G_a^e' [a in e'],
/// exact (the implicit solver's tangent). `row` lists the `length` nodes of the triangles around
/// k (k's smoothing row); out[i * length + j] is the factor of I_2 for (row[i], row[j]). Reads
/// the scratch of the last energy or forces call on the same mesh.
void stiffness_stabilisation_hessian(const std::vector<Triangle>& triangles,
                                     const NodeTriangles& rows,
                                     const StiffnessStabilisationScratch& scratch, std::size_t k,
                                     const std::int32_t* row, std::int32_t length,
                                     std::vector<double>& out);

}  // namespace duet::spfem
