#pragma once
// Particle state as a structure of arrays, readable by every method (SPFEM nodes are particles).
// SI units; tension positive; stress is a full 3x3 even in plane strain (sigma_zz kept).

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "common/tensor.hpp"

namespace duet {

/// The model internal variables of all particles: n_variables values per particle, row-major
/// (particle i's values are values[i * names.size() + k]). Names and meaning are declared by the
/// constitutive model of the particle's material; particles of different materials may use fewer.
struct InternalVariables {
  std::vector<std::string> names;  // union over the scene's models, in storage order
  std::vector<double> values;

  std::size_t n_variables() const { return names.size(); }
  double* of(std::size_t particle) { return values.data() + particle * names.size(); }
  const double* of(std::size_t particle) const { return values.data() + particle * names.size(); }
};

struct Particles {
  // Geometry and kinematics (plane, x horizontal, y vertical upward).
  std::vector<Vec2> position;      // m
  std::vector<Vec2> velocity;      // m/s
  std::vector<Vec2> displacement;  // m, from the initial position
  // Mass and volume (per unit thickness in plane strain).
  std::vector<double> mass;     // kg/m
  std::vector<double> volume;   // m^2
  std::vector<double> density;  // kg/m^3
  // Mechanics.
  std::vector<Mat3> stress;  // Pa, tension positive
  std::vector<Mat3> strain;  // accumulated (small-strain sum of increments), -
  // Which body and which material each particle came from (indices into the scene's lists).
  std::vector<std::int32_t> body;
  std::vector<std::int32_t> material;
  InternalVariables internal;

  std::size_t size() const { return position.size(); }
  /// Resize every array to n (new entries zeroed).
  void resize(std::size_t n);
};

}  // namespace duet
