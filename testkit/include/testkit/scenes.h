#pragma once
/// The scene kit: the pieces of scenes that the tests, the validation cases, the benchmarks and
/// the soak build alike, so that a ground or a stack is written once and means one thing.
///
/// Every builder creates its bodies and shapes in a fixed order and nothing else; a caller that
/// built the same scene by hand gets the same world bit for bit. Defaults are the engine's
/// (Material{}, BodyDef{}) unless a builder says otherwise.

#include <string>
#include <vector>

#include "tumble/lumped.h"
#include "tumble/tumble.h"

namespace tumble::testkit {

constexpr Real kGravity = 9.81;  ///< |g| of the kit's worlds (m/s^2)

/// Settings with sleeping off (a sleeping body would hide a slow drift or jitter): step
/// `timeStep` (s), gravity `gravity` (m/s^2), everything else the engine's default.
WorldDef quietWorld(Real timeStep = 1.0 / 60.0, const Vec3& gravity = Vec3(0, 0, -kGravity));

/// quietWorld without gravity.
WorldDef weightlessWorld(Real timeStep = 1.0 / 60.0);

/// Every world quietWorld and its callers build from now on runs the soft step with this many
/// substeps and this contact hertz (SolverSettings::softSubsteps, contactHertz; 0 substeps, the
/// default: the solver's default). For tumble-validate --soft-step, which checks the cases'
/// claims under it.
void forceSoftStep(int substeps, Real contactHertz = SolverSettings{}.contactHertz);
/// Puts forceSoftStep's settings into `settings` (nothing unless set).
void applyForcedSoftStep(SolverSettings& settings);

/// A step for the tests that hold the default step and the soft step to the same physics and
/// tolerances: 0 substeps is the default step, else the soft step at substeps x contactHertz.
struct StepChoice {
    int softSubsteps = 0;
    Real contactHertz = SolverSettings{}.contactHertz;  ///< (Hz)
};
/// The default step and the soft step at the settings its trade weighs (docs/ARCHITECTURE.md,
/// "The soft step"): 3 x 45 Hz and 4 x 30 Hz.
inline constexpr StepChoice kStepChoices[] = {{}, {3, 45}, {4, 30}};
/// For closed forms of the integrator (free fall, damping, a constant push): the default step and
/// the soft step at 2, 3 and 5 substeps, each at the hertz it caps at or below (a quarter of the
/// substep rate at 60 Hz: 30, 45, 75).
inline constexpr StepChoice kIntegratorStepChoices[] = {{}, {2, 30}, {3, 45}, {5, 45}};
/// Puts `step` into `settings`: the default step pins softSubsteps = 0, whatever the default.
void applyStep(SolverSettings& settings, const StepChoice& step);
/// The integrator's steps in one World::step of `step` (WorldDef::substeps = 1): the soft step's
/// substeps, else 1. Semi-implicit Euler's closed forms hold at h / this.
int integratorStepsPerStep(const StepChoice& step);
/// "Default" or "Soft<substeps>x<hertz>", for parameterised tests' names.
std::string stepName(const StepChoice& step);

/// The settings of the validation study's and the peers' stack scenes (DESIGN.md section 6):
/// quietWorld at `timeStep` with `iterations` PGS iterations.
WorldDef stackWorld(Real timeStep = 1.0 / 60.0, int iterations = 10);

/// A material of the validation cases: `friction`, `restitution` and a density of `density`
/// (kg/m^3; 1 by default, not the engine's 1000).
Material material(Real friction, Real restitution = 0, Real density = 1);

/// A static half-space whose surface passes through the origin with outward normal
/// `tilt * +Z`. Returns the static body.
BodyId addGround(World& world, const Material& surface = {}, const Quat& tilt = Quat::Identity());

/// A box on a new body made from `body` (pose, velocities, type...); a dynamic body takes its
/// mass from the material's density.
BodyId addBox(World& world, const BodyDef& body, const Vec3& halfExtents = Vec3::Constant(0.5),
              const Material& surface = {});

/// A dynamic box at rest at `position`, axis-aligned.
BodyId addBox(World& world, const Vec3& position, const Vec3& halfExtents = Vec3::Constant(0.5),
              const Material& surface = {});

/// A column of `count` unit cubes standing face to face on the ground (z = 0), each placed
/// exactly touching the one below. Bottom first.
std::vector<BodyId> buildStack(World& world, int count, const Material& surface = {});

/// A planar pyramid of unit cubes in the x-z plane: row j (from 0 at the ground) holds
/// base - j cubes, centred on x = 0, neighbours `gap` apart (m) so that cubes of one row touch
/// only the two below and above them. Rows touch exactly. Returns the cubes row by row and
/// appends their rows to `levels`.
std::vector<BodyId> buildPyramid(World& world, int base, Real gap, const Material& surface,
                                 std::vector<int>& levels);

/// Mixed bodies (spheres, boxes, capsules, cylinders in turn) raining in waves into a walled
/// square container: the soak's scene, the `rain` scene file's (demos/scenes/rain.json) at scale.
/// A wave is one horizontal layer of bodies `pitch` apart, spinning and falling at `speed`.
struct Rain {
    Real half = 2;      ///< inner half-width of the container (m), > pitch
    Real pitch = 0.4;   ///< spacing of the bodies of a wave, and of the first from the wall (m)
    Real height = 7;    ///< of a wave's centres (m)
    Real speed = 2;     ///< downward speed of a new body (m/s)
    Material material;  ///< of every body

    /// Bodies along each side of a wave.
    int perSide() const;
    /// Bodies in a full wave.
    int perWave() const;
    /// The static container: the floor (a half-space) and four walls 0.2 m thick and 6 m high,
    /// in that order, on one body.
    BodyId addContainer(World& world) const;
    /// The `index`th body of the rain (counting from 0 over all waves), in its wave's slot.
    BodyId addBody(World& world, int index) const;
};

/// The soak's material of the rain's bodies: friction 0.5, 700 kg/m^3, spinning and rolling
/// friction 2 mm.
Material soakMaterial();

/// The soak's pile under a net, small: 60 bodies of the rain, of soakMaterial(), in a 2 x 2 m
/// box, a wave every 30 steps, and a captureNet(10, 0.2) with the soak's drag (Drag::linear =
/// the node's mass) dropped on them from 3 m at step kNetStep.
struct PileUnderNet {
    static constexpr int kNetStep = 120;
    Rain rain{.half = 1, .material = soakMaterial()};
    std::vector<BodyId> bodies;  ///< the rain's, in the order made
    Lumped net;
    int netSide;   ///< nodes per side of the net
    Real netMesh;  ///< the net's mesh size (m)
    /// Adds the container; the net will have `side` x `side` nodes `mesh` apart.
    explicit PileUnderNet(World& world, int side = 10, Real mesh = 0.2);
    /// Adds what step `step` (counting from 0) brings; call before taking it.
    void feed(World& world, int step);
};

/// A square net of `nodesPerSide`^2 colliding nodes on tension-only threads (lumped.h), flat at
/// `center`, `meshSize` apart (m), with the soak's nodes (20 g, 3 cm), corners (0.5 kg) and
/// threads (axial rigidity 2000 N, damping 0.5); change the returned definition for others.
NetDef captureNet(int nodesPerSide, Real meshSize, const Vec3& center);

/// Steps `world` `steps` times; false as soon as a step fails (the world keeps its last valid
/// state).
bool simulate(World& world, int steps);

/// Steps `world` for `seconds` of simulated time, rounded to whole steps; false as soon as a
/// step fails.
bool simulateFor(World& world, Real seconds);

}  // namespace tumble::testkit
