"""A test per area of the API: definitions, shapes, springs, drag, joints, motors, controllers,
generators, stepping, events, queries, warnings, errors."""
import math
import threading

import numpy as np
import pytest

import tumble
from conftest import add_ball, ground_world


def test_definitions_take_keywords_with_the_cpp_defaults():
    d = tumble.WorldDef()
    assert d.time_step == pytest.approx(1 / 60) and list(d.gravity) == [0, 0, -9.81]
    assert tumble.WorldDef(substeps=4).substeps == 4
    assert tumble.Material().friction == 0.5 and tumble.JointDef().length == -1
    assert math.isinf(tumble.ControllerDef().max_force)
    with pytest.raises(TypeError, match="no field"):
        tumble.BodyDef(velocity=[1, 0, 0])


def test_bad_input_raises_invalid_argument_with_the_cpp_message():
    world = tumble.World()
    with pytest.raises(tumble.InvalidArgument) as caught:
        world.create_body(tumble.BodyDef(orientation=[0, 0, 0, 2]))
    assert isinstance(caught.value, ValueError) and "orientation" in str(caught.value)
    with pytest.raises(tumble.InvalidArgument, match="timeStep"):
        tumble.World(tumble.WorldDef(time_step=0))
    b = world.create_body()
    world.destroy_body(b)
    with pytest.raises(tumble.InvalidArgument):
        world.position(b)


def test_every_shape_attaches_and_sets_the_mass():
    world, _ = ground_world()
    hull = tumble.ConvexHull.from_points(np.array(
        [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float))
    geometries = [tumble.Sphere(radius=0.5), tumble.Capsule(radius=0.2, half_length=0.3),
                  tumble.Box(half_extents=[0.5, 0.5, 0.5]), tumble.Cylinder(radius=0.3, half_length=0.2),
                  hull]
    for k, geometry in enumerate(geometries):
        body = world.create_body(tumble.BodyDef(position=[3 * k, 0, 2]))
        shape = world.create_shape(body, tumble.ShapeDef(geometry=geometry))
        expected = tumble.mass_of(geometry, 1000).mass
        assert world.mass_properties(body).mass == pytest.approx(expected)
        assert world.shape_body(shape) == body
    assert world.mass_properties(world.bodies()[3]).mass == pytest.approx(1000.0)  # the unit box
    assert hull.vertices.shape == (4, 3) and hull.face_count == 4
    with pytest.raises(tumble.InvalidArgument):
        world.create_shape(world.bodies()[1], tumble.ShapeDef(geometry=tumble.HalfSpace()))


def test_a_spring_holds_a_mass_at_its_static_stretch():
    world = tumble.World()
    mass, k = 2.0, 400.0
    bob = world.create_body(tumble.BodyDef(position=[0, 0, -1],
                                           mass=tumble.MassProperties(mass=mass)))
    spring = world.create_spring(tumble.SpringDef(body_a=bob, local_anchor_b=[0, 0, 0],
                                                  rest_length=1, stiffness=k, damping=20))
    for _ in range(600):
        world.step()
    stretch = mass * 9.81 / k
    assert world.position(bob)[2] == pytest.approx(-1 - stretch, abs=1e-4)
    assert world.spring_state(spring).tension == pytest.approx(mass * 9.81, rel=1e-3)
    assert world.spring_count == 1


def test_drag_gives_the_terminal_speed():
    world = tumble.World()
    b = world.create_body(tumble.BodyDef(mass=tumble.MassProperties(mass=1.0)))
    world.set_drag(b, tumble.Drag(linear=2.0))
    for _ in range(600):
        world.step()
    assert world.linear_velocity(b)[2] == pytest.approx(-9.81 / 2.0, rel=1e-3)
    assert world.drag(b).linear == 2.0


def test_a_hinge_motor_and_a_controller_drive_the_joint():
    # No sleeping: the overdamped approach is slower than the sleep thresholds.
    world = tumble.World(tumble.WorldDef(gravity=[0, 0, 0], enable_sleep=False))
    wheel = world.create_body(tumble.BodyDef(position=[0, 0, 0]))
    joint = world.create_joint(tumble.JointDef(type=tumble.JointType.Hinge, body_a=wheel,
                                               axis=[0, 0, 1]))
    world.set_joint_motor(joint, True, 2.0, 100.0)
    for _ in range(30):
        world.step()
    assert world.joint_state(joint).speed == pytest.approx(2.0, rel=1e-6)
    world.set_joint_motor(joint, False, 0.0, 0.0)
    world.set_angular_velocity(wheel, [0, 0, 0])
    world.set_joint_controller(joint, tumble.ControllerDef(target=0.5, kp=20, kd=8))
    for _ in range(600):
        world.step()
    assert world.joint_state(joint).position == pytest.approx(0.5, abs=1e-3)
    assert world.joint_controller(joint).kp == 20
    assert world.joint_controller_state(joint).error == pytest.approx(0, abs=1e-3)
    world.clear_joint_controller(joint)
    assert world.joint_controller(joint) is None
    with pytest.raises(tumble.InvalidArgument):
        world.set_joint_controller(joint, tumble.ControllerDef(kp=-1))


def test_a_string_hangs_from_its_fixed_start():
    world = tumble.World()
    string = world.create_string(tumble.StringDef(start=[0, 0, 0], end=[1, 0, 0], count=10))
    assert len(string.nodes) == 10 and len(string.threads) == 10
    for _ in range(240):
        world.step()
    tip = world.view("centers", string.nodes)[-1]
    assert tip[2] < -0.5 and np.linalg.norm(tip) <= 1.0 + 0.05


def test_advance_interpolation_and_a_failed_step():
    world = tumble.World()
    b = world.create_body(tumble.BodyDef(position=[0, 0, 0]))
    result = world.advance(2.5 / 60)
    assert result.steps == 2 and result.fraction == pytest.approx(0.5)
    mid = world.interpolated_transform(b, 0.5).position[2]
    assert world.position(b)[2] < mid < world.interpolated_transform(b, 0.0).position[2]
    box = world.create_body(tumble.BodyDef(position=[0, 0, 10]))
    world.create_shape(box, tumble.ShapeDef(geometry=tumble.Box()))
    world.set_linear_velocity(box, [1e308, 0, 0])
    for _ in range(1000):  # the box's swept bounds overflow within ~110 steps
        before = world.position(box)
        status = world.step()  # returned, not raised: the world is left as before the step
        if not status.ok:
            break
    assert not status.ok and status.body == box
    assert status.code == tumble.StepCode.Overflow
    assert np.array_equal(world.position(box), before)
    with pytest.raises(tumble.StepFailed, match="body"):
        world.step_checked()


def test_events_queries_and_warnings():
    world, ground = ground_world()
    ball = add_ball(world, [0, 0, 1.0])
    begun, impacts = [], []
    for _ in range(90):
        world.step()
        begun += world.contact_begin_events()
        impacts += world.impact_events()
    assert any(e.body_b == ball or e.body_a == ball for e in begun)
    assert impacts and impacts[0].approach_speed > 0.5
    touching = [c for c in world.contacts() if c.point_count > 0]
    assert len(touching) == 1 and touching[0].normal[2] == pytest.approx(1.0)
    assert sum(touching[0].normal_impulses) == pytest.approx(
        world.mass_properties(ball).mass * 9.81 / 60, rel=0.05)
    hit = world.cast_ray_closest([0, 0, 5], [0, 0, -10])
    assert hit.body == ball and hit.point[2] == pytest.approx(1.0, abs=0.02)
    assert len(world.cast_ray_all([0, 0, 5], [0, 0, -10])) == 2
    shapes = world.overlap_shape(tumble.Sphere(radius=0.2), tumble.Transform(position=[0, 0, 0.5]))
    assert world.body_shapes(ball)[0] in shapes
    p = world.closest_point(world.body_shapes(ball)[0], [0, 0, 3])
    assert p[2] == pytest.approx(world.position(ball)[2] + 0.5)
    heavy = add_ball(world, [0, 0, 3], radius=0.5)
    world.set_mass_properties(heavy, tumble.MassProperties(mass=1e6, inertia=np.eye(3) * 1e5))
    for _ in range(60):
        world.step()
    kinds = [w.kind for w in world.warnings()]
    assert tumble.WarningKind.MassRatio in kinds
    assert "mass" in str(world.warnings()[0]).lower()


def test_the_gil_is_released_while_stepping():
    world = tumble.load_world("rain")
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(1)

    thread = threading.Thread(target=count)
    thread.start()
    for _ in range(60):
        world.step()
    stop.set()
    thread.join()
    assert len(ticks) > 100  # the other thread ran while the world stepped


def test_the_pre_step_callback_can_edit_the_world():
    world = tumble.World()
    b = world.create_body()
    seen = []

    def push(w, time):
        seen.append(time)
        w.apply_force_to_center(b, [0, 0, 9.81])

    world.set_pre_step_callback(push)
    for _ in range(10):
        world.step()
    assert len(seen) == 10 and seen[1] == pytest.approx(1 / 60)
    assert world.linear_velocity(b)[2] == pytest.approx(0, abs=1e-12)
    world.set_pre_step_callback(None)


def test_an_exception_in_the_pre_step_callback_leaves_step_before_any_stage():
    world = tumble.World()
    b = world.create_body()

    def fail(w, time):
        raise KeyError("from the callback")

    world.set_pre_step_callback(fail)
    with pytest.raises(KeyError, match="from the callback"):
        world.step()
    assert world.step_count == 0 and world.position(b)[2] == 0
