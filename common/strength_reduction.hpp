#pragma once
// Strength reduction (Peng 2015 section 5.3, eqs 39-40; Griffiths & Lane 1999): a material's c and
// phi divided by a factor f, and when in a run that factor applies. With gravity loading and
// stage "after-loading" (Peng's order: "the original (unreduced) shear parameters are used when
// computing the initial stresses") the soil settles at full strength and the strength falls to
// c/f over the first `ramp` seconds of the run; with stage "throughout" the reduced strength
// holds from the first gravity increment.

#include <map>
#include <string>

#include "common/parameter_value.hpp"
#include "common/scene.hpp"

namespace duet {

/// Peng 2015 eq 39 (c / f) and eq 40 (phi / f, rule "angle") or tan phi / f (rule "tangent"),
/// on the parameters `c` and `phi` (degrees) where given. False when there is neither.
bool reduce_strength(std::map<std::string, ParameterValue>& parameters, double factor,
                     const std::string& rule);

/// The factor the gravity loading uses: 1 under stage "after-loading", else the scene's.
double loading_strength_factor(const Scene& scene);

/// The factor in effect at run time `time` (the clock starts after any gravity loading; at
/// time 0 the soil is as the loading left it, at full strength under stage "after-loading").
double strength_factor_at(const Scene& scene, double time);

/// True when the strength changes during the run (after-loading with a factor other than 1).
bool strength_changes_in_run(const Scene& scene);

/// The parameters of `material` at strength factor `factor`: as loaded at the scene's factor,
/// else its full-strength ones reduced.
std::map<std::string, ParameterValue> parameters_at(const Scene& scene, const Material& material,
                                                    double factor);

}  // namespace duet
