"""Tumble: rigid bodies, strings and nets (SI units, double precision).

A thin mirror of the C++ API (tumble/world.h): names in snake_case, quaternions as
(x, y, z, w), vectors as numpy arrays. Bad input raises tumble.InvalidArgument (a ValueError)
with the engine's message. The state of all bodies is readable without copies through
World.centers, .orientations, .linear_velocities and .angular_velocities (StateView).
"""

import numpy as _np

from ._tumble import *  # noqa: F401,F403
from ._tumble import InvalidArgument, World, _Export  # noqa: F401
from . import _tumble

_FIELDS = {"centers": 0, "orientations": 1, "linear_velocities": 2, "angular_velocities": 3}


class StaleViewError(RuntimeError):
    """A state view was read after bodies were created or destroyed (or a checkpoint loaded)."""


class StepFailed(RuntimeError):
    """Raised by World.step_checked when a step failed; .status is its StepStatus."""

    def __init__(self, status):
        super().__init__(f"step failed: {status.code.name} at body {status.body}"
                         + ("" if status.spring.is_null() else f", spring {status.spring}"))
        self.status = status


class StateView:
    """Read-only view of one state field of a range of bodies, in dense order, in place.

    Reading it (indexing, np.asarray, arithmetic) always shows the world's current state: no
    copy is made when the view is taken, and a step is seen without taking it again. Once bodies
    are created or destroyed (or a checkpoint is restored) the view is stale and every read
    raises StaleViewError; take a new one. Indexing copies the selection. np.asarray(view)
    is the zero-copy numpy array itself: while any such array lives, creating or destroying
    bodies raises BufferError (it would dangle), as a bytearray refuses to resize under a
    memoryview.

    Fields: centers (centres of mass, m -- body origins for bodies whose mass centre is at their
    origin, e.g. every net node), orientations (x, y, z, w), linear_velocities (m/s, of the
    centre of mass), angular_velocities (rad/s, world frame).
    """

    __slots__ = ("_world", "_field", "_first", "_count", "_structure", "name")

    def __init__(self, world, name, first=0, count=None):
        self._world = world
        self.name = name
        self._field = _FIELDS[name]
        self._first = first
        self._count = world.body_count - first if count is None else count
        self._structure = world._structure

    def _array(self):
        if self._world._structure != self._structure:
            raise StaleViewError(
                f"this view of {self.name} was taken before bodies were created or destroyed "
                "(or a checkpoint restored); take a new one")
        return self._world._raw(self._field, self._first, self._count)

    def __array__(self, dtype=None):
        a = self._array()
        return a if dtype is None else a.astype(dtype)

    def __getitem__(self, index):
        return _np.array(self._array()[index])

    def __len__(self):
        return self._count

    @property
    def shape(self):
        return (self._count, 4 if self._field == 1 else 3)

    @property
    def valid(self):
        return self._world._structure == self._structure

    def copy(self):
        return _np.array(self._array())

    def __repr__(self):
        state = "valid" if self.valid else "stale"
        return f"StateView({self.name}, {self._count} bodies, {state})"

    def __array_ufunc__(self, ufunc, method, *inputs, **kwargs):
        inputs = tuple(_np.asarray(x) if isinstance(x, StateView) else x for x in inputs)
        return getattr(ufunc, method)(*inputs, **kwargs)


def _view_property(name):
    def get(self):
        return StateView(self, name)

    get.__doc__ = f"StateView of every body's {name.replace('_', ' ')}, dense order."
    return property(get)


for _name in _FIELDS:
    setattr(World, _name, _view_property(_name))


def _view(self, name, bodies=None):
    """StateView of `name` for `bodies` (a list of BodyIds consecutive in dense order, such as a
    net's nodes), or of every body."""
    if bodies is None:
        return StateView(self, name)
    first, count = self._dense_range(list(bodies))
    return StateView(self, name, first, count)


def _step_checked(self):
    """step(), raising StepFailed (naming the body) when the step failed."""
    status = self.step()
    if not status.ok:
        raise StepFailed(status)
    return status


World.view = _view
World.step_checked = _step_checked


def load_world(name_or_file, overrides=(), directory=""):
    """The World of a scene file (or built-in scene name): build_scene(load_scene(...)).world."""
    return build_scene(load_scene(name_or_file, list(overrides), directory)).world


# Plain structs take their fields as keywords (the C++ defaults for the others).
def _keyword_init(cls):
    base = cls.__init__
    fields = cls._fields

    def __init__(self, **kwargs):
        base(self)
        for key, value in kwargs.items():
            if key not in fields:
                raise TypeError(f"{cls.__name__} has no field {key!r} (fields: {', '.join(fields)})")
            setattr(self, key, value)

    def __repr__(self):
        return f"{cls.__name__}(" + ", ".join(f"{f}={getattr(self, f)!r}" for f in fields) + ")"

    __init__.__doc__ = f"{cls.__name__}(**fields): " + ", ".join(fields)
    cls.__init__ = __init__
    cls.__repr__ = __repr__


for _obj in list(vars(_tumble).values()):
    if isinstance(_obj, type) and "_fields" in vars(_obj):
        _keyword_init(_obj)
