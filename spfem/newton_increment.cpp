#include "spfem/newton_increment.hpp"

#include <Eigen/UmfPackSupport>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace duet::spfem {

namespace {

// Newton step halvings a line search may take before it accepts the step anyway
constexpr int kLineSearchHalvings = 4;

/// u = u_start + step du on the free dofs.
void take_step(const DofMap& dofs, const std::vector<Vec2>& u_start, const Eigen::VectorXd& du,
               double step, std::vector<Vec2>& u) {
  for (std::size_t i = 0; i < u.size(); ++i) {
    u[i] = u_start[i];
    for (std::int32_t a = dofs.first[i]; a < dofs.first[i + 1]; ++a) {
      u[i] += step * du(a) * dofs.direction[std::size_t(a)];
    }
  }
}

/// Backtracking line search on the residual norm: the full step unless it raises the residual
/// (Tresca's corners make a full Newton step cycle at full plastic flow). Returns the step taken
/// and sets `relative` to the residual there; a step of 0 means the stress update failed.
double line_search(IncrementOperator& op, const DofMap& dofs, IncrementResidual& residual,
                   const Eigen::VectorXd& du, std::vector<Vec2>& u, double& relative,
                   long& halvings) {
  const std::vector<Vec2> u_start = u;
  double step = 1.0;
  for (int search = 0;; ++search) {
    take_step(dofs, u_start, du, step, u);
    const bool finite = op.evaluate(u);
    const double trial = finite ? residual.relative(u) : std::numeric_limits<double>::infinity();
    if ((trial < relative || search >= kLineSearchHalvings) && (finite || search > 0)) {
      if (!finite) return 0.0;
      relative = trial;
      return step;
    }
    step *= 0.5;
    ++halvings;
  }
}

/// Where Newton gave up: the node of the largest residual component, for the user to look at.
std::string no_convergence(const DofMap& dofs, const Eigen::VectorXd& residual, int iterations,
                           const std::vector<Vec2>& positions) {
  Eigen::Index worst = 0;
  residual.cwiseAbs().maxCoeff(&worst);
  const auto node = std::size_t(dofs.node[std::size_t(worst)]);
  std::ostringstream why;
  why << "no convergence in " << iterations << " iterations (largest residual at node " << node
      << ", x = " << positions[node].x() << " m, y = " << positions[node].y() << " m)";
  return why.str();
}

}  // namespace

IncrementResidual::IncrementResidual(const IncrementOperator& op, const DofMap& dofs,
                                     const std::vector<Vec2>& external_force, double external_norm,
                                     const std::vector<std::uint8_t>& held,
                                     const NewmarkIncrement& integrator)
    : op_(op),
      dofs_(dofs),
      external_force_(external_force),
      external_norm_(external_norm),
      held_(held),
      integrator_(integrator),
      residual_(static_cast<Eigen::Index>(dofs.n_free())) {}

double IncrementResidual::relative(const std::vector<Vec2>& u) {
  const std::vector<Vec2>& f_int = op_.internal_force();
  double reaction = 0.0;
  double inertia_norm = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    const Vec2 m_a = integrator_.inertia_force(i, u[i]);
    inertia_norm += m_a.squaredNorm();
    Vec2 r = external_force_[i] - f_int[i] - m_a;
    for (std::int32_t a = dofs_.first[i]; a < dofs_.first[i + 1]; ++a) {
      const Vec2& d = dofs_.direction[std::size_t(a)];
      residual_(a) = r.dot(d);
      r -= residual_(a) * d;
    }
    if (!held_[i]) reaction += r.squaredNorm();
  }
  if (reaction_cap_ < 0.0) {
    reaction_cap_ =
        kReactionGrowth * std::max({external_norm_, std::sqrt(reaction), std::sqrt(inertia_norm)});
  }
  // (the inertia force of a flung node is as enormous: capped alike)
  const double scale = std::max({external_norm_, std::min(std::sqrt(reaction), reaction_cap_),
                                 std::min(std::sqrt(inertia_norm), reaction_cap_)});
  const double norm = residual_.norm();
  return scale > 0.0 ? norm / scale : norm;
}

std::string singular_tangent(const SparseMatrix& tangent, const DofMap& dofs,
                             const std::vector<Vec2>& positions) {
  const auto n = static_cast<std::size_t>(tangent.rows());
  std::vector<double> row_max(n, 0.0), column_max(n, 0.0);
  double largest = 0.0;
  for (Eigen::Index c = 0; c < tangent.outerSize(); ++c) {
    for (SparseMatrix::InnerIterator it(tangent, c); it; ++it) {
      const double a = std::abs(it.value());
      row_max[std::size_t(it.row())] = std::max(row_max[std::size_t(it.row())], a);
      column_max[std::size_t(c)] = std::max(column_max[std::size_t(c)], a);
      largest = std::max(largest, a);
    }
  }
  std::vector<std::int32_t> nodes;  // of the zero rows and columns, each once
  for (std::size_t a = 0; a < n; ++a) {
    if (row_max[a] > 1e-12 * largest && column_max[a] > 1e-12 * largest) continue;
    if (std::find(nodes.begin(), nodes.end(), dofs.node[a]) == nodes.end()) {
      nodes.push_back(dofs.node[a]);
    }
  }
  std::ostringstream why;
  why << "singular tangent (UMFPACK could not factorise it): ";
  if (nodes.empty()) {
    why << "no node's row is zero: a mechanism, a group of nodes free to move together that no "
           "wall, rigid body or stiff neighbour holds";
    return why.str();
  }
  why << nodes.size() << (nodes.size() == 1 ? " node has" : " nodes have")
      << " no stiffness at Newton's last iterate (a zero row or column of the tangent): ";
  for (std::size_t k = 0; k < nodes.size() && k < 3; ++k) {
    const Vec2& x = positions[std::size_t(nodes[k])];
    why << (k > 0 ? "; " : "") << "node " << nodes[k] << " at x = " << x.x() << " m, y = " << x.y()
        << " m";
  }
  if (nodes.size() > 3) why << "; ...";
  why << " (its smoothing cells carry no stiffness, as at a cohesionless soil's apex, or no "
         "triangle holds it)";
  return why.str();
}

// Why an evaluation of the operator failed (IncrementOperator::evaluate returned false)
constexpr const char* kEvaluationFailed =
    "the stress update gave a non-finite stress (or, axisymmetric, a node crossed the axis)";

NewtonOutcome newton_solve(IncrementOperator& op, const DofMap& dofs, IncrementResidual& residual,
                           const std::vector<double>& mass_diagonal,
                           const duet::SpfemImplicitOptions& o, const std::vector<Vec2>& positions,
                           Timers& timers, std::vector<Vec2>& u) {
  NewtonOutcome out;
  if (!op.evaluate(u)) {
    out.why = kEvaluationFailed;
    return out;
  }
  Eigen::UmfPackLU<SparseMatrix> lu;
  // No iterative refinement: on the footing's tangent it cost six times the solve and gave the
  // same residual (1e-13)
  lu.umfpackControl()(UMFPACK_IRSTEP) = 0;
  double relative = residual.relative(u);
  double correction = std::numeric_limits<double>::infinity();
  for (int iteration = 0;; ++iteration) {
    out.residuals.push_back(relative);
    if (!std::isfinite(relative)) {
      out.why = "non-finite residual";
      return out;
    }
    if (relative <= o.tolerance ||
        (correction <= o.displacement_tolerance && relative <= 100.0 * o.tolerance)) {
      out.converged = true;
      return out;
    }
    if (iteration >= o.max_iterations) {
      out.why = no_convergence(dofs, residual.vector(), o.max_iterations, positions);
      return out;
    }
    op.assemble_tangent(dofs, mass_diagonal);
    Eigen::VectorXd du;
    {
      ScopedTimer t(timers, Phase::solve);
      if (iteration == 0) lu.analyzePattern(op.tangent());
      lu.factorize(op.tangent());
      ++out.factorisations;
      if (lu.info() != Eigen::Success) {
        out.why = singular_tangent(op.tangent(), dofs, positions);
        return out;
      }
      du = lu.solve(residual.vector());
      ++out.iterations;
    }
    const double step = line_search(op, dofs, residual, du, u, relative, out.line_search_halvings);
    if (step == 0.0) {
      out.why = kEvaluationFailed;
      return out;
    }
    double u_norm = 0.0;
    for (const Vec2& x : u) u_norm += x.squaredNorm();
    correction = step * du.norm() / std::max(std::sqrt(u_norm), 1e-300);
  }
}

}  // namespace duet::spfem
