"""Triangle meshes and height fields built from numpy arrays: bodies rest on them, rays hit their
exact surface, holes let rays through, bad arrays are refused naming the entry, and a world
holding them checkpoints and resumes bitwise."""
import numpy as np
import pytest

import tumble


def flat_grid(n, cell):
    """n x n cells of side `cell` centred on the origin at z = 0, two triangles each."""
    ticks = (np.arange(n + 1) - n / 2) * cell
    x, y = np.meshgrid(ticks, ticks)
    vertices = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    at = np.arange((n + 1) ** 2).reshape(n + 1, n + 1)
    a, b, c, d = at[:-1, :-1].ravel(), at[:-1, 1:].ravel(), at[1:, 1:].ravel(), at[1:, :-1].ravel()
    triangles = np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    return vertices, triangles


def surface_world(geometry):
    world = tumble.World()
    ground = world.create_body(tumble.BodyDef(type=tumble.BodyType.Static))
    world.create_shape(ground, tumble.ShapeDef(geometry=geometry))
    return world


def test_a_ball_rests_on_a_mesh_made_from_arrays():
    vertices, triangles = flat_grid(8, 0.5)
    mesh = tumble.TriangleMesh.from_arrays(vertices, triangles.astype(np.int32))
    assert mesh.triangle_count == 128 and mesh.dropped_triangles == 0
    assert np.allclose(mesh.bounds.lower, [-2, -2, 0]) and np.allclose(mesh.bounds.upper, [2, 2, 0])
    world = surface_world(mesh)
    ball = world.create_body(tumble.BodyDef(position=[0.3, 0.2, 1]))
    world.create_shape(ball, tumble.ShapeDef(geometry=tumble.Sphere(radius=0.25)))
    for _ in range(180):
        assert world.step().ok
    # At rest on the surface: centre one radius up, within the contact slop.
    assert world.position(ball)[2] == pytest.approx(0.25, abs=0.01)
    assert np.linalg.norm(world.linear_velocity(ball)) < 1e-3


def test_rays_hit_a_height_field_at_its_exact_height_and_pass_through_holes():
    rows, columns, dx, dy = 6, 9, 0.5, 0.25
    j, i = np.mgrid[0:rows, 0:columns]
    heights = 0.2 * i * dx - 0.3 * j * dy  # a plane: every triangle lies in it
    holes = np.zeros((rows - 1, columns - 1), dtype=bool)
    holes[2, 3] = True  # cell (i = 3, j = 2)
    field = tumble.HeightField.from_grid(heights, spacing_x=dx, spacing_y=dy, holes=holes)
    assert (field.rows, field.columns) == (rows, columns)
    world = surface_world(field)
    world.step()  # queries see the broadphase as the last step left it
    rng = np.random.default_rng(26)
    for x, y in rng.uniform([0, 0], [(columns - 1) * dx, (rows - 1) * dy], size=(200, 2)):
        hit = world.cast_ray_closest([x, y, 5], [0, 0, -10])
        if int(x / dx) == 3 and int(y / dy) == 2:
            assert hit is None
            continue
        assert hit is not None
        assert hit.point[2] == pytest.approx(0.2 * x - 0.3 * y, abs=1e-12)
        assert np.allclose(hit.normal, np.array([-0.2, 0.3, 1]) / np.sqrt(1.13), atol=1e-12)


def test_bad_arrays_are_refused_naming_the_entry():
    vertices, triangles = flat_grid(2, 1.0)
    bad = triangles.copy()
    bad[3, 1] = -1
    with pytest.raises(tumble.InvalidArgument, match=r"triangles\[3, 1\] = -1"):
        tumble.TriangleMesh.from_arrays(vertices, bad)
    bad[3, 1] = 100
    with pytest.raises(tumble.InvalidArgument, match="vertex index 1 = 100"):
        tumble.TriangleMesh.from_arrays(vertices, bad)
    heights = np.zeros((3, 4))
    heights[1, 2] = np.nan
    with pytest.raises(tumble.InvalidArgument, match=r"heights\[6\] \(column 2, row 1\)"):
        tumble.HeightField.from_grid(heights)
    with pytest.raises(tumble.InvalidArgument, match="holes has shape"):
        tumble.HeightField.from_grid(np.zeros((3, 4)), holes=np.zeros((3, 4)))
    world = tumble.World()
    dynamic = world.create_body()
    with pytest.raises(tumble.InvalidArgument):
        world.create_shape(dynamic, tumble.ShapeDef(
            geometry=tumble.TriangleMesh.from_arrays(vertices, triangles)))


def test_a_world_with_a_mesh_and_a_height_field_resumes_bitwise():
    vertices, triangles = flat_grid(6, 0.5)
    world = surface_world(tumble.TriangleMesh.from_arrays(vertices, triangles))
    j, i = np.mgrid[0:8, 0:8]
    terrain = world.create_body(tumble.BodyDef(type=tumble.BodyType.Static, position=[4, -2, 0]))
    world.create_shape(terrain, tumble.ShapeDef(
        geometry=tumble.HeightField.from_grid(0.1 * np.sin(i) * np.cos(j), 0.5, 0.5)))
    for k in range(6):
        body = world.create_body(tumble.BodyDef(position=[-1 + 1.2 * k, 0.1 * k, 1]))
        geometry = tumble.Box(half_extents=[0.2, 0.2, 0.2]) if k % 2 else tumble.Sphere(radius=0.2)
        world.create_shape(body, tumble.ShapeDef(geometry=geometry))
    for _ in range(30):
        world.step()
    copy = tumble.World()
    copy.restore_checkpoint(world.checkpoint_bytes(), "meshes")
    for _ in range(60):
        world.step()
        copy.step()
    assert np.array_equal(np.asarray(world.centers), np.asarray(copy.centers))
    assert np.array_equal(np.asarray(world.linear_velocities), np.asarray(copy.linear_velocities))
    assert copy.checkpoint_bytes() == world.checkpoint_bytes()
