#pragma once
// The four constants c1..c4 of the Wang/Wu hypoplastic equation (Peng 2015 eq 15) from the
// parameters of one drained triaxial test (Peng 2015 section 3.2, after Wu & Bauer 1994): the
// initial tangent modulus E_i, the initial Poisson ratio nu_i, the friction angle phi and the
// dilatancy angle psi, all at the confining stress sigma_3 (-100 kPa in the paper).
// The derivation is written out in constitutive/docs/hypoplastic.md.

namespace duet::constitutive {

/// The dimensionless constants of Peng 2015 eq 15 (negative for a sand; Table 1).
struct HypoplasticConstants {
  double c1 = 0.0;
  double c2 = 0.0;
  double c3 = 0.0;
  double c4 = 0.0;
};

/// One drained triaxial test as the paper describes it. Tension positive.
struct TriaxialProperties {
  double initial_modulus = 0.0;        // E_i = [(dsigma_1 - dsigma_3)/deps_1]_{R=1}, Pa
  double initial_poisson_ratio = 0.0;  // nu_i = -[deps_3/deps_1]_{R=1}, -
  double friction_angle = 0.0;         // phi, degrees
  double dilatancy_angle = 0.0;        // psi, degrees
  double confining_stress = -100e3;    // sigma_3, Pa (compression negative)
};

/// Peng 2015 eq 17: failure stress ratio R_f = sigma_1/sigma_3 = (1 + sin phi)/(1 - sin phi).
double failure_stress_ratio(double friction_angle_deg);

/// Peng 2015 eq 18: failure Poisson ratio nu_f = -[deps_3/deps_1]_{R=R_f} = (1 + tan psi)/2,
/// i.e. tan psi = -deps_v/deps_1 at failure.
double failure_poisson_ratio(double dilatancy_angle_deg);

/// c1..c4 such that eq 15 reproduces E_i and nu_i at the isotropic state sigma_3 I and has a
/// stationary stress (zero rate) at R = R_f when the strain rate has the ratio nu_f. Throws
/// std::domain_error when the conditions are singular (nu_i = 0.5).
HypoplasticConstants calibrate_hypoplastic(const TriaxialProperties& triaxial);

/// Peng 2015 eq 38: the earth pressure at rest K0 = sigma_3/sigma_1 of an oedometer loading,
/// the root in (0, 1) of (6 c1 + 2 c4) K0^2 + (3 c1 - c4) K0 - c4 = 0. NaN when there is none.
double oedometer_k0(const HypoplasticConstants& constants);

}  // namespace duet::constitutive
