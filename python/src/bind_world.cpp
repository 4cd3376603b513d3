// The World: bodies, shapes, springs, joints, control, queries, stepping, events, checkpoints.
#include <optional>
#include <span>

#include "bindings.h"
#include "tumble/checkpoint.h"
#include "tumble/lumped.h"

namespace tumble::python {
namespace {

// A World member as a method of PyWorld, with the member's own signature.
template <typename R, typename... A>
auto wrap(R (World::*f)(A...) const) {
    return [f](const PyWorld& w, A... a) -> R { return (w.world.*f)(a...); };
}
template <typename R, typename... A>
auto wrap(R (World::*f)(A...)) {
    return [f](PyWorld& w, A... a) -> R { return (w.world.*f)(a...); };
}
template <typename T>
std::vector<T> list(std::span<const T> items) {
    return {items.begin(), items.end()};
}

void bindBodies(py::class_<PyWorld>& c) {
    const auto body = py::arg("body");
    c.def(
         "create_body",
         [](PyWorld& w, const BodyDef& def) {
             return w.restructure("create_body", [&] { return w.world.createBody(def); });
         },
         py::arg("def") = BodyDef{},
         "Creates a body (BodyDef); refuses bad input (InvalidArgument).")
        .def(
            "destroy_body",
            [](PyWorld& w, BodyId id) {
                w.restructure("destroy_body", [&] { w.world.destroyBody(id); });
            },
            body)
        .def("is_valid", wrap(static_cast<bool (World::*)(BodyId) const>(&World::isValid)), body)
        .def("is_valid", wrap(static_cast<bool (World::*)(ShapeId) const>(&World::isValid)),
             py::arg("shape"))
        .def("is_valid", wrap(static_cast<bool (World::*)(SpringId) const>(&World::isValid)),
             py::arg("spring"))
        .def("is_valid", wrap(static_cast<bool (World::*)(JointId) const>(&World::isValid)),
             py::arg("joint"))
        .def_property_readonly("body_count", wrap(&World::bodyCount))
        .def("bodies", wrap(&World::bodies),
             "Every body in dense order (the order of the state views).")
        .def("body_shapes", wrap(&World::bodyShapes), body)
        .def("body_joints", wrap(&World::bodyJoints), body)
        .def("body_springs", wrap(&World::bodySprings), body)
        .def("body_type", wrap(&World::bodyType), body)
        .def("position", wrap(&World::position), body, "Body origin (m).")
        .def("orientation", wrap(&World::orientation), body, "(x, y, z, w)")
        .def("transform", wrap(&World::transform), body)
        .def("center_of_mass", wrap(&World::centerOfMass), body, "(m), world")
        .def("linear_velocity", wrap(&World::linearVelocity), body, "(m/s)")
        .def("angular_velocity", wrap(&World::angularVelocity), body, "(rad/s)")
        .def("velocity_at", wrap(&World::velocityAt), body, py::arg("world_point"), "(m/s)")
        .def("mass_properties", wrap(&World::massProperties), body)
        .def("user_data", wrap(&World::userData), body)
        .def("linear_damping", wrap(&World::linearDamping), body, "(1/s)")
        .def("angular_damping", wrap(&World::angularDamping), body, "(1/s)")
        .def("interpolated_transform", wrap(&World::interpolatedTransform), body,
             py::arg("fraction"), "Pose between the previous (0) and current (1) step.")
        .def("angular_momentum", wrap(&World::angularMomentum), body, "(kg m^2/s)")
        .def("kinetic_energy",
             wrap(static_cast<Real (World::*)(BodyId) const>(&World::kineticEnergy)), body, "(J)")
        .def("kinetic_energy", wrap(static_cast<Real (World::*)() const>(&World::kineticEnergy)),
             "(J), all dynamic bodies")
        .def("set_transform", wrap(&World::setTransform), body, py::arg("position"),
             py::arg("orientation"))
        .def("set_linear_velocity", wrap(&World::setLinearVelocity), body, py::arg("velocity"),
             "(m/s)")
        .def("set_angular_velocity", wrap(&World::setAngularVelocity), body, py::arg("velocity"),
             "(rad/s)")
        .def("set_mass_properties", wrap(&World::setMassProperties), body, py::arg("mass"))
        .def("set_body_type", wrap(&World::setBodyType), body, py::arg("type"))
        .def("set_linear_damping", wrap(&World::setLinearDamping), body, py::arg("damping"),
             "(1/s)")
        .def("set_angular_damping", wrap(&World::setAngularDamping), body, py::arg("damping"),
             "(1/s)")
        .def("set_user_data", wrap(&World::setUserData), body, py::arg("user_data"))
        .def("is_awake", wrap(&World::isAwake), body)
        .def("set_awake", wrap(&World::setAwake), body, py::arg("awake"))
        .def_property_readonly("awake_body_count", wrap(&World::awakeBodyCount))
        .def("apply_force", wrap(&World::applyForce), body, py::arg("force"),
             py::arg("world_point"), "(N) at (m), next step")
        .def("apply_force_to_center", wrap(&World::applyForceToCenter), body, py::arg("force"),
             "(N)")
        .def("apply_torque", wrap(&World::applyTorque), body, py::arg("torque"), "(N m)")
        .def("apply_linear_impulse", wrap(&World::applyLinearImpulse), body, py::arg("impulse"),
             py::arg("world_point"), "(N s)")
        .def("apply_angular_impulse", wrap(&World::applyAngularImpulse), body, py::arg("impulse"),
             "(N m s)");
}

void bindShapesAndQueries(py::class_<PyWorld>& c) {
    const auto shape = py::arg("shape");
    const auto filter = py::arg("filter") = QueryFilter{};
    c.def("create_shape", wrap(&World::createShape), py::arg("body"), py::arg("def") = ShapeDef{})
        .def("destroy_shape", wrap(&World::destroyShape), shape)
        .def("shape_body", wrap(&World::shapeBody), shape)
        .def("shape_def", wrap(&World::shapeDef), shape)
        .def("set_shape_material", wrap(&World::setShapeMaterial), shape, py::arg("material"))
        .def("set_shape_filter", wrap(&World::setShapeFilter), shape, py::arg("filter"))
        .def("shape_transform", wrap(&World::shapeTransform), shape)
        .def("shape_bounds", wrap(&World::shapeBounds), shape, "(m)")
        .def(
            "contacts", [](const PyWorld& w) { return list(w.world.contacts()); },
            "The shape pairs of the last step (copies), deterministic order.")
        .def("cast_ray_closest", wrap(&World::castRayClosest), py::arg("origin"),
             py::arg("translation"), filter,
             "First hit of origin + t translation, t in [0, 1] (m), or None.")
        .def("cast_ray_all", wrap(&World::castRayAll), py::arg("origin"), py::arg("translation"),
             filter, "Every hit, nearest first.")
        .def("overlap_aabb", wrap(&World::overlapAabb), py::arg("box"), filter)
        .def("overlap_shape", wrap(&World::overlapShape), shape, py::arg("pose"), filter,
             "Shapes touching `shape` (a Sphere, Box, ...) placed at pose.")
        .def("closest_point", wrap(&World::closestPoint), shape, py::arg("point"), "(m)");
}

void bindSpringsAndJoints(py::class_<PyWorld>& c) {
    c.def("create_spring", wrap(&World::createSpring), py::arg("def"))
        .def("destroy_spring", wrap(&World::destroySpring), py::arg("spring"))
        .def_property_readonly("spring_count", wrap(&World::springCount))
        .def("spring_def", wrap(&World::springDef), py::arg("spring"))
        .def("spring_state", wrap(&World::springState), py::arg("spring"))
        .def("spring_potential_energy", wrap(&World::springPotentialEnergy), "(J)")
        .def("set_drag", wrap(&World::setDrag), py::arg("body"), py::arg("drag"))
        .def("drag", wrap(&World::drag), py::arg("body"))
        .def("create_joint", wrap(&World::createJoint), py::arg("def"))
        .def("destroy_joint", wrap(&World::destroyJoint), py::arg("joint"))
        .def_property_readonly("joint_count", wrap(&World::jointCount))
        .def("joint_def", wrap(&World::jointDef), py::arg("joint"))
        .def("joint_state", wrap(&World::jointState), py::arg("joint"))
        .def("set_joint_motor", wrap(&World::setJointMotor), py::arg("joint"), py::arg("enable"),
             py::arg("speed"), py::arg("max_force"), "speed (rad/s or m/s), max_force (N m or N)")
        .def("set_joint_controller", wrap(&World::setJointController), py::arg("joint"),
             py::arg("def"))
        .def("set_joint_controller_target", wrap(&World::setJointControllerTarget),
             py::arg("joint"), py::arg("target"), py::arg("target_velocity") = 0.0)
        .def("clear_joint_controller", wrap(&World::clearJointController), py::arg("joint"))
        .def("joint_controller", wrap(&World::jointController), py::arg("joint"))
        .def("joint_controller_state", wrap(&World::jointControllerState), py::arg("joint"))
        .def(
            "create_string",
            [](PyWorld& w, const StringDef& def) {
                return w.restructure("create_string", [&] { return createString(w.world, def); });
            },
            py::arg("def") = StringDef{})
        .def(
            "create_net",
            [](PyWorld& w, const NetDef& def) {
                return w.restructure("create_net", [&] { return createNet(w.world, def); });
            },
            py::arg("def") = NetDef{});
}

// step() and advance() release the GIL; the pre-step callback takes it back.
void bindStepping(py::class_<PyWorld>& c) {
    c.def(
         "step",
         [](PyWorld& w) {
             py::gil_scoped_release release;
             return w.world.step();
         },
         "One fixed step. Never raises for a failed step: returns its StepStatus (the world is "
         "left as before the step); see also step_checked.")
        .def(
            "advance",
            [](PyWorld& w, Real frameTime) {
                py::gil_scoped_release release;
                return w.world.advance(frameTime);
            },
            py::arg("frame_time"), "Whole steps for frame_time (s); AdvanceResult.")
        .def(
            "set_pre_step_callback",
            [](PyWorld& w, py::object fn) {
                if (fn.is_none()) {
                    w.world.setPreStepCallback({});
                    return;
                }
                PyWorld* self = &w;
                w.world.setPreStepCallback([fn, self](World&, Real time) {
                    py::gil_scoped_acquire acquire;
                    fn(py::cast(self, py::return_value_policy::reference), time);
                });
            },
            py::arg("callback"),
            "callback(world, time) at the start of every step; None removes it.")
        .def_property_readonly("settings", wrap(&World::settings))
        .def("set_gravity", wrap(&World::setGravity), py::arg("gravity"), "(m/s^2)")
        .def("set_time_step", wrap(&World::setTimeStep), py::arg("time_step"), "(s)")
        .def("set_max_steps_per_advance", wrap(&World::setMaxStepsPerAdvance), py::arg("steps"))
        .def("set_solver_settings", wrap(&World::setSolverSettings), py::arg("settings"))
        .def_property_readonly("time", wrap(&World::time), "simulated time (s)")
        .def_property_readonly("step_count", wrap(&World::stepCount))
        .def_property_readonly("profile", wrap(&World::profile))
        .def_property_readonly("solver_stats", wrap(&World::solverStats))
        .def("warnings", [](const PyWorld& w) { return list(w.world.warnings()); })
        .def_property_readonly("dropped_warnings", wrap(&World::droppedWarnings))
        .def("clear_warnings", wrap(&World::clearWarnings))
        .def("contact_begin_events",
             [](const PyWorld& w) { return list(w.world.contactBeginEvents()); })
        .def("contact_end_events",
             [](const PyWorld& w) { return list(w.world.contactEndEvents()); })
        .def("impact_events", [](const PyWorld& w) { return list(w.world.impactEvents()); })
        .def("joint_break_events",
             [](const PyWorld& w) { return list(w.world.jointBreakEvents()); })
        .def("sleep_events", [](const PyWorld& w) { return list(w.world.sleepEvents()); });
}

void bindCheckpoints(py::class_<PyWorld>& c) {
    c.def(
         "checkpoint_bytes",
         [](const PyWorld& w) {
             const std::vector<std::uint8_t> b = checkpointBytes(w.world);
             return py::bytes(reinterpret_cast<const char*>(b.data()), b.size());
         },
         "The whole state as bytes (the checkpoint file's contents).")
        .def(
            "restore_checkpoint",
            [](PyWorld& w, const py::bytes& data, const std::string& source) {
                const std::string_view s = data;
                w.restructure("restore_checkpoint", [&] {
                    restoreCheckpoint(w.world,
                                      {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()},
                                      source);
                });
            },
            py::arg("data"), py::arg("source") = "checkpoint")
        .def(
            "save_checkpoint",
            [](const PyWorld& w, const std::string& file) { saveCheckpoint(w.world, file); },
            py::arg("file"))
        .def(
            "load_checkpoint",
            [](PyWorld& w, const std::string& file) {
                w.restructure("load_checkpoint", [&] { loadCheckpoint(w.world, file); });
            },
            py::arg("file"));
}

}  // namespace

void bindWorld(py::module_& m) {
    py::class_<PyWorld> c(m, "World", "Owner of every body, and the fixed-step stepper.");
    c.def(py::init<const WorldDef&>(), py::arg("def") = WorldDef{});
    bindBodies(c);
    bindShapesAndQueries(c);
    bindSpringsAndJoints(c);
    bindStepping(c);
    bindCheckpoints(c);
    bindState(m, c);
}

}  // namespace tumble::python
