#include "common/energy_budget.hpp"

#include <algorithm>
#include <stdexcept>

#include "common/geometry.hpp"
#include "common/kinetic_energy.hpp"

namespace duet {

EnergyBudget::EnergyBudget(const Scene& scene, const Particles& particles, double initial_elastic)
    : scene_(scene),
      initial_position_(particles.position),
      loaded_(loaded_particles(scene, particles)),
      initial_kinetic_(kinetic_energy(particles)),
      initial_elastic_(initial_elastic) {
  for (const Wall& w : scene.walls) {
    if (w.radial) {
      incomplete_ = "wall '" + w.name + "' moves radially: its work is not computed";
      break;
    }
  }
  double mass = 0.0;
  for (double m : particles.mass) mass += m;
  const double length = (scene.domain.max - scene.domain.min).norm();
  const double speed = length / scene.time.end_time;
  floor_ = 1e-6 * mass * speed * speed;
  boundary_power_ = boundary_power(0.0, {});
  load_power_ = load_power(0.0, particles);
}

double EnergyBudget::boundary_power(double time, const std::vector<Reaction>& reactions) const {
  // The soil's force on a boundary is R; the boundary's force on the soil, -R, moves with the
  // boundary's velocity.
  double p = 0.0;
  for (const Reaction& r : reactions) {
    const Schedule* velocity = nullptr;
    for (const Wall& w : scene_.walls) {
      if (w.name == r.name && !w.radial) velocity = &w.velocity;
    }
    for (const RigidBody& rb : scene_.rigid_bodies) {
      if (rb.name == r.name) velocity = &rb.velocity;
    }
    if (velocity) p -= r.force.dot(schedule_value(*velocity, time));
  }
  return p;
}

double EnergyBudget::load_power(double time, const Particles& particles) const {
  double p = 0.0;
  for (std::size_t l = 0; l < scene_.loads.size(); ++l) {
    const std::vector<std::size_t>& carriers = loaded_[l];
    if (carriers.empty()) continue;
    Vec2 velocity_sum = Vec2::Zero();
    for (std::size_t i : carriers) velocity_sum += particles.velocity[i];
    p += schedule_value(scene_.loads[l].force, time).dot(velocity_sum) /
         static_cast<double>(carriers.size());
  }
  return p;
}

void EnergyBudget::record(double time, const Particles& particles,
                          const std::vector<Reaction>& reactions) {
  double g = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    // A node added during the run (espfem's spfem.wall_node_gap) carries its parents' mean
    // displacement, and the mass it took from them: the work stays the same sum.
    const Vec2 moved = i < initial_position_.size()
                           ? Vec2(particles.position[i] - initial_position_[i])
                           : particles.displacement[i];
    g += particles.mass[i] * scene_.gravity.dot(moved);
  }
  gravity_work_ = g;
  const double dt = time - time_;
  const double pb = boundary_power(time, reactions);
  const double pl = load_power(time, particles);
  boundary_work_ += 0.5 * dt * (boundary_power_ + pb);
  load_work_ += 0.5 * dt * (load_power_ + pl);
  boundary_power_ = pb;
  load_power_ = pl;
  time_ = time;
}

void EnergyBudget::observe(double kinetic) {
  const double ratio = kinetic / std::max(input(), floor_);
  if (ratio > peak_ratio_) {
    peak_ratio_ = ratio;
    peak_ratio_time_ = time_;
  }
}

Json EnergyBudget::to_json() const {
  Json j = Json::object();
  j["input"] = input();
  j["initial_kinetic"] = initial_kinetic_;
  j["initial_elastic"] = initial_elastic_;
  j["gravity_work"] = gravity_work_;
  j["boundary_work"] = boundary_work_;
  j["load_work"] = load_work_;
  j["floor"] = floor_;
  j["kinetic_over_input_max"] = peak_ratio_;
  j["kinetic_over_input_max_time"] = peak_ratio_time_;
  j["incomplete"] = incomplete_ ? Json(*incomplete_) : Json();
  return j;
}

}  // namespace duet

namespace duet {

void EnergyBudget::save_state(StateBag& state) const {
  put(state, "energy_budget",
      std::vector<double>{initial_kinetic_, initial_elastic_, gravity_work_, boundary_work_,
                          load_work_, floor_, time_, boundary_power_, load_power_, peak_ratio_,
                          peak_ratio_time_});
}

void EnergyBudget::restore_state(const StateBag& state) {
  const std::vector<double>& v = entry(state, "energy_budget");
  if (v.size() != 11) throw std::runtime_error("the saved state's energy_budget has another size");
  initial_kinetic_ = v[0];
  initial_elastic_ = v[1];
  gravity_work_ = v[2];
  boundary_work_ = v[3];
  load_work_ = v[4];
  floor_ = v[5];
  time_ = v[6];
  boundary_power_ = v[7];
  load_power_ = v[8];
  peak_ratio_ = v[9];
  peak_ratio_time_ = v[10];
}

}  // namespace duet
