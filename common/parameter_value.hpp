#pragma once
// A model parameter as a user gives it: a number or a word. Shared by the scene model (common)
// and the constitutive library, which reads it with ranges and units.

#include <string>
#include <variant>

namespace duet {

using ParameterValue = std::variant<double, std::string>;

}  // namespace duet
