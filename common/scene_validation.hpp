#pragma once
// Checks of a read scene that involve more than one table: geometry (bodies inside the domain,
// no overlapping bodies, no rigid body inside soil, bodies supported or enclosed by walls) and
// names (measure targets, reference measures, load bodies). Throws InputError
// "FILE:LINE: key: problem; expected ...".

#include <toml++/toml.h>

#include "common/scene.hpp"
#include "common/scene_schema.hpp"

namespace duet {

/// Rules:
/// - every body lies inside the domain and samples to at least 4 particles at the spacing;
/// - bodies do not overlap (they may touch along edges), and no rigid body overlaps a body;
/// - no wall passes through a body by more than half a spacing, and no body lies on the far side
///   of a wall segment (the side with fewer particles within reach: the side the methods put the
///   wall's dummies and contact on), unless the body says `crosses_walls = true`;
/// - under gravity, every body rests on something: the lowest point of its outline (the mean of
///   its lowest vertices along g) lies within one spacing of a wall, a rigid body or a body that
///   itself rests on something (no body floats free at t = 0, which would only be a fall);
/// - with `confined = true`, every edge of every body has a wall or rigid body within one spacing
///   of its midpoint (an oedometer sample must be closed on all sides);
/// - measures name an existing target of the right kind, references an existing measure, loads
///   an existing body.
void validate_scene(const Scene& scene, const toml::table& root, const SceneSource& source);

/// Distance from p to the nearest wall or rigid body outline (infinity when there is none).
double distance_to_walls(const Scene& scene, const Vec2& p);

}  // namespace duet
