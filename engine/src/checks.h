#pragma once
/// Boundary checks for everything the application hands the world. Each refuses bad input with an
/// InvalidArgument naming the field, the value and the rule; internal code trusts what passed.

#include <string_view>

#include "tumble/body.h"
#include "tumble/shape.h"
#include "tumble/world.h"

namespace tumble::checks {

void finiteVector(const Vec3& v, std::string_view what);
void unitQuaternion(const Quat& q, std::string_view what);
void nonNegative(Real value, std::string_view what);
void massProperties(const MassProperties& mass, std::string_view what);
void bodyDef(const BodyDef& def);
/// The contact properties of a material (friction, restitution, the friction lengths).
void surface(const Material& m, std::string_view what);
/// surface() and the density.
void material(const Material& m, std::string_view what);
void shapeDef(const ShapeDef& def, BodyType bodyType);
void timeStep(Real h, std::string_view what);
void worldDef(const WorldDef& def);
/// Whether a world asks for two counts of substeps (WorldDef::substeps > 1 with
/// SolverSettings::softSubsteps > 0), which it may not: one count per step, either the default
/// step's or the soft step's. Shared by the checks below and a restored checkpoint's.
constexpr bool twoSubstepCounts(int substeps, int softSubsteps) {
    return substeps > 1 && softSubsteps > 0;
}
/// Refuses twoSubstepCounts; `where` names the call.
void substepCounts(int substeps, int softSubsteps, std::string_view where);

}  // namespace tumble::checks
