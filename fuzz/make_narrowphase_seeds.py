#!/usr/bin/env python3
"""Writes the narrowphase seeds, fuzz/corpus/narrowphase/*: a few shape pairs in the byte layout
that fuzz/narrowphase_fuzz.cpp documents. Run from anywhere; overwrites the seeds it names."""
import math
import os
import struct

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus", "narrowphase")


def lin(x, lo, hi):
    return struct.pack("<H", round((x - lo) / (hi - lo) * 65535))


def logu(x, lo=1e-3, hi=10):
    return lin(math.log(x / lo) / math.log(hi / lo), 0, 1)


def quat(w, x, y, z):
    return b"".join(lin(c, -1, 1) for c in (w, x, y, z))


def shape(kind, sizes, q=(1, 0, 0, 0), hull=None, heights=None, bits=0):
    """kind: 0 sphere, 1 capsule, 2 box, 3 cylinder, 4 hull (points in units of sizes), 5 half-space,
    6 triangle mesh, 7 height field (9 heights in units of size 3, diagonal or hole bits)."""
    b = bytes([kind]) + b"".join(logu(s) for s in sizes)
    if kind == 4:
        b += bytes([len(hull) - 4]) + b"".join(lin(c, -1, 1) for p in hull for c in p)
    if kind in (6, 7):
        b += b"".join(lin(h, -1, 1) for h in heights) + bytes([bits])
    return b + quat(*q)


def pair(name, margin, a, b, position_a, offset):
    """offset: B's centre from A's, in units of 1.5 x (extent A + extent B), each in [-1, 1]."""
    data = lin(margin, 0, 0.1) + a + b
    data += b"".join(lin(c, -1e3, 1e3) for c in position_a)
    data += b"".join(lin(c, -1, 1) for c in offset)
    with open(os.path.join(OUT, name), "wb") as f:
        f.write(data)


s = math.sqrt(0.5)
cube = [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
tetra = [(1, 1, 1), (-1, -1, 1), (-1, 1, -1), (1, -1, -1)]
os.makedirs(OUT, exist_ok=True)
pair("box_on_half_space", 0.02, shape(5, [1, 1, 1]), shape(2, [0.5, 0.5, 0.5]), (0, 0, 0), (0, 0, 0.2))
pair("box_on_box_face", 0.02, shape(2, [1, 1, 0.5]), shape(2, [0.5] * 3), (1, 2, 3), (0, 0, 0.25))
pair("box_edge_on_box", 0.02, shape(2, [0.5] * 3), shape(2, [0.5] * 3, (s, s, 0, 0)), (0, 0, 0), (0, 0, 0.5))
pair("sphere_sphere", 0.0, shape(0, [0.5, 1, 1]), shape(0, [0.3, 1, 1]), (0, 0, 0), (0.3, 0, 0))
pair("capsule_cylinder", 0.05, shape(1, [0.2, 0.5, 1]), shape(3, [0.3, 0.4, 1], (s, 0, s, 0)), (10, 0, 0),
     (0.1, 0.05, 0))
pair("hull_on_box", 0.02, shape(4, [0.5] * 3, hull=cube), shape(2, [0.4] * 3), (0, 0, 0), (0, 0, 0.3))
pair("tetra_cylinder", 0.02, shape(4, [0.3] * 3, hull=tetra), shape(3, [0.2, 0.5, 1]), (-5, 5, 1), (0.1, 0.1, 0.1))
pair("mm_cube_on_ground", 0.02, shape(5, [1, 1, 1]), shape(2, [0.001] * 3), (1e3, -1e3, 0), (0, 0, 0.0002))
pair("box_on_mesh", 0.02, shape(6, [1, 1, 0.1], heights=[0, 0.5, 0, 0.5, 1, 0.5, 0, 0.5, 0], bits=5),
     shape(2, [0.3] * 3), (0, 0, 0), (0.3, 0.3, 0.1))
pair("capsule_on_height_field", 0.02, shape(7, [1, 1, 0.2], heights=[0, 1, 0, -1, 0, 1, 0, -1, 0], bits=2),
     shape(1, [0.2, 0.4, 1], (s, s, 0, 0)), (3, 4, 5), (0.25, 0.25, 0.1))
