"""Struct-of-arrays particle storage.

Every field is one numpy array whose first axis runs over particles. The
rank's own particles come first (``[0, n_owned)``), ghost copies received in
the halo follow (``[n_owned, n)``). Moving particles have ``kind == MOVING``;
fixed dummy wall particles have ``kind == WALL`` (no-slip) or ``WALL_SLIP``
(free-slip). ``CLAMPED`` particles belong to a solid body and evolve its
density and stress like the moving ones, but are held in place (the clamped
root of a cantilever); moving and clamped particles are the *material*.

Each field lives in a buffer with room to spare; ``arrays[name]`` is the view
of its first n rows. A new halo or a migration then reuses the buffers and
rewrites only the rows that change, instead of allocating every field anew
each step.

Fields are declared once with a per-particle shape (``()``, ``("dim",)``,
``(6,)`` for a packed symmetric 3 x 3 tensor or ``("sym",)`` for a packed
symmetric dim x dim one, tensors.py); packing to and from flat float64 rows
is what the parallel package uses to move particles and ghosts between
ranks. Integer fields go through float64 exactly (global ids stay below
2**53).
"""

from dataclasses import dataclass

import numpy as np
from numba import njit

from . import tensors

MOVING = 0
WALL = 1  # fixed wall particle, no-slip
WALL_SLIP = 2  # fixed wall particle, free-slip
CLAMPED = 3  # material particle held in place


@njit(inline="always")
def is_wall(kind):
    """True for the fixed dummy wall kinds."""
    return kind == WALL or kind == WALL_SLIP


@dataclass(frozen=True)
class Field:
    """A per-particle quantity: name, shape per particle, dtype, meaning."""

    name: str
    shape: tuple
    dtype: type
    doc: str

    def shape_in(self, dim):
        """The shape per particle in ``dim`` dimensions: "dim" and "sym" (tensors.size) resolved."""
        return tuple(dim if s == "dim" else tensors.size(dim) if s == "sym" else s for s in self.shape)


# Fields every particle has, whatever its material.
CORE_FIELDS = (
    Field("gid", (), np.int64, "global particle id"),
    Field("kind", (), np.int8, "0 moving, 1 no-slip wall, 2 free-slip wall, 3 clamped"),
    Field("x", ("dim",), np.float64, "position [m]"),
    Field("v", ("dim",), np.float64, "velocity (wall: wall velocity) [m/s]"),
    Field("mass", (), np.float64, "mass [kg; in 2D per metre of depth, kg/m]"),
    Field("rho", (), np.float64, "density [kg/m^3]"),
    Field("p", (), np.float64, "pressure [Pa]"),
    Field("normal", ("dim",), np.float64, "unit wall normal into the material (walls only) [-]"),
)


HEADROOM = 1.2  # buffers grow to this multiple of the rows needed


class Particles:
    """Owned particles followed by ghosts, one numpy array per field."""

    def __init__(self, dim, fields, arrays, n_owned):
        self.dim = dim
        self.fields = tuple(fields)
        self.arrays = arrays
        self.n_owned = n_owned
        self._buffers = dict(arrays)
        self._columns = {f.name: int(np.prod(f.shape_in(dim), dtype=np.int64)) for f in self.fields}

    @classmethod
    def empty(cls, dim, fields, n=0):
        arrays = {f.name: np.zeros((n,) + f.shape_in(dim), dtype=f.dtype) for f in fields}
        return cls(dim, fields, arrays, n)

    def __getattr__(self, name):
        try:
            return self.__dict__["arrays"][name]
        except KeyError:
            raise AttributeError(name) from None

    @property
    def n(self):
        """Owned plus ghost particles."""
        return len(self.arrays["gid"])

    @property
    def n_ghost(self):
        return self.n - self.n_owned

    def width(self, names):
        """Number of float64 columns the named fields take in a packed row."""
        return sum(self._columns[n] for n in names)

    def pack(self, names, index):
        """Rows ``index`` of the named fields as one (len(index), width) float64 array."""
        out = np.empty((len(index), self.width(names)))
        col = 0
        for name in names:
            w = self._columns[name]
            out[:, col:col + w] = self.arrays[name][index].reshape(len(index), w)
            col += w
        return out

    def unpack_into(self, names, rows, start):
        """Write packed ``rows`` into the named fields from particle ``start`` on."""
        col = 0
        n = len(rows)
        for name in names:
            a = self.arrays[name]
            w = self._columns[name]
            a[start:start + n] = rows[:, col:col + w].reshape((n,) + a.shape[1:])
            col += w

    def _resize(self, n_keep, n):
        """Make every field n rows long, keeping its first ``n_keep`` rows."""
        for name, buf in self._buffers.items():
            if len(buf) < n:
                new = np.empty((int(HEADROOM * n) + 1,) + buf.shape[1:], dtype=buf.dtype)
                new[:n_keep] = buf[:n_keep]
                self._buffers[name] = buf = new
            self.arrays[name] = buf[:n]

    def set_ghost_count(self, n_ghost):
        """Keep the owned rows and make room for ``n_ghost`` ghost rows after them."""
        self._resize(self.n_owned, self.n_owned + n_ghost)

    def keep_owned(self, keep, n_new):
        """Keep the owned rows ``keep``, in that order, and make room for ``n_new`` owned rows
        after them; ghosts are dropped. ``keep`` = all rows in a new order reorders them."""
        n_keep = len(keep)
        if n_keep < self.n_owned or np.any(keep != np.arange(n_keep)):
            for name in self._buffers:
                a = self.arrays[name]
                a[:n_keep] = a[keep]
        self._resize(n_keep, n_keep + n_new)
        self.n_owned = n_keep + n_new

    def owned(self, name):
        return self.arrays[name][: self.n_owned]

    def owned_fields(self):
        """Dict of every field over the owned particles (for frames)."""
        return {f.name: self.arrays[f.name][: self.n_owned] for f in self.fields}
