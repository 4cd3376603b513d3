"""The examples in python/examples run (short), so they cannot rot."""
import importlib.util
import pathlib

import pytest

EXAMPLES = pathlib.Path(__file__).resolve().parents[1] / "examples"


def load(name):
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_embedding_box_comes_to_rest_on_the_ground():
    heights = load("embedding").main()
    assert heights[0] < 2.0 and heights[-1] == pytest.approx(0.5, abs=0.01)


def test_bounce_study_apex_is_e_squared_h():
    for h, apex, expected, error in load("bounce_study").table(steps=(1 / 60, 1 / 240)):
        assert abs(error) < 0.01 * expected


def test_net_capture_plot(tmp_path):
    pytest.importorskip("matplotlib")
    path = tmp_path / "corners.png"
    heights = load("net_capture").plot(str(path), duration=0.25)
    assert path.stat().st_size > 1000 and heights.shape[1] == 4
    assert heights[-1].max() < heights[0].max()  # the thrown net's corners fall
