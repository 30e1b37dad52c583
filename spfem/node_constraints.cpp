#include "spfem/node_constraints.hpp"

#include <cmath>

#include "common/geometry.hpp"

namespace duet::spfem {

ConstraintKind constraint_kind(NodeCondition condition) {
  return condition == NodeCondition::bonded || condition == NodeCondition::rough
             ? ConstraintKind::fixed
             : ConstraintKind::normal;
}

Vec2 boundary_displacement(const NodeBoundary& boundary, double t0, double t1, const Vec2& point) {
  if (boundary.radial) {
    const double growth = schedule_integral(boundary.radial_velocity, std::max(t1, 0.0)).x() -
                          schedule_integral(boundary.radial_velocity, std::max(t0, 0.0)).x();
    return radial_displacement(point, boundary.centre, growth);
  }
  return schedule_integral(boundary.velocity, std::max(t1, 0.0)) -
         schedule_integral(boundary.velocity, std::max(t0, 0.0));
}

DofMap eliminate(std::size_t n_nodes, const std::vector<NodeConstraint>& constraints,
                 const std::vector<std::uint8_t>& held) {
  // Per node: fixed, or up to two distinct normals with their prescribed normal motions.
  struct Gathered {
    bool fixed = false;
    Vec2 fixed_value = Vec2::Zero();
    int n_normals = 0;
    Vec2 normal[2];
    double value[2] = {0.0, 0.0};
  };
  std::vector<Gathered> g(n_nodes);
  for (const NodeConstraint& c : constraints) {
    Gathered& n = g[static_cast<std::size_t>(c.node)];
    if (c.kind == ConstraintKind::fixed) {
      if (!n.fixed) n.fixed_value = c.increment;  // the first fixing boundary prescribes
      n.fixed = true;
      continue;
    }
    const double v = c.increment.dot(c.normal);
    bool parallel = false;
    for (int j = 0; j < n.n_normals; ++j) {
      parallel = parallel || std::abs(n.normal[j].dot(c.normal)) > 1.0 - 1e-6;
    }
    if (!parallel && n.n_normals < 2) {
      n.normal[n.n_normals] = c.normal;
      n.value[n.n_normals] = v;
      ++n.n_normals;
    }
  }
  DofMap map;
  map.first.assign(n_nodes + 1, 0);
  map.prescribed.assign(n_nodes, Vec2::Zero());
  map.constrained.assign(n_nodes, 0);
  for (std::size_t i = 0; i < n_nodes; ++i) {
    const Gathered& n = g[i];
    map.first[i] = static_cast<std::int32_t>(map.direction.size());
    const auto add = [&](const Vec2& d) {
      map.direction.push_back(d);
      map.node.push_back(static_cast<std::int32_t>(i));
    };
    if (held[i] != 0) {
      // In no triangle: nothing but its boundaries can move it. It follows the boundary that
      // touches it (its normal motion, none along it) and stays put otherwise.
      map.constrained[i] = 1;
      if (n.fixed) {
        map.prescribed[i] = n.fixed_value;
      } else if (n.n_normals == 2) {
        Mat2 a;
        a.row(0) = n.normal[0].transpose();
        a.row(1) = n.normal[1].transpose();
        map.prescribed[i] = a.inverse() * Vec2(n.value[0], n.value[1]);
      } else if (n.n_normals == 1) {
        map.prescribed[i] = n.value[0] * n.normal[0];
      }
    } else if (n.fixed) {
      map.constrained[i] = 1;
      map.prescribed[i] = n.fixed_value;
    } else if (n.n_normals == 2) {
      // u . n_j = v_j for both normals (a corner between two walls)
      Mat2 a;
      a.row(0) = n.normal[0].transpose();
      a.row(1) = n.normal[1].transpose();
      map.constrained[i] = 1;
      map.prescribed[i] = a.inverse() * Vec2(n.value[0], n.value[1]);
    } else if (n.n_normals == 1) {
      map.constrained[i] = 1;
      map.prescribed[i] = n.value[0] * n.normal[0];
      add(Vec2(-n.normal[0].y(), n.normal[0].x()));  // the tangent stays free
    } else {
      add(Vec2(1.0, 0.0));
      add(Vec2(0.0, 1.0));
    }
  }
  map.first[n_nodes] = static_cast<std::int32_t>(map.direction.size());
  return map;
}

}  // namespace duet::spfem
