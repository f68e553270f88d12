"""Lattice fills of simple shapes and dummy-particle walls around boxes.

Particles sit at the centres of lattice cells of spacing dp (lo + (i + 1/2)
dp along each axis), so every particle's volume is exactly dp^d; a box whose
side is not a multiple of dp holds floor(L/dp) particles along it. ``block`` and
``walls_around`` are sources (sources.py) that each rank reads only its slab of;
``box`` and ``box_walls`` are their arrays, for small cases.
"""

import math

import numpy as np

from .errors import InputError
from .kernels import SUPPORT_FACTOR
from .lattice import Frame, Lattice
from .memory import BUILD_BYTES_PER_PARTICLE, available_bytes, too_many
from .sources import LatticePoints


def support_layers(h_factor):
    """Lattice layers that cover one kernel support, SUPPORT_FACTOR h = SUPPORT_FACTOR h_factor dp:
    how deep dummy walls (or a clamp) must be."""
    return int(np.ceil(SUPPORT_FACTOR * h_factor))


def lattice_layers(length, dp):
    """How many lattice layers of spacing dp a side ``length`` long holds: floor(length / dp)."""
    return int(np.floor(length / dp + 1e-9))


def lattice_mismatch(symbol, length, dp):
    """A one-line warning when the side ``symbol`` (``length`` long) is not a whole number of
    spacings dp, so that its lattice fill falls short of it by up to dp; else None. A fill short
    by less than 1 % of dp (a dp typed to four digits) is not warned."""
    n = lattice_layers(length, dp)
    if length / dp - n < 0.01:
        return None
    return (f"{symbol} = {length:.4g} m is {length / dp:.4g} dp: the lattice fills {n} layers, {n * dp:.4g} m; "
            f"choose dp = {symbol} / n for a whole number n")


def _within_memory(counts, dp, what):
    """Refuse, before allocating it, a lattice of prod(``counts``) points that this machine could not
    even hold while the case is built (memory.too_many says how much a run would need)."""
    count = math.prod(int(c) for c in counts)
    available = available_bytes()
    if available is not None and count * BUILD_BYTES_PER_PARTICLE > available:
        raise InputError(too_many(count, f"dp = {dp:g} m fills {what} with", available))


def _layer_counts(lo, hi, dp, what):
    """Lattice layers along each side of the box [lo, hi]; InputError if a side holds none."""
    counts = [lattice_layers(b - a, dp) for a, b in zip(lo, hi)]
    if min(counts) < 1:
        a = int(np.argmin(counts))
        raise InputError(f"spacing dp={dp:g} m is larger than {what} ({hi[a] - lo[a]:g} m across)")
    return counts


def along(axis):
    """The function that gives each of the positions x the unit normal along ``axis`` (-1: the
    last, upwards), for the walls whose particles all face one way."""
    def normal(x):
        out = np.zeros_like(x)
        out[:, axis] = 1.0
        return out
    return normal


def block(lo, hi, dp, what="the box", normal=None, keep=None):
    """The cell-centred lattice filling the box [lo, hi] (2D or 3D), as a source (with ``normal``,
    positions -> unit normals, a wall's; with ``keep``, positions -> bool mask, only the points it
    keeps: a slope cut from the box, for example)."""
    counts = _layer_counts(lo, hi, dp, what)
    return LatticePoints(Lattice((0,) * len(lo), tuple(counts), dp, Frame(origin=tuple(map(float, lo)))),
                         keep=keep, normal=normal)


def box(lo, hi, dp, what="the box"):
    """Cell-centred lattice filling the box [lo, hi] (2D or 3D)."""
    points = block(lo, hi, dp, what)
    _within_memory([points.size], dp, what)
    return points.everything()[0]


def disk(centre, radius, dp, what="the disk"):
    """Lattice points (spacing dp, one point at the centre) inside a circle or sphere."""
    centre = np.asarray(centre, dtype=float)
    if 2 * radius < dp:
        raise InputError(f"spacing dp={dp:g} m is larger than {what} ({2 * radius:g} m across)")
    m = int(np.ceil(radius / dp))
    _within_memory([2 * m + 1] * len(centre), dp, what)
    axis = np.arange(-m, m + 1) * dp
    grids = np.meshgrid(*([axis] * len(centre)), indexing="ij")
    pts = np.stack([g.ravel() for g in grids], axis=1)
    return centre + pts[np.sum(pts**2, axis=1) < radius**2]


def upright_cylinder(base, radius, height, dp, what="the cylinder"):
    """The cell-centred lattice inside an upright cylinder standing on ``base`` (x, y, z of the centre
    of its bottom face), as a source: points at base + (i + 1/2) dp along each axis, so the fill is
    symmetric about the x-z and y-z planes through the axis and holds floor(height / dp) layers,
    a layer at a time from the bottom."""
    if 2 * radius < dp:
        raise InputError(f"spacing dp={dp:g} m is larger than {what} ({2 * radius:g} m across)")
    layers = lattice_layers(height, dp)
    if layers < 1:
        raise InputError(f"spacing dp={dp:g} m is larger than {what} ({height:g} m high)")
    m = int(np.ceil(radius / dp))
    frame = Frame(origin=tuple(map(float, base)), axes=((0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (1.0, 0.0, 0.0)))

    def inside(x):
        return (x[:, 0] - base[0]) ** 2 + (x[:, 1] - base[1]) ** 2 < radius**2

    return LatticePoints(Lattice((0, -m, -m), (layers, m, m), dp, frame), keep=inside,
                         estimate=math.pi * radius**2 * layers / dp**2)


def bed_layers(lo, hi, dp, layers, keep=None):
    """Dummy particles of a flat bed whose surface is the plane {last coordinate = 0} under the
    footprint [lo, hi] of the other axes (x in 2D, x and y in 3D), as a source: ``layers`` lattice
    layers, the shallowest first, with upward normals; ``keep`` (positions -> mask) trims the
    footprint. ``depth`` gives a particle's depth below the surface (Morris walls)."""
    counts = _layer_counts(lo, hi, dp, "the bed")
    dim = len(lo) + 1
    axes = np.zeros((dim, dim))  # lattice axis 0 points down, the others along the footprint
    axes[-1, 0] = -1.0
    for a in range(dim - 1):
        axes[a, a + 1] = 1.0
    frame = Frame(origin=tuple(map(float, lo)) + (0.0,), axes=tuple(map(tuple, axes)))
    return LatticePoints(Lattice((0,) * dim, (layers, *counts), dp, frame), keep=keep, normal=along(-1))


def depth(x):
    """The depth below the plane {last coordinate = 0} of a ``bed_layers`` particle."""
    return -x[:, -1]


def bed(lo, hi, dp, layers):
    """The arrays (positions, upward unit normals, depths below the surface) of ``bed_layers``."""
    points = bed_layers(lo, hi, dp, layers)
    _within_memory([points.size], dp, "the bed")
    x, normal = points.everything()
    return x, normal, depth(x)


class _BoxShell(LatticePoints):
    """The lattice of ``walls_around`` fitted to a box whose side along axis a is ``excess[a]``
    longer than ``counts[a]`` whole spacings: the far side's layers (index >= ``counts[a]``) move
    out by the excess, so that they start dp/2 beyond the far side as the near side's start dp/2
    before the near one, and the layers across the side (index 0 .. counts[a] - 1) spread evenly
    over it, at a spacing (1 + excess / (counts dp)) dp, so that no gap wider than a spacing opens
    where they meet the far side's."""

    def __init__(self, lattice, counts, excess, **kw):
        super().__init__(lattice, **kw)
        self.counts = counts
        self.excess = excess

    def placed(self, index):
        """Positions of the points with linear indices ``index``."""
        x = self.lattice.points(index)
        tuples = np.unravel_index(np.asarray(index, np.int64), self.lattice.shape)
        lo = self.lattice.frame.origin
        for a, (t, first) in enumerate(zip(tuples, self.lattice.first)):
            e, n = self.excess[a], self.counts[a]
            if e > 0.0:
                t = t + first
                across = (t >= 0) & (t < n)
                stretched = lo[a] + (x[:, a] - lo[a]) * (1.0 + e / (n * self.lattice.dp))
                x[:, a] = np.where(t >= n, x[:, a] + e, np.where(across, stretched, x[:, a]))
        return x

    def window(self, axis, lo, hi):
        # a superset: points move outwards along each axis, by at most the excess; the points inside
    # the box are never generated
        index = self.lattice.window(axis, lo - self.excess[axis], hi, hollow=[(0, n) for n in self.counts])
        x = self.placed(index)
        inside = (x[:, axis] >= lo) & (x[:, axis] < hi)
        return self.kept(index[inside], x[inside])

    def position(self, index):
        return self.placed(np.array([index]))[0]


def walls_around(lo, hi, dp, layers, open_sides=()):
    """Dummy wall particles in ``layers`` lattice layers around the box [lo, hi], as a source.

    ``open_sides`` names sides left without wall, e.g. ``("+y",)`` for an
    open top. Every side's layers start dp/2 behind it, on a side that is not a whole number of
    spacings too: the far side's are moved out by the excess and the layers across the side spread
    over it (``_BoxShell``). The normal of a wall particle is the unit vector from it to the nearest
    point of the box.
    """
    lo = np.asarray(lo, dtype=float)
    hi = np.asarray(hi, dtype=float)
    counts = [lattice_layers(b - a, dp) for a, b in zip(lo, hi)]
    excess = [b - a - n * dp for a, b, n in zip(lo, hi, counts)]
    excess = [e if e > 1e-9 * dp else 0.0 for e in excess]  # a whole number of spacings to round-off
    first = [-layers] * len(lo)
    last = [n + layers for n in counts]
    for side in open_sides:
        a = "xyz".index(side[1])
        if side[0] == "+":
            last[a] = counts[a]
            excess[a] = 0.0  # no far side's layers to meet: the layers across keep the lattice's spacing
        else:
            first[a] = 0
    lattice = Lattice(tuple(first), tuple(last), dp, Frame(origin=tuple(lo)))

    def outside(x):
        return ~np.all((x > lo) & (x < hi), axis=1)

    def towards_box(x):
        towards = np.clip(x, lo, hi) - x
        return towards / np.linalg.norm(towards, axis=1)[:, None]

    return _BoxShell(lattice, counts, excess, keep=outside, normal=towards_box,
                     estimate=lattice.size - math.prod(counts))


def depth_outside(lo, hi):
    """The function of positions giving their distance to the box [lo, hi], along the normals of
    ``walls_around``: the depth of its wall particles behind the wall surface (``Wall.distance``)."""
    lo = np.asarray(lo, dtype=float)
    hi = np.asarray(hi, dtype=float)
    return lambda x: np.linalg.norm(np.clip(x, lo, hi) - x, axis=1)


def box_walls(lo, hi, dp, layers, open_sides=()):
    """The arrays (positions, inward unit normals) of ``walls_around``."""
    walls = walls_around(lo, hi, dp, layers, open_sides)
    _within_memory([walls.estimate], dp, "the walls")
    return walls.everything()
