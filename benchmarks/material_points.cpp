#include "benchmarks/material_points.hpp"

#include <cmath>
#include <map>

#include "constitutive/registry.hpp"

namespace duet {

std::vector<std::unique_ptr<constitutive::Model>> build_models(const Scene& scene) {
  std::vector<std::unique_ptr<constitutive::Model>> models;
  for (const auto& material : scene.materials) {
    models.push_back(
        constitutive::make_model(material.model, material.parameters, "material." + material.name));
  }
  return models;
}

void initialise_internal_variables(const std::vector<std::unique_ptr<constitutive::Model>>& models,
                                   Particles& particles) {
  InternalVariables& iv = particles.internal;
  iv.names.clear();
  iv.slot.assign(models.size(), {});
  iv.width = 0;
  std::vector<std::vector<constitutive::InternalVariable>> declared;
  for (const auto& model : models) {
    declared.push_back(model->internal_variables());
    iv.width = std::max(iv.width, declared.back().size());
    for (const auto& v : declared.back()) {
      if (iv.index_of(v.name) < 0) iv.names.push_back(v.name);
    }
  }
  for (std::size_t m = 0; m < models.size(); ++m) {
    iv.slot[m].assign(iv.names.size(), -1);
    for (std::size_t k = 0; k < declared[m].size(); ++k) {
      iv.slot[m][static_cast<std::size_t>(iv.index_of(declared[m][k].name))] = static_cast<int>(k);
    }
  }
  iv.values.assign(particles.size() * iv.width, 0.0);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const auto& vars = declared[static_cast<std::size_t>(particles.material[i])];
    for (std::size_t k = 0; k < vars.size(); ++k) iv.of(i)[k] = vars[k].initial;
  }
}

void apply_geostatic_stress(const Scene& scene, double K0, Particles& particles) {
  const double g = scene.gravity.norm();
  const double dp = scene.spacing;
  // Surface height per (body, lattice column): the highest particle plus half a spacing.
  std::map<std::pair<int, long>, double> surface;
  auto column = [dp](double x) { return static_cast<long>(std::floor(x / dp + 0.5)); };
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const auto key = std::make_pair(particles.body[i], column(particles.position[i].x()));
    const double top = particles.position[i].y() + 0.5 * dp;
    auto [it, inserted] = surface.emplace(key, top);
    if (!inserted) it->second = std::max(it->second, top);
  }
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const double top = surface[{particles.body[i], column(particles.position[i].x())}];
    const double sigma_v = -particles.density[i] * g * (top - particles.position[i].y());
    Mat3 s = Mat3::Zero();
    s(1, 1) = sigma_v;
    s(0, 0) = s(2, 2) = K0 * sigma_v;
    particles.stress[i] = s;
  }
}

double stored_elastic_energy(const Scene& scene, const Particles& particles) {
  const auto models = build_models(scene);
  double energy = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Mat3& sigma = particles.stress[i];
    if (sigma.isZero(0.0)) continue;
    const auto& model = *models[static_cast<std::size_t>(particles.material[i])];
    const std::size_t width = model.internal_variables().size();
    const constitutive::ElasticModuli e =
        model.moduli(sigma, std::span<const double>(particles.internal.of(i), width));
    const double p = sigma.trace() / 3.0;
    const Mat3 s = sigma - p * Mat3::Identity();
    double w = 0.0;
    if (e.bulk > 0.0) w += p * p / (2.0 * e.bulk);
    if (e.shear > 0.0) w += s.squaredNorm() / (4.0 * e.shear);
    energy += particles.volume[i] * w;
  }
  return energy;
}

void initialise_material_points(const Scene& scene, Particles& particles) {
  initialise_internal_variables(build_models(scene), particles);
  if (scene.initial_stress.kind == InitialStressKind::geostatic) {
    apply_geostatic_stress(scene, scene.initial_stress.K0, particles);
  } else if (scene.initial_stress.kind == InitialStressKind::isotropic) {
    // sigma = -pressure I (compression negative).
    for (Mat3& s : particles.stress) s = -scene.initial_stress.pressure * Mat3::Identity();
  }
}

}  // namespace duet
