"""State views: zero-copy, read-only, never dangling; batch setters."""
import numpy as np
import pytest

import tumble
from conftest import add_ball, ground_world


def test_views_are_zero_copy_and_see_a_step(ground):
    world, _ = ground
    add_ball(world, [0, 0, 3])
    centers = world.centers
    raw = np.asarray(centers)
    address = raw.__array_interface__["data"][0]
    z0 = raw[1, 2]
    world.step()
    assert raw[1, 2] < z0  # the same array sees the step: it is the engine's storage
    assert centers[1, 2] == raw[1, 2]
    again = np.asarray(world.centers)
    assert again.__array_interface__["data"][0] == address
    assert not raw.flags.writeable
    with pytest.raises(ValueError):
        raw[1, 2] = 0.0


def test_view_fields_match_the_per_body_getters(ground):
    world, _ = ground
    ball = add_ball(world, [1, 2, 3], linear_velocity=[1, 0, 0], angular_velocity=[0, 0, 2])
    world.step()
    i = world.bodies().index(ball)
    assert np.array_equal(world.centers[i], world.center_of_mass(ball))
    assert np.array_equal(world.orientations[i], world.orientation(ball))
    assert np.array_equal(world.linear_velocities[i], world.linear_velocity(ball))
    assert np.array_equal(world.angular_velocities[i], world.angular_velocity(ball))
    assert world.orientations.shape == (2, 4)


def test_creating_or_destroying_bodies_makes_views_stale(ground):
    world, _ = ground
    ball = add_ball(world, [0, 0, 1])
    view = world.linear_velocities
    world.create_body(tumble.BodyDef())
    assert not view.valid
    with pytest.raises(tumble.StaleViewError, match="take a new one"):
        view[0]
    with pytest.raises(tumble.StaleViewError):
        np.asarray(view)
    fresh = world.linear_velocities
    world.destroy_body(ball)
    with pytest.raises(tumble.StaleViewError):
        fresh.copy()
    assert len(world.linear_velocities) == 2


def test_a_live_raw_array_refuses_changes_that_would_move_the_storage(ground):
    world, _ = ground
    raw = np.asarray(world.centers)
    row = raw[0]  # a slice keeps the export alive too
    del raw
    with pytest.raises(BufferError, match="would dangle"):
        world.create_body(tumble.BodyDef())
    assert world.body_count == 1  # refused before anything was created
    del row
    world.create_body(tumble.BodyDef())
    assert world.body_count == 2
    data = world.checkpoint_bytes()
    keep = np.asarray(world.orientations)
    with pytest.raises(BufferError):
        world.restore_checkpoint(data)
    del keep
    world.restore_checkpoint(data)


def test_batch_setters_go_through_the_checks_and_wake():
    world, _ = ground_world()
    balls = [add_ball(world, [2 * k, 0, 0.5]) for k in range(3)]
    for _ in range(120):
        world.step()
    assert not any(world.is_awake(b) for b in balls)
    v = np.zeros((world.body_count, 3))
    v[1:, 0] = [1.0, 2.0, 3.0]
    world.set_linear_velocities(v)
    assert all(world.is_awake(b) for b in balls)
    assert np.array_equal(world.linear_velocities[1:, 0], [1.0, 2.0, 3.0])
    v[0, 0] = 1.0  # the static ground: refused by the engine
    with pytest.raises(tumble.InvalidArgument):
        world.set_linear_velocities(v)
    bad = np.zeros((3, 3))
    bad[2, 1] = np.nan
    with pytest.raises(tumble.InvalidArgument, match=r"\[2\]"):
        world.set_angular_velocities(bad, bodies=balls)
    q = np.tile([0.0, 0.0, 0.0, 2.0], (3, 1))  # not unit
    with pytest.raises(tumble.InvalidArgument):
        world.set_poses(np.zeros((3, 3)), q, bodies=balls)
    world.set_poses([[0, 0, 5], [2, 0, 5], [4, 0, 5]], np.tile([0, 0, 0, 1.0], (3, 1)), bodies=balls)
    assert np.array_equal(world.body_positions()[1:, 2], [5, 5, 5])
    with pytest.raises(tumble.InvalidArgument, match="rows for"):
        world.set_linear_velocities(np.zeros((2, 3)), bodies=balls)


def test_a_nets_nodes_as_one_view():
    world, _ = ground_world()
    add_ball(world, [5, 5, 1])
    net = world.create_net(tumble.NetDef(rows=4, columns=5, center=[0, 0, 2]))
    nodes = world.view("centers", net.nodes)
    assert nodes.shape == (20, 3)
    assert np.allclose(nodes[:, 2], 2.0)
    world.step()
    assert np.all(nodes[:, 2] < 2.0)
    expected = np.array([world.center_of_mass(b) for b in net.nodes])
    assert np.array_equal(np.asarray(nodes), expected)
    with pytest.raises(tumble.InvalidArgument, match="dense order"):
        world.view("centers", net.nodes[::-1])
