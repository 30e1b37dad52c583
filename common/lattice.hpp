#pragma once
// Lattice sampling: bodies of a scene become particles, the same point cloud for every method
// (SPH particles and SPFEM nodes alike).

#include "common/particles.hpp"
#include "common/scene.hpp"

namespace duet {

/// Particles at the cell centres of a square lattice of spacing dp = scene.spacing, one lattice
/// per body anchored at the body's bounding-box corner (cells [min + i dp, min + (i+1) dp]), kept
/// when the centre lies inside the body's outline (point_in_polygon; a centre exactly on an edge
/// goes by its half-open rule). Each particle gets volume dp^2, mass rho dp^2 (kg/m), density rho,
/// the body's initial velocity, zero stress and strain, and its body and material indices.
///
/// A polygon edge that cuts cells: the midpoint rule. A cell belongs wholly to the body when its
/// centre does, so the cells along a slanted edge trade the parts they lose for those they gain;
/// the totals then approximate the area to O(dp * perimeter) at worst. They are exact when every
/// edge lies on lattice lines, i.e. a rectangle or an axis-aligned polygon whose side lengths
/// (measured from the bounding-box corner) are whole multiples of dp: then each cell is wholly in
/// or wholly out and its centre says which. Internal variables are left for the driver (they
/// belong to the models).
Particles sample_bodies(const Scene& scene);

/// How many particles body `body_index` samples to (the rule of sample_body, nothing stored).
std::size_t count_body_samples(const Scene& scene, std::size_t body_index);

/// Particles the scene samples to, estimated from the bodies' areas (area / dp^2), without
/// visiting the lattice: the figure for refusing a run that would not fit before any work.
double estimated_particles(const Scene& scene);

/// The same for one body (appended to `particles`), for tests and tools.
void sample_body(const Scene& scene, std::size_t body_index, Particles& particles);

}  // namespace duet
