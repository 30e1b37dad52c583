#pragma once
// Newton-Raphson on one implicit increment's free dofs (Zhang et al. 2018, "Numerical procedure
// of iSPFEM"): R(u) = F_ext - F_int(u) - M a(u) on the dofs a DofMap leaves free, the exact
// tangent of IncrementOperator factorised by UMFPACK (it is not symmetric), a backtracking line
// search on the residual's norm. The layers follow MFEM's NewtonSolver: the residual (its
// scaling), the iteration, the line search; the increment's contacts (the active set), its time
// integrator (newmark.hpp) and the increment controller live in ImplicitSolver.

#include <Eigen/Dense>
#include <cstdint>
#include <string>
#include <vector>

#include "common/particles.hpp"
#include "common/scene.hpp"
#include "common/tensor.hpp"
#include "common/timers.hpp"
#include "spfem/increment_operator.hpp"
#include "spfem/newmark.hpp"
#include "spfem/node_constraints.hpp"

namespace duet::spfem {

/// The relative residual of an increment on its free dofs. R = F_ext - F_int - M a, relative to
/// the external load or, when the reaction (the residual on the constrained parts) is larger (a
/// prescribed motion and no load: the footing, the cavity), to the reaction. The reaction and the
/// inertia force count at most kReactionGrowth times the largest of the load, the reaction and
/// the inertia force at the first evaluation (the prescribed motion on a body at rest, or the
/// guess): an iterate that flings a node far off has an enormous reaction, against which any
/// residual looks small (ImplicitFootingBenchmark.ASmoothFootingPushedDownKeepsItsNodesAndItsLoad).
class IncrementResidual {
 public:
  static constexpr double kReactionGrowth = 10.0;

  IncrementResidual(const IncrementOperator& op, const DofMap& dofs,
                    const std::vector<Vec2>& external_force, double external_norm,
                    const std::vector<std::uint8_t>& held, const NewmarkIncrement& integrator);

  /// |R| over its scale for the operator's last evaluation at u; fills vector().
  double relative(const std::vector<Vec2>& u);
  const Eigen::VectorXd& vector() const { return residual_; }

 private:
  const IncrementOperator& op_;
  const DofMap& dofs_;
  const std::vector<Vec2>& external_force_;
  double external_norm_;
  const std::vector<std::uint8_t>& held_;
  const NewmarkIncrement& integrator_;
  Eigen::VectorXd residual_;
  double reaction_cap_ = -1.0;  // set at the first evaluation
};

/// Why UMFPACK found `tangent` singular, where it can be seen: the nodes of the free dofs whose row
/// or column is zero (below 1e-12 of the largest entry), with their positions; or, with none, that
/// some group of nodes is a mechanism. A node whose smoothing cells all carry no stiffness (a
/// cohesionless soil at Drucker-Prager's apex, say) has such a row.
std::string singular_tangent(const SparseMatrix& tangent, const DofMap& dofs,
                             const std::vector<Vec2>& positions);

/// What one Newton solve did: its outcome, the relative residual after each iteration, and the
/// work (added to the solver's counters whether it converged or not).
struct NewtonOutcome {
  bool converged = false;
  std::string why;  // when not converged
  std::vector<double> residuals;
  long iterations = 0;  // linear solves
  long factorisations = 0;
  long line_search_halvings = 0;
};

/// Newton from u (the prescribed motion on the constrained parts, a guess on the free dofs) to
/// convergence: the relative residual below o.tolerance, or the relative correction below
/// o.displacement_tolerance with the residual below 100 o.tolerance. u ends at the last iterate.
/// `positions` only say where a failure is.
NewtonOutcome newton_solve(IncrementOperator& op, const DofMap& dofs, IncrementResidual& residual,
                           const std::vector<double>& mass_diagonal,
                           const duet::SpfemImplicitOptions& o, const std::vector<Vec2>& positions,
                           Timers& timers, std::vector<Vec2>& u);

}  // namespace duet::spfem
