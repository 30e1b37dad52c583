#pragma once
// Particle state as a structure of arrays, readable by every method (SPFEM nodes are particles).
// SI units; tension positive; stress is a full 3x3 even in plane strain (sigma_zz kept).

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "common/tensor.hpp"

namespace duet {

/// The model internal variables of all particles. Each particle owns a block of `width` doubles;
/// the constitutive model of its material reads and writes the first entries of that block, in the
/// order the model declares them. `names` is the union over the scene's models (for output), and
/// slot[material][k] says where name k sits in a block of that material (-1: that model lacks it).
struct InternalVariables {
  std::vector<std::string> names;
  std::vector<std::vector<int>> slot;  // [material][name index] -> position in the block, or -1
  std::size_t width = 0;
  std::vector<double> values;  // n_particles * width

  std::size_t n_variables() const { return names.size(); }
  double* of(std::size_t particle) { return values.data() + particle * width; }
  const double* of(std::size_t particle) const { return values.data() + particle * width; }
  /// Value of variable `name_index` for `particle` of material `material`; NaN where that
  /// material's model has no such variable.
  double value(std::size_t particle, int material, std::size_t name_index) const {
    const int k = slot[static_cast<std::size_t>(material)][name_index];
    return k < 0 ? std::numeric_limits<double>::quiet_NaN() : of(particle)[k];
  }
  /// Index of `name` in names, or -1.
  int index_of(const std::string& name) const {
    for (std::size_t k = 0; k < names.size(); ++k) {
      if (names[k] == name) return static_cast<int>(k);
    }
    return -1;
  }
};

struct Particles {
  // Geometry and kinematics (plane, x horizontal, y vertical upward).
  std::vector<Vec2> position;      // m
  std::vector<Vec2> velocity;      // m/s
  std::vector<Vec2> displacement;  // m, from the initial position
  // Mass and volume: per metre of thickness in plane strain; of the ring about the axis in an
  // axisymmetric scene (Scene::formulation).
  std::vector<double> mass;     // kg/m (plane strain), kg (axisymmetric)
  std::vector<double> volume;   // m^2 (plane strain), m^3 (axisymmetric)
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
  /// Velocity, displacement and strain back to zero, stress and state kept: the start of a run
  /// after gravity loading (Peng 2015 section 5.3).
  void start_from_rest();
};

}  // namespace duet
