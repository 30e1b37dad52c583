#pragma once
// Lattice sampling: bodies of a scene become particles, the same point cloud for every method
// (SPH particles and SPFEM nodes alike).

#include <string>
#include <vector>

#include "common/particles.hpp"
#include "common/scene.hpp"

namespace duet {

/// Particles at the cell centres of a square lattice of spacing dp = scene.spacing (or, for a body
/// with lattice = polar, on rings; below), one lattice
/// per body anchored at the body's bounding-box corner (cells [min + i dp, min + (i+1) dp]), kept
/// when the centre lies inside the body's outline (point_in_polygon; a centre exactly on an edge
/// goes by its half-open rule). Each particle gets volume dp^2, mass rho dp^2 (kg/m), density rho,
/// the body's initial velocity, zero stress and strain, and its body and material indices.
/// In an axisymmetric scene (x = r) a sample of area A stands for its ring: volume 2 pi r A and
/// mass rho 2 pi r A (kg), r the sample's centre (Pappus: exact for the square lattice's cells and
/// the polar lattice's annulus sectors, whose centroids lie at their centres' r to O(dp^2 / r)).
///
/// A polygon edge that cuts cells: the midpoint rule. A cell belongs wholly to the body when its
/// centre does, so the cells along a slanted edge trade the parts they lose for those they gain;
/// the totals then approximate the area to O(dp * perimeter) at worst. They are exact when every
/// edge lies on lattice lines, i.e. a rectangle or an axis-aligned polygon whose side lengths
/// (measured from the bounding-box corner) are whole multiples of dp: then each cell is wholly in
/// or wholly out and its centre says which. Internal variables are left for the driver (they
/// belong to the models).
///
/// Polar lattice (a body around a cavity): rings r_k = r_0 + (k + 1/2) dp about lattice_centre,
/// r_0 the outline's nearest vertex (0 when the centre lies inside), each ring with n_k points at
/// angles (j + 1/2) 2 pi / n_k, n_k = 4 round(pi r_k / (2 dp)), each of volume r_k dp 2 pi / n_k
/// (its share of the ring's annulus). The first ring lies dp/2 off a circular cavity of radius
/// r_0, as the square lattice's first row lies dp/2 off a straight side, and the axes through the
/// centre fall midway between points: a quarter annulus gets the area pi/4 (r_1^2 - r_0^2)
/// exactly (the midpoint rule in r is exact for the annulus) and smooth boundaries on all sides.
/// A square lattice against a curved cavity leaves its nearest nodes 0 to dp off the wall, so a
/// moving cavity wall meets them one after another.
Particles sample_bodies(const Scene& scene);

/// How many particles body `body_index` samples to (the rule of sample_body, nothing stored).
std::size_t count_body_samples(const Scene& scene, std::size_t body_index);

/// Particles the scene samples to, estimated from the bodies' areas (area / dp^2), without
/// visiting the lattice: the figure for refusing a run that would not fit before any work.
double estimated_particles(const Scene& scene);

/// Rectangles whose sides are not whole multiples of the spacing, one line per such body: the
/// square lattice is anchored at `min`, so its last row (column) ends short of or beyond `max`
/// and the sampled body differs from the drawn one (collapse.toml at dp 3.5 mm: 0.1995 x
/// 0.1015 m for 0.2 x 0.1 m; a footing on a 7.5 m block at dp 0.2 m starts a whole spacing, not
/// dp/2, above the top row, and ispfem carried no load until it had sunk 0.2 m). Said, not refused:
/// a scene may mean it. Polygons and polar lattices are not checked (slanted edges and arcs
/// never fit a lattice exactly).
std::vector<std::string> lattice_misfits(const Scene& scene);

/// The same for one body (appended to `particles`), for tests and tools.
void sample_body(const Scene& scene, std::size_t body_index, Particles& particles);

}  // namespace duet
