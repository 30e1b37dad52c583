#pragma once
// The discrete operator of one implicit SPFEM increment (Zhang 2018 slides, "Implicit SPFEM":
// weak form, K_ep + K_g, Newton-Raphson; Zhang et al. 2018): for the displacement u of the nodes
// over the increment, the internal force F_int(u) = sum_k A_k(x) B_L,k(x)^T sigma_k(u) on the
// configuration x = x_n + u (updated Lagrangian), with sigma_k(u) the shared objective stress
// update (Hughes-Winget rotation, then the model) of the increment's gradient
// G_k = sum_l u_l (x) b_kl(x_n) on the configuration at the increment's start, and its exact
// tangent dF_int/du on the free dofs (derived for this project; spfem/README.md):
//   K = sum_k A_k B_L,k^T [D_k B_L,k^0 + sigma_bar_k B_S,k^0]                 material + spin
//     + sum_k sum_{e at k} w_ke [(sigma_k grad N_I^e) (x) grad N_J^e
//                                - (sigma_k grad N_J^e) (x) grad N_I^e]         geometric
// with D_k the model's consistent tangent, sigma_bar_k the derivative of the rotated stress with
// respect to the spin (through D_k C^-1 for a return mapping on the elastic trial), and the
// geometric part from the ELEMENT gradients grad N^e of the triangles that make up row k (weights
// w_ke = SmoothingCells::triangle_weight). Like MFEM's Operator (Mult / GetGradient) it knows
// nothing of Newton; ImplicitSolver drives it.
//
// Axisymmetric (x = r about x = 0, SmoothingCells::ring = 2 pi x_k and the hoop rows h_kl
// filled at x), derived here from the virtual work sum_k V_k sigma_k : delta eps_k with
// V_k(x) = 2 pi x_k A_k(x) and the smoothed hoop strain delta eps_tt,k = sum_l delta u_x,l h_kl
// (spfem/smoothing.hpp fill_axisymmetric_terms, internal_forces):
//   F_int,l = sum_k V_k (sigma_k b_kl + sigma_tt,k h_kl e_x),
// and the increment's hoop strain is sum_l u_x,l h_kl(x_n) (linear in u on x_n, as G_k is), in
// the (2,2) slot of the gradient that goes to the stress update (no spin). With the 4 components
// (rr, zz, rz, tt) of D_k, B_m^0 = [B_L,m^0; h_km(x_n) e_x^T] and the left operator
// V_k [B_L,l; h_kl(x) e_x^T], d/du_m of F_int,l is:
//   material + spin   V_k [B_L,l; h_kl e_x^T]^T [D_k B_m^0 + sigma_bar_k B_S,m^0]
//   ring              2 pi A_k (sigma_k b_kl + sigma_tt,k h_kl e_x) e_x^T delta_mk
//                                                                   (dV_k / dx_k = 2 pi A_k)
//   geometric         2 pi x_k sigma_k d(A_k b_kl)/dx_m            (the plane terms times ring_k)
//   hoop geometric    2 pi x_k sigma_tt,k e_x d(A_k h_kl)/dx_m^T,
// the last two by central differences of row k's own construction (its triangles' centroids and
// weights).
#include <array>
#include <memory>
#include <vector>

#include <Eigen/Sparse>

#include "common/particles.hpp"
#include "common/tensor.hpp"
#include "common/timers.hpp"
#include "constitutive/model.hpp"
#include "spfem/block_tangent.hpp"
#include "spfem/nodal_discretisation.hpp"
#include "spfem/node_constraints.hpp"
#include "spfem/stiffness_stabilisation.hpp"

namespace duet::spfem {

class IncrementOperator {
 public:
  /// The increment starts from `start` (positions, stress, internal variables, material) on the
  /// cells `discretisation` holds now (built at start.position); `wall_increment` is the
  /// displacement of the wall strips' wall points over the increment (2 per strip edge: a', b').
  /// `models` by material index. The discretisation is refilled at every evaluation.
  /// `increment_stabilisation`: spfem.implicit.increment_stabilisation (0: off).
  IncrementOperator(NodalDiscretisation& discretisation,
                    const std::vector<std::unique_ptr<constitutive::Model>>& models,
                    const Particles& start, std::vector<Vec2> wall_increment,
                    Timers* timers = nullptr, double increment_stabilisation = 0.0);

  /// Stress and internal force at the nodal displacement `u`. Returns false when the model
  /// could not integrate (a non-finite stress) or, axisymmetric, when `u` puts a node at r <= 0.
  bool evaluate(const std::vector<Vec2>& u);

  /// The tangent dF_int/du on the free dofs of `dofs` at the state of the last evaluate(), plus
  /// `diagonal[i]` times the identity on node i's block when given (Newmark: c M).
  void assemble_tangent(const DofMap& dofs, const std::vector<double>& diagonal = {});

  const std::vector<Vec2>& internal_force() const { return internal_force_; }
  const std::vector<Mat3>& stress() const { return stress_; }
  const std::vector<double>& internal() const { return internal_; }  // start.internal layout
  const std::vector<Mat3>& strain_increment() const { return strain_increment_; }
  /// dF_int / du on the free dofs, from the last assemble_tangent().
  const SparseMatrix& tangent() const { return tangent_; }
  /// The positions of the last evaluation.
  const std::vector<Vec2>& position() const { return position_; }
  const SmoothingCells& start_cells() const { return start_cells_; }

 private:
  void update_stresses(const std::vector<Vec2>& u);

  NodalDiscretisation& discretisation_;
  const std::vector<std::unique_ptr<constitutive::Model>>& models_;
  const Particles& start_;
  SmoothingCells start_cells_;          // b_kl at x_n (the increment's strain operator)
  std::vector<WallEdge> start_strips_;  // the strips' wall points at x_n
  std::vector<Vec2> wall_increment_;
  std::vector<Vec2> position_;
  std::vector<Mat3> stress_;
  std::vector<double> internal_;
  std::vector<Mat3> strain_increment_;
  using Mat4 = Eigen::Matrix4d;
  using Vec4 = Eigen::Vector4d;
  // D_k on (xx, yy, xy, zz) with engineering shear: the in-plane block and the hoop (zz = tt)
  // row and column, which only an axisymmetric increment strains
  std::vector<Mat4> material_tangent_;
  std::vector<Vec4> spin_stress_;  // d sigma_k (xx, yy, xy, zz) / d W_12
  std::vector<Vec2> internal_force_;
  BlockTangent blocks_;  // the tangent's node pattern, built at the first assembly
  SparseMatrix tangent_;
  // Rows with boundary-layer or wall-strip terms: d(A_k b_kl)/dx_m by central differences
  std::vector<std::vector<Vec2>> row_derivative_;
  // and, axisymmetric (every row), d(A_k h_kl)/dx_m (the hoop force's geometric part)
  std::vector<std::vector<Vec2>> hoop_derivative_;
  Timers own_timers_;         // where the phases go when the caller passes no Timers
  Timers* timers_ = nullptr;  // mesh (refill), constitutive, assembly
  // The stabilisation energies W of spfem/stiffness_stabilisation.hpp, their forces added to
  // F_int and their (exact, constant) Hessians to the tangent:
  //   total: spfem.stiffness_stabilisation, W on the nodes' initial positions with the P-wave
  //     modulus (as the explicit solver's);
  //   increment: spfem.implicit.increment_stabilisation, W on the increment's start with 2 G,
  //     so it holds no stress from one increment to the next (a rate-like resistance of the
  //     increment's hourglass part).
  // M_e from the moduli at the increment's start.
  struct Stabilisation {
    double coefficient = 0.0;
    std::vector<Vec2> reference;
    std::vector<double> modulus;
    std::vector<Vec2> force;
    StiffnessStabilisationScratch scratch;
  };
  std::array<Stabilisation, 2> stabilisation_;
};

}  // namespace duet::spfem
