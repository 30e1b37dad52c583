#pragma once
// The models of a scene's materials, by material index, at a strength-reduction factor (the
// scene's own factor for the run; 1 for gravity loading under Peng's order:
// common/strength_reduction.hpp). Each solver's setup holds such a list.

#include <memory>
#include <vector>

#include "common/scene.hpp"
#include "constitutive/model.hpp"

namespace duet::constitutive {

using Models = std::vector<std::unique_ptr<Model>>;

/// Every material's model built from its full-strength parameters reduced by `factor`
/// (Peng 2015 eqs 39-40); at the scene's factor, the models of `scene.materials` as loaded.
Models make_scene_models(const Scene& scene, double factor);

/// No material can soften and the strength stays as given: every material's model says it cannot
/// (ModelInfo::softens false: elasticity and perfect plasticity) and no strength reduction runs,
/// so a driven load does not fall (the run's load-drop warning, ispfem's spfem.implicit.load_drop).
bool cannot_soften(const Scene& scene);

/// Replaces `models` by `replacement`, which must have as many models with as many internal
/// variables each (a strength reduced during the run); `solver` names the caller in the error.
void replace_models(Models& models, Models replacement, const char* solver);

/// The strength factor of a run whose strength falls after gravity loading (Peng's order:
/// common/strength_reduction.hpp), followed step by step: a solver swaps its models when it
/// changes. Starts at the factor the gravity loading used.
class StrengthInRun {
 public:
  explicit StrengthInRun(const Scene& scene);
  /// True when the factor at run time `time` differs from the last one seen (now `factor()`).
  bool changes_at(const Scene& scene, double time);
  /// The models at the factor last seen.
  Models models(const Scene& scene) const { return make_scene_models(scene, factor_); }

 private:
  double factor_;
};

}  // namespace duet::constitutive
