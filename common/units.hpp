#pragma once
// The units of a force and of an energy in a scene of a given formulation, for messages: per metre
// of thickness in plane strain, of the whole circumference in an axisymmetric scene.

#include "common/scene.hpp"

namespace duet {

inline const char* force_unit(Formulation f) {
  return f == Formulation::axisymmetric ? "N" : "N/m";
}

inline const char* energy_unit(Formulation f) {
  return f == Formulation::axisymmetric ? "J" : "J/m";
}

}  // namespace duet
