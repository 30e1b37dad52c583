#pragma once
// The initial state of the material points, the same for every method: each particle's internal
// variables from its material's model, and the geostatic stress when the scene asks for it.

#include <memory>
#include <vector>

#include "common/particles.hpp"
#include "common/scene.hpp"
#include "constitutive/model.hpp"

namespace duet {

/// One model per scene material, in the scene's material order.
std::vector<std::unique_ptr<constitutive::Model>> build_models(const Scene& scene);

/// Lays out particles.internal for the scene's models and sets every particle's internal
/// variables to its model's initial values.
void initialise_internal_variables(const std::vector<std::unique_ptr<constitutive::Model>>& models,
                                   Particles& particles);

/// Geostatic stress (K0 procedure): sigma_yy = -rho |g| (surface - y) with the surface the top
/// of the particle's lattice column in its body, sigma_xx = sigma_zz = K0 sigma_yy.
void apply_geostatic_stress(const Scene& scene, double K0, Particles& particles);

/// Elastic energy stored in the particles' stress (J per metre of thickness):
/// sum_i V_i (p^2 / (2 K) + s:s / (4 G)) with p, s the mean and deviatoric stress and K, G the
/// model's moduli at that stress (isotropic elasticity's complementary energy). An initial
/// (geostatic) stress released at a free face turns into motion; the blow-up check counts it as
/// energy put in.
double stored_elastic_energy(const Scene& scene, const Particles& particles);

/// build_models + initialise_internal_variables + the scene's initial stress (geostatic, or
/// isotropic: sigma = -pressure I).
void initialise_material_points(const Scene& scene, Particles& particles);

}  // namespace duet
