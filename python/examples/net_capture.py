"""The net-capture scene: a net thrown at a target, the heights of its four corners plotted
with matplotlib (a PNG), read through one zero-copy view of the net's nodes."""
import sys

import numpy as np

import tumble


def corner_heights(duration=None):
    scene = tumble.load_scene("net-capture")
    built = tumble.build_scene(scene)
    world = built.world
    corners = [built.bodies[i] for i in scene.select(["net.corners"])]
    dense = world.bodies()
    rows = [dense.index(c) for c in corners]
    centers = world.centers  # every body, in place: sees each step
    times, heights = [], []
    end = scene.duration if duration is None else duration
    while world.time < end:
        world.step()
        times.append(world.time)
        heights.append(centers[rows, 2])
    return np.array(times), np.array(heights)


def plot(path, duration=None):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    times, heights = corner_heights(duration)
    fig, ax = plt.subplots(figsize=(6, 3.5))
    for k in range(heights.shape[1]):
        ax.plot(times, heights[:, k], label=f"corner {k}")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("height (m)")
    ax.set_title("net capture: corner heights")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return heights


if __name__ == "__main__":
    plot(sys.argv[1] if len(sys.argv) > 1 else "net-capture-corners.png")
