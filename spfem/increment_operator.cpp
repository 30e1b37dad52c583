#include "spfem/increment_operator.hpp"

#include <omp.h>

#include <cmath>
#include <numbers>
#include <span>

#include "constitutive/objective.hpp"

namespace duet::spfem {

namespace {

constexpr std::size_t kParallelMin = 2048;  // as in explicit_solver.cpp

// Voigt positions (xx, yy, zz, xy, yz, zx) of the components xx, yy, xy and zz (the hoop tt
// of an axisymmetric scene), in the order of the operator's 4-component D_k.
constexpr int kComponent[4] = {0, 1, 3, 2};

using Vec4 = Eigen::Vector4d;

/// D C^-1 dsigma: how the model's return maps a change of its trial stress, for a model that
/// integrates from an elastic trial sigma + C d_eps (Drucker-Prager, Tresca, Mohr-Coulomb,
/// elasticity); a model with a tangent bound (hypoplastic) integrates a rate, whose start-stress
/// derivative is the identity to first order.
Vec4 through_return(const Mat6& d, const constitutive::ElasticModuli& e, const Mat3& dsigma) {
  if (e.tangent_bound > 0.0 || !(e.shear > 0.0) || !(e.bulk > 0.0)) {
    return Vec4(dsigma(0, 0), dsigma(1, 1), dsigma(0, 1), dsigma(2, 2));
  }
  // elastic compliance: eps = dev(dsigma) / 2G + tr(dsigma) / 9K I, engineering shear
  const double mean = dsigma.trace() / 3.0;
  Vec6 strain;
  for (int i = 0; i < 3; ++i) {
    strain(i) = (dsigma(i, i) - mean) / (2.0 * e.shear) + mean / (3.0 * e.bulk);
  }
  strain(3) = dsigma(0, 1) / e.shear;
  strain(4) = dsigma(1, 2) / e.shear;
  strain(5) = dsigma(0, 2) / e.shear;
  const Vec6 s = d * strain;
  return Vec4(s(0), s(1), s(3), s(2));
}

/// B of one node (4 x 2): [b_x 0; 0 b_y; b_y b_x; hoop 0], `hoop` = 1 / r_k for node k's own
/// entry of an axisymmetric row (the hoop strain u_r / r), else 0.
Eigen::Matrix<double, 4, 2> strain_operator(const Vec2& b, double hoop = 0.0) {
  Eigen::Matrix<double, 4, 2> m;
  m << b.x(), 0.0, 0.0, b.y(), b.y(), b.x(), hoop, 0.0;
  return m;
}

}  // namespace

IncrementOperator::IncrementOperator(
    NodalDiscretisation& discretisation,
    const std::vector<std::unique_ptr<constitutive::Model>>& models, const Particles& start,
    std::vector<Vec2> wall_increment, Timers* timers, double increment_stabilisation)
    : discretisation_(discretisation),
      models_(models),
      start_(start),
      start_cells_(discretisation.cells()),
      start_strips_(discretisation.wall_strips().edges),
      wall_increment_(std::move(wall_increment)),
      timers_(timers != nullptr ? timers : &own_timers_) {
  // The layer's shape tests and wedge branches as at the increment's start (smoothing.hpp)
  discretisation_.freeze_layer_branches(true);
  const std::size_t n = start.size();
  stress_ = start.stress;
  internal_ = start.internal.values;
  strain_increment_.assign(n, Mat3::Zero());
  material_tangent_.assign(n, Mat4::Zero());
  spin_stress_.assign(n, Vec4::Zero());
  internal_force_.assign(n, Vec2::Zero());
  Stabilisation& total = stabilisation_[0];
  Stabilisation& per_increment = stabilisation_[1];
  total.coefficient = discretisation_.options().stiffness_stabilisation;
  per_increment.coefficient = increment_stabilisation;
  const bool total_on = total.coefficient > 0.0;
  const bool increment_on = per_increment.coefficient > 0.0;
  if (!total_on && !increment_on) return;
  if (total_on) {
    total.reference.resize(n);
    total.modulus.resize(n);
  }
  if (increment_on) {
    per_increment.reference = start.position;
    per_increment.modulus.resize(n);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto m = std::size_t(start.material[i]);
    const constitutive::ElasticModuli e = models_[m]->moduli(
        start.stress[i],
        std::span<const double>(start.internal.of(i), models_[m]->internal_variables().size()));
    if (total_on) {
      total.reference[i] = start.position[i] - start.displacement[i];
      total.modulus[i] = block_modulus(e);  // as the explicit solver's
    }
    // 2 G, not the P-wave modulus: at nu near 1/2 the latter would penalise the volumetric part
    // of the deviation some 80 times harder, which is the locking nodal integration avoids
    if (increment_on) per_increment.modulus[i] = 2.0 * std::abs(e.shear);
    // Axisymmetric: each node's modulus weighed by its ring 2 pi r on the energy's reference
    // positions, so that W counts a ring's worth as the internal force does; held fixed, W
    // stays quadratic in x and its Hessian exact
    if (discretisation_.axisymmetric()) {
      constexpr double two_pi = 2.0 * std::numbers::pi;
      if (total_on) total.modulus[i] *= two_pi * total.reference[i].x();
      if (increment_on) per_increment.modulus[i] *= two_pi * per_increment.reference[i].x();
    }
  }
}

void IncrementOperator::update_stresses(const std::vector<Vec2>& u) {
  const std::size_t n = start_.size();
  const SmoothingCells& b0 = start_cells_;
  const std::size_t width = start_.internal.width;
  const bool walls = !b0.wall_offset.empty();
  const bool ring = !b0.ring.empty();
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::size_t k = 0; k < n; ++k) {
    stress_[k] = start_.stress[k];
    std::copy(start_.internal.of(k), start_.internal.of(k) + width, internal_.data() + k * width);
    strain_increment_[k].setZero();
    material_tangent_[k].setZero();
    spin_stress_[k].setZero();
    if (!(b0.area[k] > 0.0)) continue;
    // G_k = sum_l u_l (x) b_kl(x_n) (+ the wall points' motion through the wall strips)
    Mat2 g = Mat2::Zero();
    for (std::int32_t e = b0.offset[k]; e < b0.offset[k + 1]; ++e) {
      g.noalias() +=
          u[std::size_t(b0.column[std::size_t(e)])] * b0.gradient[std::size_t(e)].transpose();
    }
    if (walls) {
      for (std::int32_t e = b0.wall_offset[k]; e < b0.wall_offset[k + 1]; ++e) {
        g.noalias() += wall_increment_[std::size_t(b0.wall_column[std::size_t(e)])] *
                       b0.wall_gradient[std::size_t(e)].transpose();
      }
    }
    Mat3 l = Mat3::Zero();
    l.topLeftCorner<2, 2>() = g;
    // Axisymmetric: the smoothed hoop strain sum_l u_r,l h_kl(x_n), linear in u on x_n as G_k
    // is (a ring's circumference grows with its radius; it spins nothing)
    if (ring) l(2, 2) = smoothed_hoop_rate(b0, u, k);
    const Mat3 d_strain = sym(l);
    const Mat3 d_spin = skew(l);
    const auto m = std::size_t(start_.material[k]);
    const constitutive::Model& model = *models_[m];
    const std::span<double> internal(internal_.data() + k * width,
                                     model.internal_variables().size());
    // The objective update of every method (constitutive/objective.hpp): rotate, then integrate.
    Mat3 rotated = start_.stress[k];
    if (d_spin.squaredNorm() > 0.0) {
      const Mat3 r = constitutive::rotation_increment(d_spin);
      rotated = r * rotated * r.transpose();
    }
    const constitutive::ElasticModuli moduli = model.moduli(rotated, internal);
    Mat3 s = rotated;
    Mat6 d;
    model.integrate_with_tangent(d_strain, s, internal, d);
    model.correct(s, internal);
    stress_[k] = s;
    strain_increment_[k] = d_strain;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) material_tangent_[k](i, j) = d(kComponent[i], kComponent[j]);
    }
    // d(R sigma R^T)/dW_12 = (Omega sigma_r - sigma_r Omega) / (1 + W_12^2 / 4) for the
    // Hughes-Winget (Cayley) rotation, Omega = [[0, 1], [-1, 0]]: in Voigt
    // [2 s_xy, -2 s_xy, 0, s_yy - s_xx] (notes: sigma_bar), carried through the return.
    const double w = d_spin(0, 1);
    Mat3 dsigma = Mat3::Zero();
    dsigma(0, 0) = 2.0 * rotated(0, 1);
    dsigma(1, 1) = -2.0 * rotated(0, 1);
    dsigma(0, 1) = dsigma(1, 0) = rotated(1, 1) - rotated(0, 0);
    dsigma(0, 2) = dsigma(2, 0) = rotated(1, 2);
    dsigma(1, 2) = dsigma(2, 1) = -rotated(0, 2);
    spin_stress_[k] = through_return(d, moduli, dsigma) / (1.0 + 0.25 * w * w);
  }
}

bool IncrementOperator::evaluate(const std::vector<Vec2>& u) {
  const std::size_t n = start_.size();
  position_.resize(n);
  for (std::size_t i = 0; i < n; ++i) position_[i] = start_.position[i] + u[i];
  // Axisymmetric: an iterate that puts a node on or across the axis has no ring there (the
  // cells' refill would throw); a failed evaluation lets the line search shorten the step, or
  // the increment be cut, as for a non-finite stress
  if (discretisation_.axisymmetric()) {
    for (const Vec2& x : position_) {
      if (!(x.x() > 0.0)) return false;
    }
  }
  // The strips' wall points: on a no-slip wall they follow the wall; on a free-slip wall they
  // move with their nodes.
  WallStrips& strips = discretisation_.wall_strips();
  for (std::size_t e = 0; e < strips.edges.size() && e < start_strips_.size(); ++e) {
    WallEdge& edge = strips.edges[e];
    const WallEdge& start = start_strips_[e];
    if (edge.free_slip) {
      edge.a_wall = start.a_wall + u[std::size_t(edge.a)];
      edge.b_wall = start.b_wall + u[std::size_t(edge.b)];
    } else {
      edge.a_wall = start.a_wall + wall_increment_[2 * e];
      edge.b_wall = start.b_wall + wall_increment_[2 * e + 1];
    }
  }
  Timers& timers = *timers_;
  {
    ScopedTimer t(timers, Phase::mesh);
    discretisation_.refill(position_);
  }
  {
    ScopedTimer t(timers, Phase::constitutive);
    update_stresses(u);
  }
  for (const Mat3& s : stress_) {
    if (!s.allFinite()) return false;
  }
  ScopedTimer t(timers, Phase::assembly);
  // Zhang 2018 slides, iSPFEM: F_int = sum_k B_L^(k)T sigma_k A^(k) on the current configuration
  internal_forces(discretisation_.cells(), stress_, internal_force_);
  if (!discretisation_.mesh().triangles.empty()) {
    for (Stabilisation& w : stabilisation_) {
      if (!(w.coefficient > 0.0)) continue;
      // spfem/stiffness_stabilisation.hpp: the force -dW/dx resists like an internal force
      stiffness_stabilisation_forces(discretisation_.mesh().triangles,
                                     discretisation_.cells().node_triangles, w.reference, position_,
                                     w.modulus, w.coefficient, w.scratch, w.force);
      for (std::size_t i = 0; i < n; ++i) internal_force_[i] -= w.force[i];
    }
  }
  return true;
}

void IncrementOperator::assemble_tangent(const DofMap& dofs, const std::vector<double>& diagonal) {
  ScopedTimer timer(*timers_, Phase::assembly);
  const std::size_t n = start_.size();
  // The geometric part of rows with layer or wall-strip terms (their weights are not A_e / 3
  // and depend on edge lengths and turns), and of every axisymmetric row (its hoop row's
  // triangle centroids): by central differences of the row's own terms
  const bool ring = !discretisation_.cells().ring.empty();
  row_derivative_.resize(n);
  hoop_derivative_.resize(n);
  const double h = 1e-6 * discretisation_.spacing();
  for (std::size_t k = 0; k < n; ++k) {
    row_derivative_[k].clear();
    hoop_derivative_[k].clear();
    if (start_cells_.area[k] > 0.0 && (ring || discretisation_.has_layer_terms(k))) {
      discretisation_.row_derivative(position_, k, h, row_derivative_[k],
                                     ring ? &hoop_derivative_[k] : nullptr);
    }
  }
  const SmoothingCells& cells = discretisation_.cells();
  const SmoothingCells& b0 = start_cells_;
  const std::vector<Triangle>& triangles = discretisation_.mesh().triangles;
  const int n_threads = n > kParallelMin ? omp_get_max_threads() : 1;
  // The rows' structure is fixed within the increment (refill keeps it): one pattern
  if (!blocks_.built()) blocks_.build(b0, n_threads);
  blocks_.zero();

#pragma omp parallel num_threads(n_threads)
  {
    Mat2* out = blocks_.blocks(omp_get_thread_num());
    std::vector<Eigen::Matrix<double, 4, 2>> q;
    std::vector<double> hessian;
    const bool meshed = !discretisation_.mesh().triangles.empty();
#pragma omp for schedule(static)
    for (std::size_t k = 0; k < n; ++k) {
      if (!(b0.area[k] > 0.0)) continue;
      const std::int32_t begin = cells.offset[k];
      const std::int32_t length = cells.offset[k + 1] - begin;
      // dF_l/du_m for l = column[begin + i], m = column[begin + j]: block pair[i * length + j]
      const std::int32_t* pair = blocks_.row_pairs(k);
      // Node k's own entry of its row (the hoop terms sit there), -1 in plane strain
      std::int32_t self =
          ring ? find_in_row(&cells.column[std::size_t(begin)], length, std::int32_t(k)) : -1;
      if (self == length) self = -1;
      // Material and spin: V_k B_l^T [D_k B_m^0 + sigma_bar_k B_S,m^0] (the hoop rows h_km at
      // x_n on the right, at x on the left: header)
      const auto hoop_at = [&](const SmoothingCells& c, std::int32_t entry) {
        return ring ? c.hoop[std::size_t(entry)] : 0.0;
      };
      q.resize(std::size_t(length));
      for (std::int32_t j = 0; j < length; ++j) {
        const Vec2& b = b0.gradient[std::size_t(begin + j)];
        Eigen::Matrix<double, 1, 2> spin;  // B_S = 1/2 [b_y, -b_x]
        spin << 0.5 * b.y(), -0.5 * b.x();
        q[std::size_t(j)] = material_tangent_[k] * strain_operator(b, hoop_at(b0, begin + j)) +
                            spin_stress_[k] * spin;
      }
      const double area = cells.area[k];
      const double volume = cell_volume(cells, k);
      for (std::int32_t i = 0; i < length; ++i) {
        const Eigen::Matrix<double, 2, 4> left =
            volume *
            strain_operator(cells.gradient[std::size_t(begin + i)], hoop_at(cells, begin + i))
                .transpose();
        for (std::int32_t j = 0; j < length; ++j) {
          out[pair[i * length + j]].noalias() += left * q[std::size_t(j)];
        }
      }
      const Mat2 sigma = stress_[k].topLeftCorner<2, 2>();
      if (self >= 0) {
        constexpr double two_pi = 2.0 * std::numbers::pi;
        // Ring: dV_k/dx_k = 2 pi A_k on sigma_k b_kl + sigma_tt,k h_kl e_x, column (k, x)
        for (std::int32_t i = 0; i < length; ++i) {
          Vec2 f = sigma * cells.gradient[std::size_t(begin + i)];
          f.x() += stress_[k](2, 2) * cells.hoop[std::size_t(begin + i)];
          out[pair[i * length + self]].col(0) += two_pi * area * f;
        }
        // Hoop geometric: ring_k sigma_tt,k d(A_k h_kl)/dx_m on row (l, x)
        const double hoop_force = cells.ring[k] * stress_[k](2, 2);
        const std::vector<Vec2>& dh = hoop_derivative_[k];
        for (std::int32_t i = 0; i < length * length; ++i) {
          out[pair[i]].row(0) += hoop_force * dh[std::size_t(i)].transpose();
        }
      }
      for (const Stabilisation& w : stabilisation_) {
        if (!(w.coefficient > 0.0) || !meshed) continue;
        // d^2 W / dx^2 of node k's stabilisation terms (exact: W is quadratic in x)
        stiffness_stabilisation_hessian(triangles, cells.node_triangles, w.scratch, k,
                                        &cells.column[std::size_t(begin)], length, hessian);
        for (std::int32_t i = 0; i < length * length; ++i) {
          out[pair[i]].diagonal().array() += hessian[std::size_t(i)];
        }
      }
      // Geometric: ring_k sigma_k d(A_k b_kl)/du_m (ring_k = 1 in plane strain)
      const Mat2 ring_sigma = ring ? Mat2(cells.ring[k] * sigma) : sigma;
      if (!row_derivative_.empty() && !row_derivative_[k].empty()) {
        const std::vector<Vec2>& d = row_derivative_[k];
        for (std::int32_t i = 0; i < length * length; ++i) {
          Mat2& block = out[pair[i]];
          block.col(0) += ring_sigma * d[std::size_t(i * 2)];
          block.col(1) += ring_sigma * d[std::size_t(i * 2 + 1)];
        }
        continue;
      }
      // the element gradients of the triangles that make up row k, weighted as there:
      // d(w grad N_I) = w (tr G_e grad N_I - G_e^T grad N_I) for w = A_e / 3 (notes)
      for (std::int32_t r = cells.node_triangles.offset[k]; r < cells.node_triangles.offset[k + 1];
           ++r) {
        const auto e = std::size_t(cells.node_triangles.triangle[std::size_t(r)]);
        const TriangleTerms& terms = cells.triangle_terms[e];
        if (terms.area == 0.0) continue;
        const double w = cells.triangle_weight[std::size_t(r)];
        const std::array<std::int32_t, 3>& corner = cells.corner_entry[std::size_t(r)];
        std::array<Vec2, 3> grad;
        std::array<Vec2, 3> sg;
        for (int c = 0; c < 3; ++c) {
          grad[std::size_t(c)] = terms.weighted_gradient[std::size_t(c)] * (3.0 / terms.area);
          sg[std::size_t(c)] = ring_sigma * grad[std::size_t(c)];
        }
        for (int i = 0; i < 3; ++i) {
          for (int j = 0; j < 3; ++j) {
            out[pair[(corner[std::size_t(i)] - begin) * length + corner[std::size_t(j)] - begin]]
                .noalias() += w * (sg[std::size_t(i)] * grad[std::size_t(j)].transpose() -
                                   sg[std::size_t(j)] * grad[std::size_t(i)].transpose());
          }
        }
      }
    }
  }
  if (!diagonal.empty()) blocks_.add_to_diagonal(diagonal);
  blocks_.write_free_dofs(dofs, tangent_);
}

}  // namespace duet::spfem
