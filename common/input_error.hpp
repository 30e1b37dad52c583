#pragma once
// Bad input (scene file, --set override, model parameters): refused before any work, exit status 2.

#include <stdexcept>
#include <string>

namespace duet {

/// Thrown for input the user must correct. The message names the file (or source), line when
/// known, key, the value and what was expected, e.g.
///   "material.sand.nu = 0.62: Poisson's ratio must lie in [0, 0.5)".
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace duet
