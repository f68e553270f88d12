"""Cell-centred lattices in a frame, and the points of a lattice inside one slab.

A lattice of spacing dp in a ``Frame`` has a point at origin + axes @ ((i + 1/2) dp) for every
integer index tuple i in the box [first, last). Its linear index (row-major over that box, the
last axis fastest) names each point: a particle's global id is its source's offset plus this
index (``sources.py``), so ids do not depend on which rank built the particle.

World coordinates are computed element by element in one fixed order (``_world``), never by a
matrix product, whose blocking may round a row differently with the batch it is in: a point has
the same bits whichever slab, and so whichever rank, generates it.
"""

import math
from dataclasses import dataclass

import numpy as np

from .errors import InputError


@dataclass(frozen=True)
class Frame:
    """A lattice frame: ``origin`` and ``axes`` (d x d, the columns are the lattice axes,
    orthonormal; default: the world axes)."""

    origin: tuple = (0.0, 0.0, 0.0)
    axes: tuple | None = None

    def matrix(self):
        d = len(self.origin)
        r = np.eye(d) if self.axes is None else np.asarray(self.axes, float)
        if r.shape != (d, d) or not np.allclose(r.T @ r, np.eye(d), atol=1e-12):
            raise InputError(f"a lattice frame needs {d} orthonormal axes")
        return r

    def local(self, x):
        """World points -> coordinates along the frame's axes."""
        return (np.asarray(x, float) - np.asarray(self.origin, float)) @ self.matrix()


def _world(origin, r, u, axes=None):
    """origin + r @ u for each row of the frame coordinates ``u``, along the world ``axes`` (all)."""
    axes = range(len(origin)) if axes is None else axes
    out = np.empty((len(u), len(axes)))
    for k, d in enumerate(axes):
        acc = u[:, 0] * r[d, 0]
        for a in range(1, u.shape[1]):
            acc += u[:, a] * r[d, a]
        out[:, k] = origin[d] + acc
    return out


@dataclass(frozen=True)
class Lattice:
    """The points of ``frame`` (spacing ``dp``) with index tuples in [first, last)."""

    first: tuple
    last: tuple
    dp: float
    frame: Frame

    @classmethod
    def covering(cls, lo, hi, dp, frame):
        """The lattice of the cells whose centres lie in the frame-coordinate box [lo, hi]."""
        first = tuple(int(v) for v in np.floor(np.asarray(lo) / dp + 1e-9))
        last = tuple(int(v) for v in np.ceil(np.asarray(hi) / dp - 1e-9))
        return cls(first, last, dp, frame)

    @property
    def shape(self):
        return tuple(max(b - a, 0) for a, b in zip(self.first, self.last))

    @property
    def size(self):
        return math.prod(self.shape)

    def frame_coordinates(self, index):
        """(i + 1/2) dp of the points with linear indices ``index``."""
        tuples = np.unravel_index(np.asarray(index, np.int64), self.shape)
        return np.column_stack([(t + f + 0.5) * self.dp for t, f in zip(tuples, self.first)])

    def points(self, index):
        """World positions (n, d) of the points with linear indices ``index``."""
        return _world(self.frame.origin, self.frame.matrix(), self.frame_coordinates(index))

    def window(self, axis, lo, hi, hollow=None):
        """Linear indices (ascending) of the points whose world coordinate along ``axis`` lies in
        [lo, hi), leaving out those whose index tuple lies in the box ``hollow`` (a [start, stop)
        per axis, in the indices of ``first`` and ``last``; None: none left out). Generated a
        lattice plane (first index) at a time, skipping the planes whose range along ``axis``
        cannot meet the window, so the time and memory are those of the answer's planes."""
        shape, dp = self.shape, self.dp
        if self.size == 0:
            return np.zeros(0, np.int64)
        r, origin = self.frame.matrix(), self.frame.origin
        slope = r[axis] * dp  # change of the world coordinate per index step along each lattice axis
        # range of the world coordinate over a plane of fixed first index, about its first point
        rest = sum(min(0.0, slope[a] * (shape[a] - 1)) for a in range(1, len(shape)))
        spread = sum(abs(slope[a]) * (shape[a] - 1) for a in range(1, len(shape)))
        slack = 1e-9 * (abs(origin[axis]) + np.abs(slope).sum() * max(shape) + 1.0)
        plane = np.arange(math.prod(shape[1:]), dtype=np.int64)
        rim, hollow_planes = plane, (0, 0)
        if hollow is not None:  # the hollow's planes hold only their points outside it
            inside = np.ones(len(plane), bool)
            for t, f, (a, b) in zip(np.unravel_index(plane, shape[1:]), self.first[1:], hollow[1:]):
                inside &= (t + f >= a) & (t + f < b)
            rim = plane[~inside]
            hollow_planes = (hollow[0][0] - self.first[0], hollow[0][1] - self.first[0])
        u0 = (np.arange(shape[0]) + self.first[0] + 0.5) * dp
        start = origin[axis] + u0 * r[axis, 0] + sum((f + 0.5) * dp * r[axis, a]
                                                      for a, f in enumerate(self.first) if a > 0)
        out = []
        for i in np.nonzero((start + rest + spread >= lo - slack) & (start + rest < hi + slack))[0]:
            index = i * len(plane) + (rim if hollow_planes[0] <= i < hollow_planes[1] else plane)
            s = _world(origin, r, self.frame_coordinates(index), axes=(axis,))[:, 0]
            out.append(index[(s >= lo) & (s < hi)])
        return np.concatenate(out) if out else np.zeros(0, np.int64)
