#include "benchmarks/check_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "benchmarks/driver.hpp"
#include "benchmarks/material_points.hpp"
#include "benchmarks/methods.hpp"
#include "benchmarks/reports.hpp"
#include "benchmarks/scene_input.hpp"
#include "common/geometry.hpp"
#include "common/input_error.hpp"
#include "common/lattice.hpp"
#include "constitutive/model.hpp"
#include "spfem/explicit_solver.hpp"

namespace duet {

namespace {

struct CheckArgs {
  std::string scene;
  std::string method;
  double spacing = 0.0;
  std::vector<std::string> sets;
  bool force = false;
};

/// Three significant digits: what an estimate deserves.
std::string about(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

std::string with_commas(double value) {
  // Beyond a long long (a mistaken spacing or density): the order of magnitude is the message.
  if (!(std::abs(value) < 1e15)) return about(value);
  std::string digits = std::to_string(static_cast<long long>(std::llround(value)));
  for (int at = static_cast<int>(digits.size()) - 3; at > 0; at -= 3) digits.insert(at, ",");
  return digits;
}

/// The fastest wave over the particles in their initial state: sqrt(M / rho), M the models'
/// tangent bound at the initial stress (constitutive::block_modulus: the P-wave modulus K + 4G/3
/// of elasticity, the hypoplastic L + N); `stiffening` where a model's bound grows with the stress
/// (espfem's stress-increment limit then shortens steps near zero stress). A scene too large to
/// sample here gives 0.
struct InitialWaves {
  double speed = 0.0;
  bool stiffening = false;
};

InitialWaves initial_waves(const Scene& scene) {
  InitialWaves w;
  if (estimated_particles(scene) > 2.0e6) return w;
  Particles particles = sample_bodies(scene);
  initialise_material_points(scene, particles);
  const auto models = build_models(scene);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const auto& model = *models[static_cast<std::size_t>(particles.material[i])];
    const constitutive::ElasticModuli e = model.moduli(
        particles.stress[i],
        std::span<const double>(particles.internal.of(i), model.internal_variables().size()));
    w.speed = std::max(w.speed, std::sqrt(constitutive::block_modulus(e) / particles.density[i]));
    w.stiffening = w.stiffening || e.tangent_bound > 0.0;
  }
  return w;
}

void print_scene(const Scene& scene, std::ostream& out) {
  const double frames = std::floor(scene.time.end_time / scene.time.output_interval + 1e-9) + 1.0;
  out << "scene " << scene.name << " (" << scene.path << "): valid\n"
      << "  spacing " << format_number(scene.spacing) << " m, end time "
      << format_number(scene.time.end_time) << " s, a frame every "
      << format_number(scene.time.output_interval) << " s (" << with_commas(frames) << " frames)\n";
  if (scene.formulation == Formulation::axisymmetric) {
    out << "  axisymmetric: x = r about the axis x = 0; masses, reactions and energies of the "
           "whole circumference\n";
  }
  const bool huge = estimated_particles(scene) > 5.0e7;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const Body& body = scene.bodies[b];
    const Material& m = scene.materials[static_cast<std::size_t>(body.material_index)];
    out << "  body " << body.name << " (" << m.name << ", " << m.model << "): ";
    if (huge) {
      out << "about "
          << format_number(std::abs(signed_area(body.outline)) / (scene.spacing * scene.spacing))
          << " particles\n";
    } else {
      out << with_commas(static_cast<double>(count_body_samples(scene, b))) << " particles\n";
    }
  }
  for (const Wall& w : scene.walls)
    out << "  wall " << w.name << " (" << to_string(w.condition)
        << (w.radial             ? ", radial"
            : w.velocity.empty() ? ""
                                 : ", moving")
        << ")\n";
  for (const RigidBody& rb : scene.rigid_bodies)
    out << "  rigid body " << rb.name << " (" << to_string(rb.surface)
        << (rb.velocity.empty() ? "" : ", moving") << ")\n";
  for (const Measure& m : scene.measures)
    out << "  measure " << m.name << " (" << to_string(m.kind) << ", " << to_string(m.at) << ")\n";
  for (const Reference& r : scene.references) {
    out << "  scored: " << r.measure << " against ";
    if (r.curve.empty()) {
      out << format_number(r.value);
    } else {
      out << "the curve " << r.curve_file << " (" << r.curve.size() << " points, holds from "
          << format_number(r.holds.x()) << " to " << format_number(r.holds.y()) << ")";
    }
    for (const Measure& m : scene.measures) {
      if (m.name == r.measure && m.at == MeasureAt::curve) {
        out << " over " << m.abscissa << " from " << format_number(m.x_window.x()) << " to "
            << format_number(m.x_window.y());
      }
    }
    out << " (tolerance " << format_number(100.0 * r.tolerance) << " %)\n";
  }
}

/// Why SPH's sound speed is what it is: the solver takes sph.sound_speed as given (its time step,
/// Peng 2015 eq 37, and Monaghan's viscosity alpha c_s); set beside the soil's P-wave speed, the
/// step's Courant number against the fastest elastic wave.
std::string sph_sound_speed_note(const Scene& scene, double wave_speed) {
  std::ostringstream note;
  note << "the sound speed is sph.sound_speed as given (the solver does not raise it to the "
          "soil's P-wave speed";
  if (wave_speed > 0.0) {
    note << ", here " << about(wave_speed) << " m/s";
    if (wave_speed > scene.sph.sound_speed) {
      note << ": the step is then " << about(scene.sph.cfl * wave_speed / scene.sph.sound_speed)
           << " Courant numbers against it, not cfl " << format_number(scene.sph.cfl);
    }
  }
  note << ")";
  return note.str();
}

/// One line per method: its step and steps (or increments) and memory.
void print_method(const Scene& scene, const MethodInfo& method, const InitialWaves& waves,
                  std::ostream& out) {
  const double wave_speed = waves.speed;
  const RunEstimate e = estimate_run(scene, method);
  std::ostringstream line;
  line << "  " << method.name << ": ";
  if (method.name == "sph") {
    // sph/sph_solver.cpp: dt <= cfl h / sound_speed (and the acceleration limit).
    const double h = scene.sph.h_over_dp * scene.spacing;
    const double dt = scene.sph.cfl * h / scene.sph.sound_speed;
    line << "time step at most " << about(dt) << " s (cfl " << format_number(scene.sph.cfl)
         << " x h / sound speed " << format_number(scene.sph.sound_speed) << " m/s), at least "
         << with_commas(std::ceil(scene.time.end_time / dt)) << " steps; "
         << sph_sound_speed_note(scene, wave_speed);
  } else if (method.name == "espfem" && wave_speed > 0.0) {
    // spfem/explicit_solver.cpp: dt = safety x the rule's step on a lattice (a fraction of dp /
    // P-wave speed), times the linear bulk viscosity's factor
    const double b1 = scene.spfem.bulk_viscosity;
    const double viscous = spfem::bulk_viscosity_step_factor(b1);
    const double rule = spfem::lattice_step_over_dp_per_c(scene.spfem.time_step);
    const double dt = viscous * scene.spfem.time_step_safety * rule * scene.spacing / wave_speed;
    line << "time step about " << about(dt) << " s (safety "
         << format_number(scene.spfem.time_step_safety) << " x ";
    if (rule != 1.0) line << format_number(rule) << " x ";
    line << "dp / P-wave speed " << about(wave_speed) << " m/s";
    if (b1 > 0.0) line << " x " << about(viscous) << " for bulk_viscosity " << format_number(b1);
    line << "), about " << with_commas(std::ceil(scene.time.end_time / dt)) << " steps";
    if (waves.stiffening && scene.spfem.stress_increment_limit > 0.0) {
      // The limit follows the strain rates of the run: no estimate before it
      line << " at least: spfem.stress_increment_limit shortens the steps where the soil, whose "
              "stiffness grows with its stress, is near zero stress, by how much only the run "
              "knows (metrics.json: stress_limited_steps)";
    } else {
      line << " (slivers of the mesh shorten it)";
    }
  } else if (method.name == "espfem") {
    line << "time step not estimated (too many particles to sample the wave speed here)";
  } else if (method.name == "ispfem") {
    const double increment = scene.spfem_implicit.increment > 0.0
                                 ? scene.spfem_implicit.increment
                                 : scene.time.end_time / scene.spfem_implicit.load_steps;
    line << "increments of " << format_number(increment) << " s, "
         << with_commas(std::ceil(scene.time.end_time / increment - 1e-9))
         << " of them (more where Newton cuts them)";
  }
  line << "; memory about " << about(e.bytes / 1e9) << " GB of this machine's "
       << about(e.machine_bytes / 1e9) << " GB";
  out << line.str() << '\n';
}

}  // namespace

void add_check_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* cmd =
      app.add_subcommand("check", "validate a scene and print what a run would be; run nothing");
  cmd->add_option("scene", args->scene, "scene file (TOML)")->required();
  cmd->add_option("--method", args->method, "sph | espfem | ispfem (default: every one)");
  cmd->add_option("--spacing", args->spacing, "particle spacing dp (m), overrides the scene's");
  cmd->add_option("--set", args->sets, "override a scene key: dotted.key=value (repeatable)");
  cmd->add_flag("--force", args->force,
                "do not refuse a run estimated beyond the memory, or a modulus or strength that "
                "looks like MPa or kPa written in Pa (as duet run --force)");
  cmd->callback([args, cmd, &exit_code] {
    std::vector<std::string> overrides = args->sets;
    if (cmd->count("--spacing") > 0) overrides.push_back(spacing_override(args->spacing));
    const Scene scene = load_scene_checked(args->scene, overrides, args->force);
    std::vector<const MethodInfo*> methods;
    if (args->method.empty()) {
      for (const auto& name : builtin_methods().names())
        methods.push_back(&builtin_methods().find(name));
    } else {
      methods.push_back(&builtin_methods().find(args->method));
    }
    for (const MethodInfo* m : methods) refuse_if_too_large(scene, *m, args->force);
    // What a method refuses when it builds its solver (ispfem: a body set moving, a face no
    // static equilibrium holds), as `duet run` would: an error for the method asked for, a line
    // for each of the others
    std::map<const MethodInfo*, std::string> refusals;
    for (const MethodInfo* m : methods) {
      try {
        m->make(scene);
      } catch (const InputError& e) {
        if (!args->method.empty()) throw;
        refusals[m] = e.what();
      }
    }
    print_scene(scene, std::cout);
    const InitialWaves waves = initial_waves(scene);
    for (const MethodInfo* m : methods) {
      if (refusals.count(m) != 0) {
        std::cout << "  " << m->name << ": refused (duet run exits 2): " << refusals[m] << '\n';
      } else {
        print_method(scene, *m, waves, std::cout);
      }
    }
    exit_code = 0;
  });
}

}  // namespace duet
