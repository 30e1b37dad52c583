#pragma once
// Whether the scene's bodies can stand at all under gravity without inertia: a free face of a
// cohesionless frictional soil steeper than its friction angle has no static equilibrium (a dry
// slope stands at most at its angle of repose, phi: the infinite-slope limit tan(beta) = tan(phi)
// with c = 0). A quasi-static method has nothing to find there and refuses the scene before work.

#include <string>

#include "common/scene.hpp"

namespace duet {

/// The first free face (no wall, rigid body or other body within one spacing of it) of a body of
/// cohesionless soil (c = 0: drucker-prager, mohr-coulomb, simhypo-sand with phi_c, hypoplastic
/// with its phi, or below 90 deg given by c1..c4) inclined to the horizontal by more than the
/// soil's friction angle, said as "body.NAME: ..."; "" when there is none or the scene has no
/// gravity.
std::string face_steeper_than_friction(const Scene& scene);

}  // namespace duet
