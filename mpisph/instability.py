"""A measure of tensile instability computed from a frame.

Three symptoms, as fractions of the moving particles, one count and one spacing:

- clustering: the nearest other particle (walls included) is closer than
  0.5 dp;
- inner voids: the particle is surrounded (moving particles between 1.5 dp
  and 4 h away in each of the 8 directions of a square's neighbours in 2D,
  the 26 of a cube's in 3D (``direction_bin``); the two particle layers
  under a free surface are not, and a gap wider than about 4 h counts as
  free surface: a crack) yet its position divergence (000_ Eq. 31, walls included) is below
  the free-surface threshold 0.75 d, i.e. a hole opened next to it inside
  the body;
- min_spacing: the smallest nearest-neighbour distance over dp, a graded
  early sign (an undisturbed lattice gives 1; particles pairing up under
  tension in an uncorrected beam come to about 0.55 before any pair is
  closer than 0.5 dp);
- fragments and detached: the body's pieces. Two moving particles nearer than
  1.5 dp are linked (a lattice's nearest neighbours at 1 dp, and its diagonal
  ones at 1.41 dp, are; two faces of a crack 1.5 dp or more apart are not),
  and a fragment is a connected set of linked particles: ``fragments`` counts
  them (a particle on its own is one), ``detached`` is the fraction of the
  moving particles outside the largest. A fracture across the body shows
  there where clustering and voids see nothing: the uncorrected beam breaks
  off at its clamp while no pair comes nearer than 0.55 dp. Walls link
  nothing: two pieces resting on one floor are two fragments.

The spacing dp is recovered from the particle volumes, h and the kernel from
the frame's parameters; periodic axes (lengths given by the caller) get
images of the particles near their ends.
"""

import math

import numpy as np
from numba import njit

from .kernels import Kernel
from .neighbours import neighbour_lists
from .particles import MOVING
from .surface import SURFACE_THRESHOLD, position_divergence

CLUSTER_DISTANCE = 0.5  # times dp
LINK_DISTANCE = 1.5  # times dp: particles of one fragment
BIN_TAN = math.tan(math.pi / 8)  # direction_bin: a component counts beyond this share of the largest
SURROUNDING_SHELL = 1.5  # times dp: particles this far out count for "surrounded" ...
SURROUNDING_REACH = 4.0  # times h: ... up to this distance


@njit(cache=True)
def direction_bin(d, dim):
    """Which of the 3^dim - 1 lattice directions (the 8 of a square's neighbours, the 26 of a cube's)
    the offset ``d`` falls under: each component counts as its sign where it is at least
    tan(22.5 degrees) times the largest, as 0 otherwise. A neighbour in a plane through the particle
    never falls under a direction out of that plane, so a lattice's face particle has every direction
    beyond its face empty (octants, split by the sign of each component, put its in-plane neighbours
    on one side of the face)."""
    largest = 0.0
    for a in range(dim):
        largest = max(largest, abs(d[a]))
    k = 0
    scale = 1
    for a in range(dim):
        if d[a] >= BIN_TAN * largest:
            k += 2 * scale
        elif d[a] > -BIN_TAN * largest:
            k += scale
        scale *= 3
    return k


@njit(cache=True)
def nearest_and_surrounded(n, start, nbr, x, kind, r_far, nearest, surrounded):
    """Distance to the nearest neighbour, and whether every lattice direction (``direction_bin``) has
    a moving neighbour at least ``r_far`` away (beyond the first shell)."""
    dim = x.shape[1]
    d = np.zeros(dim)
    every = (1 << 3 ** dim) - 1 - (1 << (3 ** dim - 1) // 2)  # every bin but the centre's
    for i in range(n):
        if kind[i] != MOVING:
            continue
        best = np.inf
        seen = 0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            r2 = 0.0
            for a in range(dim):
                d[a] = x[j, a] - x[i, a]
                r2 += d[a] * d[a]
            r = math.sqrt(r2)
            best = min(best, r)
            if kind[j] != MOVING or r < r_far:
                continue
            seen |= 1 << direction_bin(d, dim)
        nearest[i] = best
        surrounded[i] = seen == every


@njit(cache=True)
def _root(parent, i):
    """The representative of i's set, halving the path on the way."""
    while parent[i] != i:
        parent[i] = parent[parent[i]]
        i = parent[i]
    return i


@njit(cache=True)
def fragment_sizes(n, start, nbr, x, kind, owner, link):
    """Sizes of the fragments of the moving particles [0, n) (module docstring): linked when nearer
    than ``link``; ``owner`` maps every row (periodic images included) to the moving particle it is."""
    parent = np.arange(n)
    dim = x.shape[1]
    for i in range(n):
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            if kind[j] != MOVING:
                continue
            r2 = 0.0
            for a in range(dim):
                d = x[j, a] - x[i, a]
                r2 += d * d
            if r2 < link * link:
                a_root, b_root = _root(parent, i), _root(parent, owner[j])
                if a_root != b_root:
                    parent[max(a_root, b_root)] = min(a_root, b_root)
    size = np.zeros(n, np.int64)
    for i in range(n):
        size[_root(parent, i)] += 1
    return size[size > 0]


def _with_periodic_images(x, arrays, lo, lengths, radius):
    """Append copies of the particles within ``radius`` of a periodic end, shifted by the period."""
    for a, length in enumerate(lengths):
        if not length:
            continue
        near_lo = x[:, a] < lo[a] + radius
        near_hi = x[:, a] >= lo[a] + length - radius
        shifted = [x]
        for mask, shift in ((near_lo, length), (near_hi, -length)):
            image = x[mask].copy()
            image[:, a] += shift
            shifted.append(image)
        arrays = [np.concatenate([v, v[near_lo], v[near_hi]]) for v in arrays]
        x = np.concatenate(shifted)
    return x, arrays


def spacing(frame):
    """The particle spacing dp of ``frame``: the median of its moving particles' volumes m / rho, to the
    power 1 / D."""
    moving = frame["kind"] == MOVING
    return float(np.median((frame["mass"][moving] / frame["rho"][moving]) ** (1.0 / frame["x"].shape[1])))


def tensile_instability(frame, domain_lo=None, periodic_lengths=()):
    """{n, dp, clustering, inner_voids, surface, min_spacing, fragments, detached} from
    ``read_frame(path, walls=True)``.

    ``periodic_lengths`` has the period of each axis (0 where not periodic),
    ``domain_lo`` the domain's lower corner.
    """
    x, kind, mass, rho = frame["x"], frame["kind"], frame["mass"], frame["rho"]
    dim = x.shape[1]
    moving = kind == MOVING
    n_moving = int(moving.sum())
    dp = spacing(frame)
    kernel = Kernel(frame["params"].get("kernel", "wendland_c2"), frame["params"].get("h_factor", 1.3) * dp, dim)
    h = kernel.h
    order = np.argsort(~moving, kind="stable")  # moving particles first: they get lists
    x, kind, mass, rho, gid = x[order], kind[order], mass[order], rho[order], frame["gid"][order]
    link = LINK_DISTANCE * dp
    reach = max(kernel.support, link)  # the support's lists hold the links too
    if any(periodic_lengths):
        x, (kind, mass, rho, gid) = _with_periodic_images(x, [kind, mass, rho, gid], domain_lo,
                                                           periodic_lengths, reach)
    n = len(x)
    start, nbr = neighbour_lists(x, gid, kind, n_moving, reach, x.min(axis=0))
    div = np.zeros(n)
    position_divergence(n_moving, start, nbr, x, mass, rho, kind, kernel.params, div)
    originals = np.argsort(gid[:n_moving])
    owner = originals[np.searchsorted(gid[:n_moving], gid, sorter=originals).clip(0, n_moving - 1)]
    sizes = fragment_sizes(n_moving, start, nbr, x, kind, owner, link)
    start, nbr = neighbour_lists(x, gid, kind, n_moving, SURROUNDING_REACH * h, x.min(axis=0))
    nearest = np.full(n, np.inf)
    surrounded = np.zeros(n, np.bool_)
    nearest_and_surrounded(n_moving, start, nbr, x, kind, SURROUNDING_SHELL * dp, nearest, surrounded)
    low = div[:n_moving] < SURFACE_THRESHOLD * dim
    return {
        "n": n_moving,
        "dp": dp,
        "clustering": float(np.mean(nearest[:n_moving] < CLUSTER_DISTANCE * dp)),
        "inner_voids": float(np.mean(low & surrounded[:n_moving])),
        "surface": float(np.mean(low & ~surrounded[:n_moving])),
        "min_spacing": float(nearest[:n_moving].min() / dp),
        "fragments": len(sizes),
        "detached": float(1.0 - sizes.max() / n_moving),
    }
