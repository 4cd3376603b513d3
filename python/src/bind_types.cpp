// Plain types: ids, enums, definitions, shapes and what steps and queries report.
#include <functional>

#include "bindings.h"

namespace tumble::python {
namespace {

template <typename Id>
void bindId(py::module_& m, const char* name) {
    py::class_<Id>(m, name, "A value handle: checked by generation and world; the default is null.")
        .def(py::init<>())
        .def_readonly("index", &Id::index)
        .def_readonly("generation", &Id::generation)
        .def_readonly("world", &Id::world)
        .def("is_null", &Id::isNull)
        .def("__eq__", [](const Id& a, const Id& b) { return a == b; })
        .def("__hash__",
             [](const Id& id) {
                 return std::hash<std::uint64_t>{}((std::uint64_t{id.world} << 48) ^
                                                   (std::uint64_t{id.generation} << 32) ^ id.index);
             })
        .def("__repr__", [name](const Id& id) {
            return std::string(name) + "(index=" + std::to_string(id.index) +
                   ", generation=" + std::to_string(id.generation) + ")";
        });
}

void bindEnums(py::module_& m) {
    py::enum_<BodyType>(m, "BodyType")
        .value("Static", BodyType::Static)
        .value("Kinematic", BodyType::Kinematic)
        .value("Dynamic", BodyType::Dynamic);
    py::enum_<SpringFormulation>(m, "SpringFormulation")
        .value("Explicit", SpringFormulation::Explicit)
        .value("Implicit", SpringFormulation::Implicit);
    py::enum_<JointType>(m, "JointType")
        .value("Ball", JointType::Ball)
        .value("Hinge", JointType::Hinge)
        .value("Slider", JointType::Slider)
        .value("Fixed", JointType::Fixed)
        .value("Distance", JointType::Distance);
    py::enum_<ControlMode>(m, "ControlMode")
        .value("Position", ControlMode::Position)
        .value("Velocity", ControlMode::Velocity);
    py::enum_<FrictionModel>(m, "FrictionModel")
        .value("Coupled", FrictionModel::Coupled)
        .value("Box", FrictionModel::Box);
    py::enum_<Stabilisation>(m, "Stabilisation")
        .value("SplitImpulse", Stabilisation::SplitImpulse)
        .value("Baumgarte", Stabilisation::Baumgarte);
    py::enum_<SpringSolve>(m, "SpringSolve")
        .value("Direct", SpringSolve::Direct)
        .value("Iterative", SpringSolve::Iterative);
}

void bindShapes(py::module_& m) {
    Struct<Sphere>(m, "Sphere", "A sphere about the local origin.")
        .field("radius", &Sphere::radius, "(m), > 0");
    Struct<Capsule>(m, "Capsule", "Points within radius of the local z segment +-half_length.")
        .field("radius", &Capsule::radius, "(m), > 0")
        .field("half_length", &Capsule::halfLength, "(m), >= 0");
    Struct<Box>(m, "Box", "A box about the local origin.")
        .field("half_extents", &Box::halfExtents, "(m), each > 0");
    Struct<Cylinder>(m, "Cylinder", "A solid cylinder about local z.")
        .field("radius", &Cylinder::radius, "(m), > 0")
        .field("half_length", &Cylinder::halfLength, "(m), > 0");
    Struct<HalfSpace>(m, "HalfSpace", "The solid {x : normal . x <= offset}; static bodies only.")
        .field("normal", &HalfSpace::normal, "outward, unit")
        .field("offset", &HalfSpace::offset, "(m)");
    py::class_<ConvexHull>(m, "ConvexHull", "A convex hull of a point cloud (Qhull).")
        .def_static(
            "from_points",
            [](const Eigen::Matrix<Real, Eigen::Dynamic, 3, Eigen::RowMajor>& points) {
                std::vector<Vec3> v(static_cast<std::size_t>(points.rows()));
                for (Eigen::Index i = 0; i < points.rows(); ++i)
                    v[static_cast<std::size_t>(i)] = points.row(i).transpose();
                return ConvexHull::fromPoints(v);
            },
            py::arg("points"), "Hull of an (n, 3) array of points (m); >= 4 non-coplanar.")
        .def_property_readonly("vertices",
                               [](const ConvexHull& h) {
                                   Eigen::Matrix<Real, Eigen::Dynamic, 3, Eigen::RowMajor> out(
                                       h.data->vertices.size(), 3);
                                   for (std::size_t i = 0; i < h.data->vertices.size(); ++i)
                                       out.row(static_cast<Eigen::Index>(i)) =
                                           h.data->vertices[i].transpose();
                                   return out;
                               })
        .def_property_readonly("face_count",
                               [](const ConvexHull& h) { return h.data->faces.size(); });
}

void bindDefinitions(py::module_& m) {
    Struct<Transform>(m, "Transform", "A rigid transform: x_world = rotation * x_local + position.")
        .field("position", &Transform::position, "(m)")
        .field("rotation", &Transform::rotation, "unit quaternion (x, y, z, w)");
    Struct<Aabb>(m, "Aabb", "Axis-aligned box (m).")
        .field("lower", &Aabb::lower, "(m)")
        .field("upper", &Aabb::upper, "(m)");
    Struct<MassProperties>(m, "MassProperties",
                           "Mass, centre of mass and inertia in the body frame.")
        .field("mass", &MassProperties::mass, "(kg), > 0 for a dynamic body")
        .field("local_center", &MassProperties::localCenter, "centre of mass, body frame (m)")
        .field("inertia", &MassProperties::inertia, "about the centre of mass (kg m^2), 3x3 SPD");
    Struct<Material>(m, "Material", "Surface and bulk properties of a shape.")
        .field("friction", &Material::friction, "Coulomb coefficient, >= 0")
        .field("restitution", &Material::restitution, "in [0, 1]")
        .field("density", &Material::density, "(kg/m^3), > 0")
        .field("spinning_friction", &Material::spinningFriction, "torsional length (m), >= 0")
        .field("rolling_friction", &Material::rollingFriction, "rolling length (m), >= 0");
    Struct<CollisionFilter>(m, "CollisionFilter", "a, b collide when category & mask both ways.")
        .field("category", &CollisionFilter::category, "bits")
        .field("mask", &CollisionFilter::mask, "bits");
    Struct<QueryFilter>(m, "QueryFilter", "A query sees shapes whose category has a bit in mask.")
        .field("mask", &QueryFilter::mask, "bits");
    Struct<ShapeDef>(m, "ShapeDef", "A shape to attach to a body (World.create_shape).")
        .field("geometry", &ShapeDef::geometry,
               "Sphere, Capsule, Box, Cylinder, ConvexHull, HalfSpace, TriangleMesh or "
               "HeightField")
        .field("local_pose", &ShapeDef::localPose, "the shape's frame in the body frame")
        .field("material", &ShapeDef::material, "Material")
        .field("filter", &ShapeDef::filter, "CollisionFilter")
        .field("update_body_mass", &ShapeDef::updateBodyMass, "body mass from its shapes");
    Struct<BodyDef>(m, "BodyDef", "A body to create (World.create_body).")
        .field("type", &BodyDef::type, "BodyType")
        .field("position", &BodyDef::position, "body origin, world (m)")
        .field("orientation", &BodyDef::orientation, "body to world, unit (x, y, z, w)")
        .field("linear_velocity", &BodyDef::linearVelocity, "of the centre of mass (m/s)")
        .field("angular_velocity", &BodyDef::angularVelocity, "world frame (rad/s)")
        .field("mass", &BodyDef::mass, "MassProperties, dynamic bodies")
        .field("linear_damping", &BodyDef::linearDamping, "(1/s), >= 0")
        .field("angular_damping", &BodyDef::angularDamping, "(1/s), >= 0")
        .field("gravity_scale", &BodyDef::gravityScale, "multiplies the world's gravity")
        .field("user_data", &BodyDef::userData, "opaque integer")
        .field("allow_sleep", &BodyDef::allowSleep, "may the body fall asleep")
        .field("awake", &BodyDef::awake, "created awake")
        .field("fixed_rotation", &BodyDef::fixedRotation, "translation only");
    Struct<SpringDef>(m, "SpringDef", "A spring-damper (World.create_spring).")
        .field("body_a", &SpringDef::bodyA, "BodyId, valid")
        .field("body_b", &SpringDef::bodyB, "BodyId or null: local_anchor_b is a world point")
        .field("local_anchor_a", &SpringDef::localAnchorA, "A's body frame (m)")
        .field("local_anchor_b", &SpringDef::localAnchorB, "B's body frame or world (m)")
        .field("rest_length", &SpringDef::restLength, "L0 (m), > 0")
        .field("stiffness", &SpringDef::stiffness, "k (N/m), >= 0")
        .field("damping", &SpringDef::damping, "c (N s/m), >= 0")
        .field("tension_only", &SpringDef::tensionOnly, "a thread: never pushes")
        .field("formulation", &SpringDef::formulation, "SpringFormulation")
        .field("contact_radius", &SpringDef::contactRadius,
               "(m), >= 0; > 0: the segment touches static shapes as a capsule")
        .field("contact_friction", &SpringDef::contactFriction, "mu of the segment, >= 0");
    Struct<Drag>(m, "Drag", "Drag on the centre of mass: -(linear + quadratic |u|) u, u = P v.")
        .field("linear", &Drag::linear, "b1 (N s/m), >= 0")
        .field("quadratic", &Drag::quadratic, "b2 (N s^2/m^2), >= 0")
        .field("projection", &Drag::projection, "P, 3x3");
    m.def("axial_stiffness", &axialStiffness, py::arg("youngs_modulus"), py::arg("area"),
          py::arg("rest_length"), "k = E A / L0 (N/m) from E (Pa), A (m^2), L0 (m).");
}

void bindJointTypes(py::module_& m) {
    Struct<JointDef>(m, "JointDef", "A joint, world frame at creation (World.create_joint).")
        .field("type", &JointDef::type, "JointType")
        .field("body_a", &JointDef::bodyA, "BodyId, valid")
        .field("body_b", &JointDef::bodyB, "BodyId or null (the world)")
        .field("anchor", &JointDef::anchor, "world (m)")
        .field("anchor_b", &JointDef::anchorB, "distance joints: B's end, world (m)")
        .field("axis", &JointDef::axis, "hinge axis / slider direction, world")
        .field("length", &JointDef::length, "distance joints (m); < 0: from the anchors")
        .field("rope", &JointDef::rope, "distance joints: one-sided")
        .field("enable_limit", &JointDef::enableLimit, "")
        .field("lower", &JointDef::lower, "(rad or m)")
        .field("upper", &JointDef::upper, "(rad or m)")
        .field("enable_motor", &JointDef::enableMotor, "")
        .field("motor_speed", &JointDef::motorSpeed, "(rad/s or m/s)")
        .field("max_motor_force", &JointDef::maxMotorForce, "(N m or N), >= 0")
        .field("break_force", &JointDef::breakForce, "(N), > 0; inf: unbreakable")
        .field("break_torque", &JointDef::breakTorque, "(N m), > 0; inf: unbreakable")
        .field("collide_connected", &JointDef::collideConnected, "");
    Struct<JointState>(m, "JointState", "What a joint reports.")
        .field("force", &JointState::force, "on B, last step (N)")
        .field("torque", &JointState::torque, "on B, last step (N m)")
        .field("position", &JointState::position, "angle (rad) or translation/distance (m)")
        .field("speed", &JointState::speed, "(rad/s or m/s)")
        .field("broken", &JointState::broken, "")
        .field("anchor_a", &JointState::anchorA, "(m)")
        .field("anchor_b", &JointState::anchorB, "(m)")
        .field("axis", &JointState::axis, "unit");
    Struct<ControllerDef>(m, "ControllerDef", "PD/PID controller of a hinge or slider.")
        .field("mode", &ControllerDef::mode, "ControlMode")
        .field("target", &ControllerDef::target, "(rad or m)")
        .field("target_velocity", &ControllerDef::targetVelocity, "(rad/s or m/s)")
        .field("kp", &ControllerDef::kp, ">= 0 (N m/rad)")
        .field("ki", &ControllerDef::ki, ">= 0 (N m/(rad s))")
        .field("kd", &ControllerDef::kd, ">= 0 (N m s/rad)")
        .field("max_force", &ControllerDef::maxForce, "cap (N m or N), > 0");
    Struct<ControllerState>(m, "ControllerState", "What a controller did in the last step.")
        .field("error", &ControllerState::error, "")
        .field("integral", &ControllerState::integral, "")
        .field("output", &ControllerState::output, "(N m or N)");
    Struct<SpringState>(m, "SpringState", "What a spring reports.")
        .field("length", &SpringState::length, "(m)")
        .field("tension", &SpringState::tension, "(N), > 0 pulls")
        .field("slack", &SpringState::slack, "");
}

void bindLumpedTypes(py::module_& m) {
    Struct<ThreadDef>(m, "ThreadDef", "Threads of a string or net.")
        .field("axial_rigidity", &ThreadDef::axialRigidity, "E A (N), > 0")
        .field("damping", &ThreadDef::damping, "(N s/m), >= 0")
        .field("tension_only", &ThreadDef::tensionOnly, "")
        .field("formulation", &ThreadDef::formulation, "SpringFormulation")
        .field("collide", &ThreadDef::collide, "segments touch static shapes");
    Struct<NodeDef>(m, "NodeDef", "Nodes of a string or net.")
        .field("mass", &NodeDef::mass, "(kg), > 0")
        .field("radius", &NodeDef::radius, "(m), > 0")
        .field("collide", &NodeDef::collide, "give each node a sphere")
        .field("fixed_rotation", &NodeDef::fixedRotation, "point masses")
        .field("material", &NodeDef::material, "Material")
        .field("filter", &NodeDef::filter, "CollisionFilter");
    Struct<StringDef>(m, "StringDef", "A string of nodes from start to end.")
        .field("start", &StringDef::start, "(m)")
        .field("end", &StringDef::end, "(m)")
        .field("count", &StringDef::count, "nodes")
        .field("fixed_start", &StringDef::fixedStart, "")
        .field("fixed_end", &StringDef::fixedEnd, "")
        .field("rest_length_ratio", &StringDef::restLengthRatio, "> 0")
        .field("velocity", &StringDef::velocity, "(m/s)")
        .field("node", &StringDef::node, "NodeDef")
        .field("thread", &StringDef::thread, "ThreadDef");
    Struct<NetDef>(m, "NetDef", "An n x m square net.")
        .field("rows", &NetDef::rows, ">= 2")
        .field("columns", &NetDef::columns, ">= 2")
        .field("mesh_size", &NetDef::meshSize, "(m), > 0")
        .field("center", &NetDef::center, "(m)")
        .field("orientation", &NetDef::orientation, "unit (x, y, z, w)")
        .field("node", &NetDef::node, "NodeDef")
        .field("corner_mass", &NetDef::cornerMass, "(kg), 0 keeps node.mass")
        .field("thread", &NetDef::thread, "ThreadDef")
        .field("velocity", &NetDef::velocity, "(m/s)")
        .field("spread_speed", &NetDef::spreadSpeed, "(m/s)");
    Struct<Lumped>(m, "Lumped", "What a generator made: nodes, threads, corners.")
        .field("nodes", &Lumped::nodes, "BodyIds in order")
        .field("threads", &Lumped::threads, "SpringIds")
        .field("corners", &Lumped::corners, "nets: 4 BodyIds");
}

void bindSettings(py::module_& m) {
    Struct<SolverSettings>(m, "SolverSettings", "The constraint solver's settings.")
        .field("iterations", &SolverSettings::iterations, ">= 1")
        .field("relax_iterations", &SolverSettings::relaxIterations, ">= 0")
        .field("link_iterations", &SolverSettings::linkIterations,
               ">= 1: at least these many in a solve with springs, joints or thread contacts")
        .field("link_relax_iterations", &SolverSettings::linkRelaxIterations, ">= 0: likewise")
        .field("tolerance", &SolverSettings::tolerance, "(m/s), >= 0")
        .field("relaxation", &SolverSettings::relaxation, "in (0, 2)")
        .field("friction", &SolverSettings::friction, "FrictionModel")
        .field("stabilisation", &SolverSettings::stabilisation, "Stabilisation")
        .field("baumgarte", &SolverSettings::baumgarte, "in [0, 1]")
        .field("split_impulse_factor", &SolverSettings::splitImpulseFactor, "in (0, 1]")
        .field("slop", &SolverSettings::slop, "(m), >= 0")
        .field("restitution_threshold", &SolverSettings::restitutionThreshold, "(m/s), >= 0")
        .field("warm_start", &SolverSettings::warmStart, "")
        .field("spring_solve", &SolverSettings::springSolve, "SpringSolve")
        .field("project_springs", &SolverSettings::projectSprings, "")
        .field("joint_geometric_stiffness", &SolverSettings::jointGeometricStiffness, "")
        .field("joint_solve", &SolverSettings::jointSolve, "SpringSolve")
        .field("friction_anchors", &SolverSettings::frictionAnchors,
               "sticking contacts held in place (split impulse only)")
        .field("soft_substeps", &SolverSettings::softSubsteps,
               ">= 0; > 0: the soft step with this many substeps")
        .field("contact_hertz", &SolverSettings::contactHertz, "soft step (Hz), > 0")
        .field("contact_damping_ratio", &SolverSettings::contactDampingRatio, "soft step, >= 0")
        .field("max_push_out_speed", &SolverSettings::maxPushOutSpeed, "soft step (m/s), > 0");
    Struct<WorldDef>(m, "WorldDef", "World settings.")
        .field("gravity", &WorldDef::gravity, "(m/s^2)")
        .field("time_step", &WorldDef::timeStep, "h (s), > 0")
        .field("max_steps_per_advance", &WorldDef::maxStepsPerAdvance, ">= 1")
        .field("substeps", &WorldDef::substeps, ">= 1")
        .field("contact_margin", &WorldDef::contactMargin, "(m), >= 0")
        .field("aabb_margin", &WorldDef::aabbMargin, "(m), >= 0")
        .field("solver", &WorldDef::solver, "SolverSettings")
        .field("enable_sleep", &WorldDef::enableSleep, "")
        .field("linear_sleep_velocity", &WorldDef::linearSleepVelocity, "(m/s)")
        .field("angular_sleep_velocity", &WorldDef::angularSleepVelocity, "(rad/s)")
        .field("time_to_sleep", &WorldDef::timeToSleep, "(s)")
        .field("impact_speed_threshold", &WorldDef::impactSpeedThreshold, "(m/s)");
    Struct<SolverStats>(m, "SolverStats", "What the last solve reports.")
        .field("iterations", &SolverStats::iterations, "")
        .field("max_residual", &SolverStats::maxResidual, "(m/s)")
        .field("deepest_penetration", &SolverStats::deepestPenetration, "(m)");
    Struct<Profile>(m, "Profile", "Wall-clock time of the last step's stages (s).")
        .field("forces", &Profile::forces, "(s)")
        .field("broadphase", &Profile::broadphase, "(s)")
        .field("narrowphase", &Profile::narrowphase, "(s)")
        .field("islands", &Profile::islands, "(s)")
        .field("solve", &Profile::solve, "(s)")
        .field("integrate", &Profile::integrate, "(s)")
        .field("finalize", &Profile::finalize, "(s)")
        .field("bounds", &Profile::bounds, "(s)")
        .field("sleep", &Profile::sleep, "(s)")
        .field("total", &Profile::total, "(s)");
}

void bindReports(py::module_& m) {
    py::enum_<StepStatus::Code>(m, "StepCode")
        .value("Ok", StepStatus::Code::Ok)
        .value("NonFiniteState", StepStatus::Code::NonFiniteState)
        .value("Overflow", StepStatus::Code::Overflow);
    Struct<StepStatus>(m, "StepStatus",
                       "What a step reports; a failed step left the world as before.")
        .field("code", &StepStatus::code, "StepCode")
        .field("body", &StepStatus::body, "the first offending body")
        .field("spring", &StepStatus::spring, "the spring that drove it, or null")
        .cls()
        .def_property_readonly("ok", &StepStatus::ok)
        .def("__bool__", &StepStatus::ok);
    Struct<AdvanceResult>(m, "AdvanceResult", "What advance() did.")
        .field("steps", &AdvanceResult::steps, "whole steps taken")
        .field("fraction", &AdvanceResult::fraction, "leftover / h, in [0, 1)")
        .field("dropped_time", &AdvanceResult::droppedTime, "(s)")
        .field("status", &AdvanceResult::status, "StepStatus of the last step");
    Struct<RayCastHit>(m, "RayCastHit", "A ray cast's hit.")
        .field("shape", &RayCastHit::shape, "")
        .field("body", &RayCastHit::body, "")
        .field("fraction", &RayCastHit::fraction, "point = origin + fraction * translation")
        .field("point", &RayCastHit::point, "(m)")
        .field("normal", &RayCastHit::normal, "unit");
    py::class_<Contact>(m, "Contact", "A shape pair of the last step, with its manifold.")
        .def_readonly("shape_a", &Contact::shapeA)
        .def_readonly("shape_b", &Contact::shapeB)
        .def_readonly("body_a", &Contact::bodyA)
        .def_readonly("body_b", &Contact::bodyB)
        .def_property_readonly(
            "normal", [](const Contact& c) { return c.manifold.normal; }, "from A to B, unit")
        .def_property_readonly("point_count",
                               [](const Contact& c) { return c.manifold.pointCount; })
        .def_property_readonly(
            "points",
            [](const Contact& c) {
                Eigen::Matrix<Real, Eigen::Dynamic, 3, Eigen::RowMajor> p(c.manifold.pointCount, 3);
                for (int k = 0; k < c.manifold.pointCount; ++k)
                    p.row(k) = c.manifold.points[static_cast<std::size_t>(k)].position.transpose();
                return p;
            },
            "(point_count, 3) world positions (m)")
        .def_property_readonly(
            "separations",
            [](const Contact& c) {
                std::vector<Real> d;
                for (int k = 0; k < c.manifold.pointCount; ++k)
                    d.push_back(c.manifold.points[static_cast<std::size_t>(k)].separation);
                return d;
            },
            "(m), negative when penetrating")
        .def_property_readonly(
            "normal_impulses",
            [](const Contact& c) {
                return std::vector<Real>(c.normalImpulse.begin(),
                                         c.normalImpulse.begin() + c.manifold.pointCount);
            },
            "of the last solve (N s)");
    Struct<ContactEvent>(m, "ContactEvent", "Two shapes began or stopped touching.")
        .field("shape_a", &ContactEvent::shapeA, "")
        .field("shape_b", &ContactEvent::shapeB, "")
        .field("body_a", &ContactEvent::bodyA, "")
        .field("body_b", &ContactEvent::bodyB, "");
    Struct<ImpactEvent>(m, "ImpactEvent", "Two shapes met at least at the impact threshold.")
        .field("shape_a", &ImpactEvent::shapeA, "")
        .field("shape_b", &ImpactEvent::shapeB, "")
        .field("body_a", &ImpactEvent::bodyA, "")
        .field("body_b", &ImpactEvent::bodyB, "")
        .field("point", &ImpactEvent::point, "(m)")
        .field("normal", &ImpactEvent::normal, "A to B, unit")
        .field("approach_speed", &ImpactEvent::approachSpeed, "(m/s)")
        .field("normal_impulse", &ImpactEvent::normalImpulse, "(N s)");
    Struct<JointBreakEvent>(m, "JointBreakEvent", "A joint broke.")
        .field("joint", &JointBreakEvent::joint, "")
        .field("body_a", &JointBreakEvent::bodyA, "")
        .field("body_b", &JointBreakEvent::bodyB, "")
        .field("force", &JointBreakEvent::force, "(N)")
        .field("torque", &JointBreakEvent::torque, "(N m)");
    Struct<SleepEvent>(m, "SleepEvent", "A body fell asleep or woke.")
        .field("body", &SleepEvent::body, "")
        .field("asleep", &SleepEvent::asleep, "");
    py::enum_<Warning::Kind>(m, "WarningKind")
        .value("MassRatio", Warning::Kind::MassRatio)
        .value("SmallerThanSlop", Warning::Kind::SmallerThanSlop)
        .value("ExplicitSpringUnstable", Warning::Kind::ExplicitSpringUnstable);
    Struct<Warning>(m, "Warning", "Legal input the engine handles poorly.")
        .field("kind", &Warning::kind, "WarningKind")
        .field("body_a", &Warning::bodyA, "")
        .field("body_b", &Warning::bodyB, "")
        .field("spring", &Warning::spring, "")
        .field("joint", &Warning::joint, "")
        .field("value", &Warning::value, "")
        .field("limit", &Warning::limit, "")
        .cls()
        .def("describe", [](const Warning& w) { return describe(w); })
        .def("__str__", [](const Warning& w) { return describe(w); });
}

}  // namespace

void bindIds(py::module_& m) {
    bindId<BodyId>(m, "BodyId");
    bindId<ShapeId>(m, "ShapeId");
    bindId<SpringId>(m, "SpringId");
    bindId<JointId>(m, "JointId");
}

void bindTypes(py::module_& m) {
    bindEnums(m);
    bindShapes(m);
    bindDefinitions(m);
    bindJointTypes(m);
    bindLumpedTypes(m);
    bindSettings(m);
    bindReports(m);
    m.def("mass_of", &massOf, py::arg("shape"), py::arg("density"),
          "Mass properties of the solid shape at density (kg/m^3), in its frame.");
    m.def("bounds_of", &boundsOf, py::arg("shape"), py::arg("pose") = Transform{},
          "Tight bounding box of the shape at pose (m).");
}

}  // namespace tumble::python
