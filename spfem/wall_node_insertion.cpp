#include "spfem/wall_node_insertion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace duet::spfem {

double arc_position(const std::vector<Vec2>& polyline, const Vec2& x) {
  double best = std::numeric_limits<double>::infinity();
  double at = 0.0;
  double start = 0.0;  // arc length at the segment's first point
  for (std::size_t s = 0; s + 1 < polyline.size(); ++s) {
    const Vec2 a = polyline[s];
    const Vec2 d = polyline[s + 1] - a;
    const double length = d.norm();
    const double t = length > 0.0 ? std::clamp((x - a).dot(d) / (length * length), 0.0, 1.0) : 0.0;
    const double distance = (a + t * d - x).squaredNorm();
    if (distance < best) {
      best = distance;
      at = start + t * length;
    }
    start += length;
  }
  return at;
}

namespace {

struct WallNode {
  double along;     // arc position of its contact point
  double distance;  // from the wall, on the soil side
  std::int32_t node;
};

/// Appends node n as the mass-weighted mean of a and b, each giving kInsertedShare of its mass
/// and volume.
void add_between(Particles& p, std::size_t a, std::size_t b, const Vec2& position) {
  const std::size_t n = p.size();
  p.resize(n + 1);
  const double ma = kInsertedShare * p.mass[a];
  const double mb = kInsertedShare * p.mass[b];
  const double wa = ma / (ma + mb);
  const double wb = 1.0 - wa;
  p.position[n] = position;
  p.velocity[n] = wa * p.velocity[a] + wb * p.velocity[b];
  p.displacement[n] = wa * p.displacement[a] + wb * p.displacement[b];
  p.stress[n] = wa * p.stress[a] + wb * p.stress[b];
  p.strain[n] = wa * p.strain[a] + wb * p.strain[b];
  p.mass[n] = ma + mb;
  p.volume[n] = kInsertedShare * (p.volume[a] + p.volume[b]);
  p.density[n] = p.mass[n] / p.volume[n];
  p.body[n] = p.body[a];
  p.material[n] = p.material[a];
  const std::size_t w = p.internal.width;
  for (std::size_t k = 0; k < w; ++k) {
    p.internal.values[n * w + k] =
        wa * p.internal.values[a * w + k] + wb * p.internal.values[b * w + k];
  }
  for (const std::size_t parent : {a, b}) {
    p.mass[parent] *= 1.0 - kInsertedShare;
    p.volume[parent] *= 1.0 - kInsertedShare;
  }
}

}  // namespace

std::vector<InsertedNode> insert_wall_nodes(const std::vector<NodeBoundary>& boundaries,
                                            const std::vector<BoundaryGeometry>& geometry,
                                            double spacing, double gap_factor,
                                            Particles& particles) {
  const double reach = 0.5 * spacing * (1.0 + 1e-6);  // node_contact's, as the explicit solver's
  std::vector<InsertedNode> added;
  std::vector<NodeContact> found;
  std::vector<WallNode> row;
  const double depth = reach;  // a node just crossed still belongs to the row
  for (std::size_t b = 0; b < boundaries.size(); ++b) {
    if (boundaries[b].rigid_body) continue;
    const BoundaryGeometry& g = geometry[b];
    row.clear();
    const std::size_t n = particles.size();  // the nodes added for an earlier wall are not on it
    for (std::size_t i = 0; i < n; ++i) {
      found.clear();
      const auto node = static_cast<std::int32_t>(i);
      find_node_contacts(g, false, node, static_cast<std::int32_t>(b), particles.position[i], reach,
                         depth, found);
      if (found.empty()) continue;
      const NodeContact& c = found.front();
      row.push_back({arc_position(g.points, c.point), c.distance, node});
    }
    std::sort(row.begin(), row.end(),
              [](const WallNode& l, const WallNode& r) { return l.along < r.along; });
    for (std::size_t k = 0; k + 1 < row.size(); ++k) {
      const auto a = static_cast<std::size_t>(row[k].node);
      const auto c = static_cast<std::size_t>(row[k + 1].node);
      if (particles.body[a] != particles.body[c] ||
          particles.material[a] != particles.material[c]) {
        continue;
      }
      // Stretched, not sampled so: two neighbours on the row may have lain further apart than dp
      // from the start (the polar lattice's first nodes off a symmetry plane, one ring in two
      // within reach of it); their gap counts from where they were, x - u.
      const double gap = (particles.position[c] - particles.position[a]).norm();
      const double was = (particles.position[c] - particles.displacement[c] -
                          particles.position[a] + particles.displacement[a])
                             .norm();
      const double limit = gap_factor * std::max(spacing, was);
      if (!(gap > limit && gap < 2.0 * limit)) continue;
      // Between the two, at their mean distance from the wall (the chord's midpoint lies nearer
      // a concave wall than either of them).
      Vec2 x = 0.5 * (particles.position[a] + particles.position[c]);
      found.clear();
      find_contacts(g, false, -1, static_cast<std::int32_t>(b), x, 2.0 * reach, depth, found);
      if (!found.empty()) {
        const double wanted = 0.5 * (row[k].distance + row[k + 1].distance);
        x += (wanted - found.front().distance) * found.front().normal;
      }
      add_between(particles, a, c, x);
      added.push_back({static_cast<std::int32_t>(particles.size() - 1),
                       {static_cast<std::int32_t>(a), static_cast<std::int32_t>(c)}});
    }
  }
  return added;
}

}  // namespace duet::spfem
