"""Overhead of the bindings (a benchmark, not a test): stepping a 1,000-body pile from Python
against the cost of the binding call itself, and reading all poses into numpy.

    PYTHONPATH=build/release/python /usr/bin/python3 python/bench/overhead.py
"""
import time

import numpy as np

import tumble


def pile(n=10):
    world = tumble.World(tumble.WorldDef(enable_sleep=False))  # every body stepped
    ground = world.create_body(tumble.BodyDef(type=tumble.BodyType.Static))
    world.create_shape(ground, tumble.ShapeDef(geometry=tumble.HalfSpace()))
    for i in range(n):
        for j in range(n):
            for k in range(n):
                b = world.create_body(tumble.BodyDef(position=[0.3 * i, 0.3 * j, 0.2 + 0.3 * k]))
                world.create_shape(b, tumble.ShapeDef(geometry=tumble.Sphere(radius=0.1)))
    return world


def best(fn, repeat):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def main():
    world = pile()
    for _ in range(30):
        world.step()
    step = sum(best(world.step, 1) for _ in range(100)) / 100  # mean step
    empty = tumble.World()
    call = best(empty.step, 2000)  # the binding's own cost plus an empty step
    copy = best(lambda: np.array(world.centers), 2000)
    poses = best(lambda: (np.array(world.centers), np.array(world.orientations)), 2000)
    print(f"bodies {world.body_count - 1}")
    print(f"step of the pile from Python: {step * 1e3:.3f} ms")
    print(f"step of an empty world from Python (call overhead bound): {call * 1e6:.2f} us"
          f" = {100 * call / step:.3f} % of the pile's step")
    print(f"all centres into numpy (copy): {copy * 1e6:.2f} us; centres + orientations:"
          f" {poses * 1e6:.2f} us")


if __name__ == "__main__":
    main()
