#pragma once
// The spellings a scene file uses for the scene's enums, one table per enum: the loader reads a
// name through its table (no cast of a list position to the enum) and the resolved scene writes
// it back through the same table, so the two cannot fall out of step. A value missing from its
// table is a programming error, said loudly (std::logic_error), never written as another value.

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "common/scene.hpp"

namespace duet {

template <class Enum>
struct EnumName {
  Enum value;
  const char* name;
};

inline constexpr EnumName<Formulation> kFormulationNames[] = {
    {Formulation::plane_strain, "plane-strain"},
    {Formulation::axisymmetric, "axisymmetric"},
};

inline constexpr EnumName<MeasureKind> kMeasureKindNames[] = {
    {MeasureKind::front, "front"},
    {MeasureKind::height, "height"},
    {MeasureKind::reaction, "reaction"},
    {MeasureKind::wall_stress, "wall_stress"},
    {MeasureKind::max_displacement, "max_displacement"},
    {MeasureKind::displacement, "displacement"},
    {MeasureKind::period, "period"},
    {MeasureKind::safety_factor, "safety_factor"},
    {MeasureKind::expansion, "expansion"},
    {MeasureKind::point_displacement, "point_displacement"},
};

inline constexpr EnumName<MeasureAt> kMeasureAtNames[] = {
    {MeasureAt::end, "end"},   {MeasureAt::max, "max"},     {MeasureAt::series, "series"},
    {MeasureAt::time, "time"}, {MeasureAt::curve, "curve"},
};

inline constexpr EnumName<InitialStressKind> kInitialStressKindNames[] = {
    {InitialStressKind::none, "none"},
    {InitialStressKind::isotropic, "isotropic"},
    {InitialStressKind::geostatic, "geostatic"},
    {InitialStressKind::gravity_loading, "gravity-loading"},
};

inline constexpr EnumName<WallCondition> kWallConditionNames[] = {
    {WallCondition::no_slip, "no-slip"},
    {WallCondition::free_slip, "free-slip"},
    {WallCondition::symmetry, "symmetry"},
};

inline constexpr EnumName<Surface> kSurfaceNames[] = {
    {Surface::rough, "rough"},
    {Surface::smooth, "smooth"},
    {Surface::friction, "friction"},
};

inline constexpr EnumName<SphKernel> kSphKernelNames[] = {
    {SphKernel::cubic_spline, "cubic-spline"},
    {SphKernel::wendland_c2, "wendland-c2"},
};

inline constexpr EnumName<SphWallStress> kSphWallStressNames[] = {
    {SphWallStress::sigma_max, "sigma-max"},
    {SphWallStress::bui, "bui"},
};

inline constexpr EnumName<SphDummyVelocity> kSphDummyVelocityNames[] = {
    {SphDummyVelocity::wall, "wall"},
    {SphDummyVelocity::extrapolated, "extrapolated"},
};

inline constexpr EnumName<SphIntegrator> kSphIntegratorNames[] = {
    {SphIntegrator::verlet, "verlet"},
    {SphIntegrator::leapfrog, "leapfrog"},
};

inline constexpr EnumName<SpfemTimeStep> kSpfemTimeStepNames[] = {
    {SpfemTimeStep::cell_size, "cell-size"},
    {SpfemTimeStep::gershgorin, "gershgorin"},
};

inline constexpr EnumName<Remesh> kRemeshNames[] = {
    {Remesh::every_step, "every-step"},
    {Remesh::angle, "angle"},
};

/// Every name of a table, in its order (the choices a key offers).
template <class Enum, std::size_t N>
std::vector<std::string> names_of(const EnumName<Enum> (&table)[N]) {
  std::vector<std::string> names;
  for (const EnumName<Enum>& entry : table) names.emplace_back(entry.name);
  return names;
}

/// The value spelled `name` (a name the loader has already checked is one of the table's).
template <class Enum, std::size_t N>
Enum value_named(std::string_view name, const EnumName<Enum> (&table)[N]) {
  for (const EnumName<Enum>& entry : table) {
    if (name == entry.name) return entry.value;
  }
  throw std::logic_error("no scene enum value is named \"" + std::string(name) + "\"");
}

/// The name of `value`.
template <class Enum, std::size_t N>
const char* name_of(Enum value, const EnumName<Enum> (&table)[N]) {
  for (const EnumName<Enum>& entry : table) {
    if (entry.value == value) return entry.name;
  }
  throw std::logic_error("a scene enum value (" + std::to_string(static_cast<int>(value)) +
                         ") has no name in common/enum_names.hpp");
}

}  // namespace duet
