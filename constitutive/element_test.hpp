#pragma once
// Element tests: one material point, strain controlled, no particles. Drives any Model through
// the laboratory paths used to calibrate and check soil models (Peng 2015 sec 5.1 oedometer; the
// drained triaxial and simple shear tests of the simhypo-sand paper sec 4).
//
// Axes: axial = y (index 1), lateral = x (index 0), out-of-plane = z (index 2), shear = xy.
// Tension positive (compression negative) as everywhere in duet. The driver prescribes the
// co-rotational strain increment only (no spin): a small-strain element test, as laboratory
// element-test curves are read. Strains in the rows are the sums of the increments.

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "constitutive/model.hpp"

namespace duet::constitutive {

enum class ElementTestKind {
  oedometer,     // eps_xx = eps_zz = 0, axial strain prescribed; optional unloading
  triaxial,      // drained, axisymmetric: sigma_xx = sigma_zz = initial stress held
  simple_shear,  // gamma_xy prescribed, eps_xx = eps_zz = 0, sigma_yy = initial stress held
};

/// "oedometer", "triaxial", "simple-shear".
std::string element_test_name(ElementTestKind kind);
std::vector<std::string> element_test_names();
/// Throws InputError naming the known tests (with a did-you-mean) when `name` is unknown.
ElementTestKind parse_element_test_kind(const std::string& name);

struct ElementTest {
  ElementTestKind kind = ElementTestKind::triaxial;
  double initial_stress = -100e3;  // isotropic start, Pa (negative in compression)
  double strain = -0.1;  // final axial strain (simple shear: final engineering gamma_xy), signed
  int increments = 100;  // equal strain steps from 0 to `strain`
  std::optional<double> unload_to;  // oedometer only: reverse to this axial strain after loading
};

/// One row of element.csv: the state after an increment (the first row is the start).
struct ElementRow {
  double axial_strain = 0.0;         // eps_yy
  double lateral_strain = 0.0;       // eps_xx
  double volumetric_strain = 0.0;    // eps_xx + eps_yy + eps_zz (negative in compaction)
  double shear_strain = 0.0;         // engineering gamma_xy = 2 eps_xy
  double axial_stress = 0.0;         // sigma_yy, Pa
  double lateral_stress = 0.0;       // sigma_xx, Pa
  double out_of_plane_stress = 0.0;  // sigma_zz, Pa
  double shear_stress = 0.0;         // sigma_xy, Pa
  double p = 0.0;  // mean stress tr(sigma)/3, Pa, tension positive (negative in compression)
  double q = 0.0;  // von Mises equivalent stress sqrt(3 J2), Pa
  double void_ratio = 0.0;   // the model's `void_ratio` internal variable, NaN when it has none
  double corrections = 0.0;  // the model's `corrections` internal variable, 0 when it has none
};

/// Numerical failure of a test (Newton on the held stresses not converging, non-finite stress):
/// a result, not a crash. Carries the rows completed before the failure.
class ElementTestFailure : public std::runtime_error {
 public:
  ElementTestFailure(const std::string& what, std::vector<ElementRow> rows)
      : std::runtime_error(what), rows_(std::move(rows)) {}
  const std::vector<ElementRow>& rows() const { return rows_; }

 private:
  std::vector<ElementRow> rows_;
};

/// Relative tolerance on the held stress components (relative to the stress level).
inline constexpr double element_test_tolerance = 1e-9;

/// Checks the test definition (increments >= 1, strain != 0, unload_to only for the oedometer
/// and only as a reversal); throws InputError naming the key ("element.increments = 0: ...").
void validate(const ElementTest& test);

/// Number of unloading increments: the loading step size, reversed, to reach unload_to (0 when
/// there is no unloading).
int unloading_increments(const ElementTest& test);

/// Runs the test: increments + 1 + unloading_increments(test) rows, the start first. Uses only
/// the Model interface: integrate() then correct() per increment; the held stresses are found by
/// Newton on Model::tangent, falling back to a finite-difference Jacobian of the response; an
/// increment that does not converge is cut in halves (at most to 1/64) before it is a failure.
/// Throws InputError for an invalid test and ElementTestFailure on numerical failure.
std::vector<ElementRow> run_element_test(const Model& model, const ElementTest& test);

}  // namespace duet::constitutive
