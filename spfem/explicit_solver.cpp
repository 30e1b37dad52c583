#include "spfem/explicit_solver.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <stdexcept>
#include <string>

#include "common/input_error.hpp"
#include "common/solver.hpp"
#include "constitutive/objective.hpp"
#include "constitutive/scene_models.hpp"
#include "spfem/wall_node_insertion.hpp"

namespace duet::spfem {

namespace {

// Below this many nodes (or triangles) a loop runs on one thread: a parallel region costs more
// than the work, and far more when the cores are shared.
constexpr std::size_t kParallelMin = 2048;

Mat3 embed(const Mat2& a) {
  Mat3 b = Mat3::Zero();
  b.topLeftCorner<2, 2>() = a;
  return b;
}

Mat2 sym2(const Mat2& a) {
  return 0.5 * (a + a.transpose());
}

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Gradients of the linear shape functions of a triangle (counter-clockwise) and its area.
std::array<Vec2, 3> shape_gradients(const Vec2& x0, const Vec2& x1, const Vec2& x2, double& area) {
  const double twice = cross(x1 - x0, x2 - x0);
  area = 0.5 * twice;
  // grad N_i = (y_j - y_k, x_k - x_j) / (2 A) for (i, j, k) cyclic
  return {Vec2(x1.y() - x2.y(), x2.x() - x1.x()) / twice,
          Vec2(x2.y() - x0.y(), x0.x() - x2.x()) / twice,
          Vec2(x0.y() - x1.y(), x1.x() - x0.x()) / twice};
}

/// M / |sigma| (1/strain) for a model whose tangent bound M scales with the stress (the
/// hypoplastic one, homogeneous of degree 1: at -p I M = 689 p for the sand collapse), 0 for a
/// model that gives no bound (elasticity, Drucker-Prager: their stiffness does not grow with
/// the stress). A strain increment |D| dt changes the stress by up to M |D| dt.
double stiffening(const constitutive::ElasticModuli& e, const Mat3& stress) {
  const double size = stress.norm();
  return e.tangent_bound > 0.0 && size > 0.0 ? e.tangent_bound / size : 0.0;
}

}  // namespace

ExplicitSolver::ExplicitSolver(EspfemSetup setup)
    : setup_(std::move(setup)),
      discretisation_(setup_.options, setup_.spacing, setup_.boundaries, setup_.axisymmetric) {
  if (setup_.axisymmetric && setup_.options.stiffness_stabilisation > 0.0) {
    throw InputError(
        "spfem.stiffness_stabilisation: its energy is per metre of a plane mesh; an axisymmetric "
        "scene runs without it");
  }
  const duet::SpfemOptions& o = setup_.options;
  if (!(o.time_step_safety > 0.0)) throw InputError("spfem.time_step_safety must be > 0");
  if (!(o.stiffness_stabilisation >= 0.0)) {
    throw InputError("spfem.stiffness_stabilisation must be >= 0");
  }
}

void ExplicitSolver::initialise(Particles& particles) {
  const std::size_t n = particles.size();
  n_internal_.clear();
  for (const auto& model : setup_.models) n_internal_.push_back(model->internal_variables().size());
  for (std::size_t i = 0; i < n; ++i) {
    const int m = particles.material[i];
    if (m < 0 || static_cast<std::size_t>(m) >= setup_.models.size()) {
      throw std::invalid_argument("espfem: particle without a material model");
    }
    if (n_internal_[static_cast<std::size_t>(m)] > particles.internal.width) {
      throw std::invalid_argument("espfem: internal variable block narrower than the model needs");
    }
  }
  discretisation_.initialise(particles.position);
  boundary_force_.assign(setup_.boundaries.size(), Vec2::Zero());
  velocity_gradient_.assign(n, Mat2::Zero());
  wave_speed_.assign(n, 0.0);
  block_modulus_.assign(n, 0.0);
  stiffening_.assign(n, 0.0);
  internal_force_.assign(n, Vec2::Zero());
  stabilisation_force_.assign(n, Vec2::Zero());
  stiffness_force_.assign(n, Vec2::Zero());
  reference_position_.assign(n, Vec2::Zero());
  stiffness_energy_ = 0.0;
  external_force_.assign(n, Vec2::Zero());
  scratch_stress_.assign(n, Mat3::Zero());
  scratch_force_.assign(n, Vec2::Zero());
  counters_ = EspfemCounters{};
  energy_reference_set_ = false;
  timers_.reset();
  // Wave speeds of the initial state, for the first time step.
  for (std::size_t i = 0; i < n; ++i) {
    const auto m = static_cast<std::size_t>(particles.material[i]);
    const constitutive::ElasticModuli e = setup_.models[m]->moduli(
        particles.stress[i], std::span<const double>(particles.internal.of(i), n_internal_[m]));
    wave_speed_[i] = std::sqrt(std::max(e.bulk + 4.0 * e.shear / 3.0, 0.0) / particles.density[i]);
    block_modulus_[i] = block_modulus(e);
    stiffening_[i] = stiffening(e, particles.stress[i]);
  }
}

void ExplicitSolver::use_models(std::vector<std::unique_ptr<constitutive::Model>> models) {
  constitutive::replace_models(setup_.models, std::move(models), "espfem");
}

double ExplicitSolver::time_step(const Particles& particles) {
  double dt = setup_.options.time_step == SpfemTimeStep::cell_size
                  ? cell_size_time_step(particles)
                  : gershgorin_time_step(particles);
  // The bulk viscosity damps the highest mode, which shortens the stable step
  dt *= bulk_viscosity_step_factor(setup_.options.bulk_viscosity);
  // Stress increment: a hypoplastic node's stiffness grows with its stress, so a node near the
  // apex (little stress, much strain rate: a free-falling grain hitting the pile) stiffens by
  // up to exp(M / |sigma| |D| dt) within one step, far beyond what the start-of-step stiffness
  // of either rule allowed for. Bound the relative stress increment, M / |sigma| |D| dt <= limit,
  // at the nodes being loaded (stress power sigma : D > 0); one unloading or pulled apart (a
  // surface node leaving the body, whose strain rate is largest) only softens.
  const double limit = setup_.options.stress_increment_limit;
  if (!(limit > 0.0)) return dt;
  const std::size_t n = velocity_gradient_.size();
  double rate = 0.0;
#pragma omp parallel for schedule(static) reduction(max : rate) if (n > kParallelMin)
  for (std::size_t k = 0; k < n; ++k) {
    if (stiffening_[k] > 0.0 && cells().area[k] > 0.0) {
      const Mat2 d = sym2(velocity_gradient_[k]);
      const Mat2 sigma = particles.stress[k].topLeftCorner<2, 2>();
      if ((sigma.array() * d.array()).sum() > 0.0) rate = std::max(rate, stiffening_[k] * d.norm());
    }
  }
  if (rate * dt > limit) {
    ++counters_.stress_limited_steps;
    return limit / rate;
  }
  return dt;
}

double ExplicitSolver::gershgorin_time_step(const Particles& particles) {
  // `gershgorin`. Central
  // difference is stable for dt <= 2 / omega_max (undamped), with omega_max^2 the largest
  // eigenvalue of M^-1 K, K = sum_k A_k B_k^T D_k B_k the smoothed stiffness and M the lumped
  // (particle) masses. Its 2x2 block (l, m) is sum_k A_k [lambda b_kl b_km^T + G (b_kl . b_km) I
  // + G b_km b_kl^T], of norm <= sum_k A_k (|lambda| + 2 G)_k |b_kl| |b_km|, so the block
  // Gershgorin theorem (Feingold & Varga 1962) bounds, with no eigen-solve,
  //   omega_max^2 <= max_l (1 / m_l) sum_k A_k M_k |b_kl| sum_m |b_km|,  M_k = |lambda| + 2 G
  // (= K + 4G/3 for lambda >= 0). It follows the node's true mass and the stiffness its cells
  // carry: a surface node held by an alpha-shape sliver has a tiny cell A_k but the full particle
  // mass, and sqrt(A_k) / c (the former l_min / c) cut dt by the ratio of the two. Two O(nnz)
  // passes, no allocation once sized: w_k = A_k M_k sum_m |b_km| per cell, then each row l
  // gathers w_k |b_kl| through the transpose map.
  // Axisymmetric: V_k = 2 pi r_k A_k for A_k, and node k's strain has the hoop row h_km
  // besides, so |B_km| <= |b_km| + |h_km| takes the place of |b_km|.
  const std::size_t n = cells().area.size();
  const bool hoop = !cells().hoop.empty();
  cell_weight_.resize(n);
  gradient_norm_.resize(cells().gradient.size());
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::size_t k = 0; k < n; ++k) {
    double row_sum = 0.0;
    for (std::int32_t e = cells().offset[k]; e < cells().offset[k + 1]; ++e) {
      const auto entry = static_cast<std::size_t>(e);
      double norm = cells().gradient[entry].norm();  // |b_km|
      if (hoop) norm += std::abs(cells().hoop[entry]);
      gradient_norm_[entry] = norm;
      row_sum += norm;
    }
    cell_weight_[k] = cell_volume(cells(), k) * block_modulus_[k] * row_sum;
  }
  double omega_squared = 0.0;
#pragma omp parallel for schedule(static) reduction(max : omega_squared) if (n > kParallelMin)
  for (std::size_t l = 0; l < n; ++l) {
    double bound = 0.0;
    // Row l lists every k whose cell sees node l; b_kl is entry (k, l), read through transpose.
    for (std::int32_t e = cells().offset[l]; e < cells().offset[l + 1]; ++e) {
      const auto k = static_cast<std::size_t>(cells().column[static_cast<std::size_t>(e)]);
      const auto kl = static_cast<std::size_t>(cells().transpose[static_cast<std::size_t>(e)]);
      bound += cell_weight_[k] * gradient_norm_[kl];
    }
    omega_squared = std::max(omega_squared, std::abs(bound) / particles.mass[l]);
  }
  if (!(omega_squared > 0.0)) {
    // No mesh (every node isolated): the former estimate with l = dp.
    double c_max = 0.0;
    for (const double c : wave_speed_) c_max = std::max(c_max, c);
    if (!(c_max > 0.0)) {
      throw NumericalFailure("espfem: no positive wave speed (every node has zero stiffness)");
    }
    return setup_.options.time_step_safety * setup_.spacing / c_max;
  }
  // dt = safety x the central-difference limit 2 / omega_max (safety 1: stable for linear
  // elasticity without damping, guaranteed by the bound)
  return setup_.options.time_step_safety * 2.0 / std::sqrt(omega_squared);
}

double ExplicitSolver::cell_size_time_step(const Particles& particles) const {
  // Zhang 2018 slides, Algorithm 1 step 3, computes dt from the node volumes: l_min is the smallest
  // smoothing-cell size sqrt(A_k) over the nodes in the mesh, c_max the largest wave speed
  // sqrt(M / rho) over all nodes, M the bound on the tangent that `gershgorin` uses: K + 4G/3 for
  // elasticity and Drucker-Prager; the hypoplastic tangent_bound, whose L + N exceeds L's
  // isotropic K + 4G/3 by 2.2 at K0 (the oedometer at dp = 2.5 cm with that P-wave speed lost its
  // stress from 1.4 % strain at safety 0.5). (The smallest triangle altitude fell 100x on thin
  // alpha-shape surface triangles, which a node's cell shares with its neighbours; a node held by
  // slivers alone still has a tiny cell and still cuts dt: `gershgorin` does not.) Global minimum
  // against global maximum: conservative where the stiffness varies, which `gershgorin` follows
  // node by node.
  const std::size_t n = cells().area.size();
  double smallest_area = std::numeric_limits<double>::infinity();
#pragma omp parallel for schedule(static) reduction(min : smallest_area) if (n > kParallelMin)
  for (std::size_t k = 0; k < n; ++k) {
    if (cells().area[k] > 0.0) smallest_area = std::min(smallest_area, cells().area[k]);
  }
  const double l_min =
      std::isfinite(smallest_area) ? std::sqrt(smallest_area) : setup_.spacing;  // no mesh: dp
  double c_max = 0.0;
#pragma omp parallel for schedule(static) reduction(max : c_max) if (n > kParallelMin)
  for (std::size_t k = 0; k < n; ++k) {
    c_max = std::max(c_max, std::sqrt(block_modulus_[k] / particles.density[k]));
  }
  if (!(c_max > 0.0)) {
    throw NumericalFailure("espfem: no positive wave speed (every node has zero stiffness)");
  }
  // Zhang 2018 slides, explicit cycle step 3: dt_cr = alpha l_min / c
  return setup_.options.time_step_safety * l_min / c_max;
}

void ExplicitSolver::update_stress(Particles& particles, double dt) {
  const std::size_t n = particles.size();
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    const auto m = static_cast<std::size_t>(particles.material[i]);
    const constitutive::Model& model = *setup_.models[m];
    const std::span<double> internal(particles.internal.of(i), n_internal_[m]);
    if (cells().area[i] > 0.0) {
      const Mat3 l = full_velocity_gradient(particles, i);
      const Mat3 d = sym(l);
      // Zhang 2018 slides, explicit cycle step 5: sigma_dot = H(eps_dot, kappa), Jaumann rate
      constitutive::update_stress(model, d * dt, skew(l) * dt, particles.stress[i], internal);
      model.correct(particles.stress[i], internal);
      particles.strain[i] += d * dt;
      particles.volume[i] *= std::exp(d.trace() * dt);
      particles.density[i] = particles.mass[i] / particles.volume[i];
    }
    const constitutive::ElasticModuli e = model.moduli(particles.stress[i], internal);
    // P-wave speed c = sqrt((K + 4 G / 3) / rho)
    wave_speed_[i] = std::sqrt(std::max(e.bulk + 4.0 * e.shear / 3.0, 0.0) / particles.density[i]);
    block_modulus_[i] = block_modulus(e);
    stiffening_[i] = stiffening(e, particles.stress[i]);
  }
}

void ExplicitSolver::add_stabilisation(const Particles& particles) {
  // Stabilised nodal integration, viscous form: per triangle e the exact strain rate d_e of the
  // linear element minus the mean of its nodes' smoothed strain rates, sigma_s,e = s rho c l_e
  // (d_e - mean_k d_k). The force is the work conjugate of (d_e - mean_k d_k):
  //   F_l = sum_e A_e sigma_s,e grad N_l^e - sum_k S_k b_kl,  S_k = sum_{e at k} A_e sigma_s,e / 3,
  // so its power is sum_e A_e s rho c l_e |d_e - mean d_k|^2 >= 0, and it vanishes for every
  // linear velocity field (patch test).
  const double s = setup_.options.stabilisation;
  const std::vector<Vec2>& x = particles.position;
  const std::vector<Vec2>& v = particles.velocity;
  const std::size_t n_triangles = mesh().triangles.size();
  triangle_stress_.resize(n_triangles);
  triangle_grad_.resize(n_triangles);
  std::vector<double>& area = triangle_area_;
  area.resize(n_triangles);
#pragma omp parallel for schedule(static) if (n_triangles > kParallelMin)
  for (std::size_t e = 0; e < n_triangles; ++e) {
    const Triangle& t = mesh().triangles[e];
    const auto a = static_cast<std::size_t>(t[0]);
    const auto b = static_cast<std::size_t>(t[1]);
    const auto c = static_cast<std::size_t>(t[2]);
    triangle_grad_[e] = shape_gradients(x[a], x[b], x[c], area[e]);
    Mat2 l_e = Mat2::Zero();
    for (int k = 0; k < 3; ++k) {
      l_e += v[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])] *
             triangle_grad_[e][static_cast<std::size_t>(k)].transpose();
    }
    const Mat2 mean_smoothed =
        sym2(velocity_gradient_[a] + velocity_gradient_[b] + velocity_gradient_[c]) / 3.0;
    const double rho = (particles.density[a] + particles.density[b] + particles.density[c]) / 3.0;
    const double speed = (wave_speed_[a] + wave_speed_[b] + wave_speed_[c]) / 3.0;
    const double length = std::sqrt(2.0 * std::abs(area[e]));
    triangle_stress_[e] = s * rho * speed * length * (sym2(l_e) - mean_smoothed);
    // Axisymmetric: the triangle's ring 2 pi r at its centroid weighs its power (Pappus); any
    // positive weight keeps the force zero on a linear velocity field
    if (!cells().ring.empty()) {
      triangle_stress_[e] *= 2.0 * std::numbers::pi * (x[a].x() + x[b].x() + x[c].x()) / 3.0;
    }
  }
  const std::size_t n = particles.size();
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::size_t l = 0; l < n; ++l) {
    Vec2 f = Vec2::Zero();
    Mat2 s_l = Mat2::Zero();
    for (std::int32_t r = cells().node_triangles.offset[l];
         r < cells().node_triangles.offset[l + 1]; ++r) {
      const auto e =
          static_cast<std::size_t>(cells().node_triangles.triangle[static_cast<std::size_t>(r)]);
      const Triangle& t = mesh().triangles[e];
      const std::size_t k = t[0] == static_cast<std::int32_t>(l)   ? 0
                            : t[1] == static_cast<std::int32_t>(l) ? 1
                                                                   : 2;
      f += area[e] * (triangle_stress_[e] * triangle_grad_[e][k]);
      s_l += area[e] / 3.0 * triangle_stress_[e];
    }
    stabilisation_force_[l] = f;
    scratch_stress_[l] =
        cells().area[l] > 0.0 ? embed(s_l / cell_volume(cells(), l)) : Mat3::Zero();
  }
  // sum_k S_k b_kl = sum_k V_k (S_k / V_k) b_kl: the smoothed internal-force operator (S_k has no
  // hoop component, so it adds no hoop force)
  internal_forces(cells(), scratch_stress_, scratch_force_);
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::size_t l = 0; l < n; ++l) stabilisation_force_[l] -= scratch_force_[l];
}

void ExplicitSolver::assemble_forces(const Particles& particles) {
  const double b1 = setup_.options.bulk_viscosity;
  if (b1 > 0.0) {
    // Linear bulk viscosity (Abaqus/Explicit's b1, LS-DYNA's): sigma + b1 rho c l tr(D) I, l =
    // sqrt(A_k). Its power b1 rho c l tr(D)^2 A_k >= 0; an isochoric flow (the undrained soil's
    // quasi-static one) has tr(D) = 0 and feels none of it, a volumetric ringing does.
    const std::size_t n = particles.size();
    viscous_stress_.resize(n);
#pragma omp parallel for schedule(static) if (n > kParallelMin)
    for (std::size_t k = 0; k < n; ++k) {
      viscous_stress_[k] = particles.stress[k];
      const double area = cells().area[k];
      if (area > 0.0) {
        const double eta = b1 * particles.density[k] * wave_speed_[k] * std::sqrt(area);
        const double p = eta * full_velocity_gradient(particles, k).trace();
        viscous_stress_[k](0, 0) += p;
        viscous_stress_[k](1, 1) += p;
        if (setup_.axisymmetric) viscous_stress_[k](2, 2) += p;  // the hoop force carries it
      }
    }
  }
  // Zhang 2018 slides, explicit cycle step 6: F_int = sum_k B_k^T sigma_k A_k
  internal_forces(cells(), b1 > 0.0 ? viscous_stress_ : particles.stress, internal_force_);
  if (setup_.options.stabilisation > 0.0 && !mesh().triangles.empty()) {
    add_stabilisation(particles);
  } else {
    std::fill(stabilisation_force_.begin(), stabilisation_force_.end(), Vec2::Zero());
  }
  stiffness_energy_ = 0.0;
  if (setup_.options.stiffness_stabilisation > 0.0 && !mesh().triangles.empty()) {
    // Stiffness stabilisation on the nodes' initial positions x - u (the displacement is
    // measured from the start of the run, after any gravity loading)
    const std::size_t n = particles.size();
#pragma omp parallel for schedule(static) if (n > kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
      reference_position_[i] = particles.position[i] - particles.displacement[i];
    }
    stiffness_energy_ = stiffness_stabilisation_forces(
        mesh().triangles, cells().node_triangles, reference_position_, particles.position,
        block_modulus_, setup_.options.stiffness_stabilisation, stiffness_scratch_,
        stiffness_force_);
    // stabilisation_force_ is subtracted in M a = ... - F_stab, stiffness_force_ = -dW/dx acts
#pragma omp parallel for schedule(static) if (n > kParallelMin)
    for (std::size_t i = 0; i < n; ++i) stabilisation_force_[i] -= stiffness_force_[i];
  }
}

void ExplicitSolver::integrate(Particles& particles, double time, double dt) {
  const duet::SpfemOptions& o = setup_.options;
  const std::size_t n = particles.size();
  const std::size_t n_boundaries = setup_.boundaries.size();
  discretisation_.place_boundaries(time, settling_);
  const std::vector<BoundaryGeometry>& geometry = discretisation_.geometry();
  const WallStrips& wall_strips = discretisation_.wall_strips();
  const double reach = 0.5 * setup_.spacing * (1.0 + 1e-6);
  const double depth = setup_.spacing;
  const double viscous = o.damping + damping_;
  const int n_threads = omp_get_max_threads();
  std::vector<Vec2> impulse(static_cast<std::size_t>(n_threads) * n_boundaries, Vec2::Zero());
  long n_contacts = 0;

#pragma omp parallel reduction(+ : n_contacts) if (n > kParallelMin)
  {
    std::vector<NodeContact> found;
    Vec2* my_impulse =
        impulse.data() + static_cast<std::size_t>(omp_get_thread_num()) * n_boundaries;
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const double m = particles.mass[i];
      const Vec2 v = particles.velocity[i];
      // Zhang 2018 slides, explicit cycle step 7: M a = F_ext - F_int (+ body force m g)
      Vec2 f = external_force_[i] + m * setup_.gravity - internal_force_[i] -
               stabilisation_force_[i] - viscous * m * v;
      if (o.local_damping > 0.0) {
        // Cundall local non-viscous damping: -alpha |F| sign(v), per component
        for (int c = 0; c < 2; ++c) {
          const double sign = v[c] > 0.0 ? 1.0 : (v[c] < 0.0 ? -1.0 : 0.0);
          f[c] -= o.local_damping * std::abs(f[c]) * sign;
        }
      }
      Vec2 v_new = v + dt * f / m;  // central difference: velocity first
      found.clear();
      for (std::size_t b = 0; b < n_boundaries; ++b) {
        find_node_contacts(geometry[b], setup_.boundaries[b].rigid_body,
                           static_cast<std::int32_t>(i), static_cast<std::int32_t>(b),
                           particles.position[i], reach, depth, found);
      }
      for (const NodeContact& c : found) {
        const NodeBoundary& b = setup_.boundaries[static_cast<std::size_t>(c.boundary)];
        if (held_by_wall_strip(wall_strips, c)) continue;  // its wall strip carries it
        const Vec2 dv = constrain_velocity(c, b.condition, b.friction, v_new);
        // Force of the soil on the boundary: m (a_free - a_constrained)
        my_impulse[c.boundary] -= m * dv / dt;
        if (c.distance < 0.0) {
          // Crossed: back onto the contact distance.
          const Vec2 back = (reach - c.distance) * c.normal;
          particles.position[i] += back;
          particles.displacement[i] += back;
        }
      }
      n_contacts += static_cast<long>(found.size());
      particles.velocity[i] = v_new;
      particles.position[i] += dt * v_new;  // then position
      particles.displacement[i] += dt * v_new;
    }
  }
  for (std::size_t b = 0; b < n_boundaries; ++b) {
    Vec2 f = Vec2::Zero();
    for (int t = 0; t < n_threads; ++t)
      f += impulse[static_cast<std::size_t>(t) * n_boundaries + b];
    boundary_force_[b] = f;
  }
  // Wall strips: the soil pushes each wall point with -F_w (force of the soil on the wall)
  add_wall_strip_reactions(wall_strips, discretisation_.cells(), particles.stress, boundary_force_);
  counters_.contacts_max = std::max(counters_.contacts_max, n_contacts);
}

void ExplicitSolver::insert_nodes(Particles& particles) {
  const std::vector<InsertedNode> added =
      insert_wall_nodes(setup_.boundaries, discretisation_.geometry(), setup_.spacing,
                        setup_.options.wall_node_gap, particles);
  if (added.empty()) return;
  counters_.inserted_nodes += static_cast<long>(added.size());
  const std::size_t n = particles.size();
  // The arrays the next step reads before it computes them anew (the time step reads the
  // stiffness of the last stress update): the parents' means; the rest are refilled.
  const auto mean = [](std::vector<double>& v, const InsertedNode& a) {
    v[static_cast<std::size_t>(a.node)] = 0.5 * (v[static_cast<std::size_t>(a.parents[0])] +
                                                 v[static_cast<std::size_t>(a.parents[1])]);
  };
  wave_speed_.resize(n, 0.0);
  block_modulus_.resize(n, 0.0);
  stiffening_.resize(n, 0.0);
  for (const InsertedNode& a : added) {
    mean(wave_speed_, a);
    mean(block_modulus_, a);
    mean(stiffening_, a);
  }
  velocity_gradient_.resize(n, Mat2::Zero());
  internal_force_.resize(n, Vec2::Zero());
  stabilisation_force_.resize(n, Vec2::Zero());
  stiffness_force_.resize(n, Vec2::Zero());
  reference_position_.resize(n, Vec2::Zero());
  external_force_.resize(n, Vec2::Zero());
  scratch_stress_.resize(n, Mat3::Zero());
  scratch_force_.resize(n, Vec2::Zero());
}

double ExplicitSolver::energy(const Particles& particles) const {
  double e = stiffness_energy_;
  const std::size_t n = particles.size();
#pragma omp parallel for schedule(static) reduction(+ : e) if (n > kParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    e += 0.5 * particles.mass[i] * particles.velocity[i].squaredNorm();
    if (i < cells().area.size()) {
      e += 0.5 * cell_volume(cells(), i) * contract(particles.stress[i], particles.strain[i]);
    }
  }
  return e;
}

double ExplicitSolver::step(Particles& particles, double time) {
  {
    ScopedTimer t(timers_, Phase::mesh);
    // The walls at t, for the wall strips of this step (integrate() reads the same geometry)
    discretisation_.place_boundaries(time, settling_);
    if (setup_.options.wall_node_gap > 0.0 && !settling_) insert_nodes(particles);
    discretisation_.update(particles.position);
  }
  double dt = 0.0;
  {
    ScopedTimer t(timers_, Phase::constitutive);
    // Zhang 2018 slides, explicit cycle step 4: smoothed strain (rate) of the nodes, before dt,
    // which the stress increment it gives also bounds
    smoothed_velocity_gradients(cells(), particles.velocity, velocity_gradient_);
    dt = time_step(particles);
    update_stress(particles, dt);
  }
  {
    ScopedTimer t(timers_, Phase::forces);
    assemble_forces(particles);
  }
  {
    ScopedTimer t(timers_, Phase::integration);
    integrate(particles, time, dt);
  }
  ScopedTimer checks(timers_, Phase::other);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (!particles.position[i].allFinite() || !particles.velocity[i].allFinite() ||
        !particles.stress[i].allFinite()) {
      throw NumericalFailure("non-finite node state after the explicit SPFEM update",
                             static_cast<long>(i));
    }
  }
  counters_.dt_min = counters_.steps == 0 ? dt : std::min(counters_.dt_min, dt);
  counters_.dt_max = std::max(counters_.dt_max, dt);
  ++counters_.steps;
  if (!settling_) {
    const double e = energy(particles);
    if (!energy_reference_set_) {
      counters_.energy_reference = e;
      energy_reference_set_ = true;
    } else if (counters_.energy_reference > 0.0) {
      counters_.energy_drift_max =
          std::max(counters_.energy_drift_max,
                   std::abs(e - counters_.energy_reference) / counters_.energy_reference);
    }
  }
  return dt;
}

void ExplicitSolver::settle(Particles& particles, double duration, double damping) {
  damping_ = damping;
  settling_ = true;
  double t = -duration;
  while (t < 0.0) t += step(particles, t);
  damping_ = 0.0;
  settling_ = false;
  particles.start_from_rest();
  energy_reference_set_ = false;
}

Json ExplicitSolver::diagnostics() const {
  const EspfemCounters& c = counters_;
  const MeshCounters& m = discretisation_.counters();
  Json j = Json::object();
  j["steps"] = c.steps;
  j["remeshes"] = m.remeshes;
  j["forced_remeshes"] = m.forced_remeshes;
  j["remesh"] = to_string(setup_.options.remesh);
  j["remesh_angle"] = setup_.options.remesh_angle;
  j["remesh_angle_fraction"] = setup_.options.remesh_angle_fraction;
  j["triangles"] = static_cast<long>(m.triangles);
  j["surface_nodes"] = static_cast<long>(m.surface_nodes);
  j["components"] = static_cast<long>(m.components);
  j["isolated_nodes_max"] = static_cast<long>(m.isolated_nodes_max);
  j["short_edge_triangles_max"] = static_cast<long>(m.short_edge_triangles_max);
  j["dt_min"] = c.dt_min;
  j["dt_max"] = c.dt_max;
  j["smallest_angle"] = m.smallest_angle;
  j["contacts_max"] = c.contacts_max;
  j["wall_strip_edges"] = static_cast<long>(discretisation_.wall_strips().edges.size());
  j["stabilisation"] = setup_.options.stabilisation;
  j["stiffness_stabilisation"] = setup_.options.stiffness_stabilisation;
  j["stiffness_stabilisation_energy"] = stiffness_energy_;
  j["stress_limited_steps"] = c.stress_limited_steps;
  j["bulk_viscosity"] = setup_.options.bulk_viscosity;
  j["wall_node_gap"] = setup_.options.wall_node_gap;
  j["inserted_nodes"] = c.inserted_nodes;
  j["energy_reference"] = c.energy_reference;
  j["energy_drift_max"] = c.energy_drift_max;
  const double steps = static_cast<double>(std::max(c.steps, 1L));
  j["mesh_seconds_per_step"] = timers_.seconds(Phase::mesh) / steps;
  const double total = timers_.total_seconds();
  j["node_steps_per_second"] =
      total > 0.0 ? static_cast<double>(velocity_gradient_.size()) * steps / total : 0.0;
  return j;
}

}  // namespace duet::spfem

namespace duet::spfem {

void ExplicitSolver::save_state(StateBag& state) const {
  const EspfemCounters& c = counters_;
  put(state, "solver.counters",
      std::vector<double>{double(c.steps), c.dt_min, c.dt_max, double(c.contacts_max),
                          c.energy_reference, c.energy_drift_max, double(c.stress_limited_steps),
                          energy_reference_set_ ? 1.0 : 0.0});
  put(state, "solver.boundary_force", boundary_force_);
  discretisation_.save_state(state, "solver.mesh_counters");
}

void ExplicitSolver::restore_state(const StateBag& state, std::size_t nodes) {
  const std::vector<double>& k = entry(state, "solver.counters");
  if (k.size() != 8) throw std::runtime_error("the saved state's solver.counters has another size");
  if (entry(state, "solver.boundary_force").size() != 2 * boundary_force_.size()) {
    throw std::runtime_error("the saved state's solver.boundary_force is not this scene's");
  }
  EspfemCounters& c = counters_;
  c.steps = static_cast<long>(k[0]);
  c.dt_min = k[1];
  c.dt_max = k[2];
  c.contacts_max = static_cast<long>(k[3]);
  c.energy_reference = k[4];
  c.energy_drift_max = k[5];
  c.stress_limited_steps = static_cast<long>(k[6]);
  energy_reference_set_ = k[7] != 0.0;
  get(state, "solver.boundary_force", boundary_force_);
  discretisation_.restore_state(state, "solver.mesh_counters", nodes);
}

}  // namespace duet::spfem
