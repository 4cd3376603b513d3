"""Scene files, `tumble run`, checkpoints, and bitwise identity with the C++ API."""
import json
import pathlib
import struct

import numpy as np
import pytest

import tumble

GOLDEN = pathlib.Path(__file__).resolve().parents[2] / "tests" / "golden" / "trajectories.txt"
MASK = (1 << 64) - 1


class Fnv:
    """testkit::Hash (tests/.../state_hash.h): FNV-1a over the bytes of 64-bit words."""

    def __init__(self):
        self.value = 0xCBF29CE484222325

    def add_bytes(self, data):
        h = self.value
        for byte in data:
            h = ((h ^ byte) * 0x100000001B3) & MASK
        self.value = h

    def add_word(self, word):
        self.add_bytes(struct.pack("<Q", word))


def state_hash(world, bodies):
    """testkit::stateHash, from the Python API."""
    words = [struct.pack("<Q", world.step_count), struct.pack("<d", world.time)]
    for b in bodies:
        q = world.orientation(b)  # (x, y, z, w); the hash takes w first
        values = np.concatenate([world.position(b), [q[3], q[0], q[1], q[2]],
                                 world.linear_velocity(b), world.angular_velocity(b)])
        words.append(values.astype("<f8").tobytes())
        words.append(struct.pack("<Q", int(world.is_awake(b))))
    h = Fnv()
    h.add_bytes(b"".join(words))
    return h.value


def golden():
    table = {}
    for line in GOLDEN.read_text().splitlines():
        if line and not line.startswith("#"):
            name, steps, value = line.split()
            table[name] = (int(steps), int(value, 16))
    return table


@pytest.mark.parametrize("scene", ["pyramid", "net-capture"])
def test_a_scene_stepped_from_python_is_bitwise_the_cpp_trajectory(scene):
    steps, expected = golden()[scene]
    built = tumble.build_scene(tumble.load_scene(scene))
    trajectory = Fnv()
    trajectory.add_word(state_hash(built.world, built.bodies))
    for _ in range(steps):
        assert built.world.step().ok
        trajectory.add_word(state_hash(built.world, built.bodies))
    assert f"{trajectory.value:016x}" == f"{expected:016x}"


def test_checkpoint_round_trip_is_bitwise(tmp_path):
    world = tumble.load_world("pyramid")
    for _ in range(30):
        world.step()
    path = tmp_path / "pyramid.ckpt"
    world.save_checkpoint(str(path))
    copy = tumble.World()
    copy.load_checkpoint(str(path))
    assert copy.checkpoint_bytes() == world.checkpoint_bytes()
    for _ in range(40):
        world.step()
        copy.step()
    assert np.array_equal(np.asarray(world.centers), np.asarray(copy.centers))
    assert np.array_equal(np.asarray(world.orientations), np.asarray(copy.orientations))
    assert np.array_equal(np.asarray(world.linear_velocities), np.asarray(copy.linear_velocities))
    with pytest.raises(tumble.InvalidArgument, match="truncated|short|size|version"):
        copy.restore_checkpoint(world.checkpoint_bytes()[:40], "cut")


def test_scene_loading_names_the_json_path(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"bodies": [{"shape": {"sphere": {"radius": -1}}}]}')
    with pytest.raises(tumble.InvalidArgument, match="bodies"):
        tumble.load_scene(str(bad))
    scene = tumble.load_scene("net-capture", ["duration=0.5"])
    assert scene.duration == 0.5
    assert len(scene.select(["net.corners"])) == 4
    assert "pyramid" in tumble.builtin_scenes()


def test_run_is_the_command(tmp_path):
    summary = tmp_path / "s.json"
    result = tumble.run("bounce", time=0.5, dt=1 / 100, summary=str(summary), quiet=True)
    assert result.status == 0
    figures = json.loads(summary.read_text())
    assert figures["steps"] == 50 and figures["status"] == "ok"
    with pytest.raises(tumble.InvalidArgument, match="no-such-scene|not found|scene"):
        tumble.run("no-such-scene", quiet=True)
