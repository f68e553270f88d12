"""Where a body's or a wall's particles come from: point sets a rank reads one slab of.

A case gives each body and wall its positions either as an array or as a ``Points`` source that
generates them on demand (a lattice fill, dummy layers behind a surface). Every source has

- ``size``: its ids run over [0, size); a particle's global id is the source's offset (the sizes
  of the sources before it, bodies then walls) plus its index, so it does not depend on the
  number of ranks; for a lattice the index is the lattice index, so ids may have gaps;
- ``estimate``: about how many particles it holds, known before any is generated (the memory
  check of a case too large refuses it from this);
- ``window(axis, lo, hi)``: the indices, positions and normals (None for a body) of its
  particles whose coordinate along ``axis`` lies in [lo, hi), ascending by index.

``initial.particles_from_case`` builds each rank's slab from these windows alone.
"""

import numpy as np


class Points:
    """A source of particle positions (module docstring); subclasses set ``size``, ``estimate``
    and ``window``."""

    size = 0
    estimate = 0

    def window(self, axis, lo, hi):
        raise NotImplementedError

    def near(self, point, reach):
        """(indices, positions) of its particles within ``reach`` of ``point`` along every axis (and
        some beyond): here those of the window along x."""
        index, x, _ = self.window(0, point[0] - reach, point[0] + reach)
        return index, x

    def everything(self):
        """(positions, normals or None) of all its particles, for small cases and tests."""
        _, x, normal = self.window(0, -np.inf, np.inf)
        return x, normal

    def position(self, index):
        """The position of the point with index ``index`` (of a lattice: also where ``keep`` put none)."""
        raise NotImplementedError

    def holds(self, index):
        """Whether ``index`` is one of its particles' indices."""
        return 0 <= index < self.size


class ArrayPoints(Points):
    """Positions (and wall normals) given as arrays: the index is the row."""

    def __init__(self, x, normal=None):
        self.x = np.asarray(x, float)
        self.normal = None if normal is None else np.asarray(normal, float)
        self.size = self.estimate = len(self.x)

    def window(self, axis, lo, hi):
        s = self.x[:, axis]
        index = np.nonzero((s >= lo) & (s < hi))[0]
        return index, self.x[index], None if self.normal is None else self.normal[index]

    def position(self, index):
        return self.x[index]


class LatticePoints(Points):
    """The points of a ``lattice.Lattice`` that ``keep`` (positions -> bool mask; None: all)
    accepts, with normals from ``normal`` (positions -> (n, d) unit vectors; None: a body).
    ``estimate`` defaults to the lattice's size."""

    def __init__(self, lattice, keep=None, normal=None, estimate=None):
        self.lattice = lattice
        self.keep = keep
        self.normal = normal
        self.size = lattice.size
        self.estimate = lattice.size if estimate is None else int(estimate)

    def window(self, axis, lo, hi):
        index = self.lattice.window(axis, lo, hi)
        return self.kept(index, self.lattice.points(index))

    def near(self, point, reach):
        """(indices, positions) of its particles in the box of lattice points within ``reach`` of
        ``point`` along each of the frame's axes: a few, however fine the lattice (a slab along x
        of a fine 3D lattice would hold billions)."""
        lattice = self.lattice
        u = lattice.frame.local(np.asarray(point, float)[None])[0] / lattice.dp - 0.5  # in index units
        steps = int(np.ceil(reach / lattice.dp))
        lo = np.maximum(np.floor(u).astype(np.int64) - steps, lattice.first)
        hi = np.minimum(np.floor(u).astype(np.int64) + steps + 2, lattice.last)
        if np.any(hi <= lo):
            return np.zeros(0, np.int64), np.zeros((0, len(u)))
        box = np.stack(np.meshgrid(*[np.arange(a, b) for a, b in zip(lo, hi)], indexing="ij"), -1).reshape(-1, len(u))
        index = np.ravel_multi_index(tuple((box - lattice.first).T), lattice.shape)
        index, x, _ = self.kept(index, lattice.points(index))
        return index, x

    def kept(self, index, x):
        """(indices, positions, normals or None) of the points among ``index`` (at ``x``) that
        ``keep`` accepts."""
        if self.keep is not None:
            kept = self.keep(x)
            index, x = index[kept], x[kept]
        return index, x, None if self.normal is None else self.normal(x)

    def position(self, index):
        return self.lattice.points(np.array([index]))[0]

    def holds(self, index):
        return 0 <= index < self.size and (self.keep is None or bool(self.keep(self.position(index)[None])[0]))


def as_points(x, normal=None):
    """``x`` itself if it is a source, else the arrays ``x`` (and ``normal``) as one."""
    return x if isinstance(x, Points) else ArrayPoints(x, normal)
