#pragma once
// The element-test demonstration (`duet demo` until a solver is registered): every built-in soil
// model, with its registered example parameters, through a drained triaxial test from -100 kPa to
// -10 % axial strain and an oedometer test to -5 %; a table of the key numbers on stdout and in
// OUT/element_demo.md, and element.csv / element.json / element.png per model and test under
// OUT/<model>-<test>/.

#include <string>

namespace duet {

/// Runs the demo; returns the exit status: 0 when every test completed, 3 when one failed
/// numerically, 2 when a model's example parameters were refused (the table says which).
int run_element_demo(const std::string& out_dir);

}  // namespace duet
