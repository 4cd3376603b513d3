import pytest

import tumble


def ground_world(**settings):
    """A world with a static half-space ground at z = 0; returns (world, ground body)."""
    world = tumble.World(tumble.WorldDef(**settings))
    ground = world.create_body(tumble.BodyDef(type=tumble.BodyType.Static))
    world.create_shape(ground, tumble.ShapeDef(geometry=tumble.HalfSpace()))
    return world, ground


def add_ball(world, position, radius=0.5, **body):
    b = world.create_body(tumble.BodyDef(position=position, **body))
    world.create_shape(b, tumble.ShapeDef(geometry=tumble.Sphere(radius=radius)))
    return b


@pytest.fixture
def ground():
    return ground_world()
