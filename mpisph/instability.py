"""A measure of tensile instability computed from a frame.

Two symptoms, as fractions of the moving particles, and one spacing:

- clustering: the nearest other particle (walls included) is closer than
  0.5 dp;
- inner voids: the particle is surrounded (moving particles between 1.5 dp
  and 4 h away in each of 8 directions: 45-degree sectors in 2D, octants in
  3D; the two particle layers under a free surface are not, and a gap wider
  than about 4 h counts as free surface: a crack) yet its position divergence (000_ Eq. 31, walls included) is below
  the free-surface threshold 0.75 d, i.e. a hole opened next to it inside
  the body;
- min_spacing: the smallest nearest-neighbour distance over dp, a graded
  early sign (an undisturbed lattice gives 1; particles pairing up under
  tension in an uncorrected beam come to about 0.55 before any pair is
  closer than 0.5 dp).

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
SECTORS = 8
SURROUNDING_SHELL = 1.5  # times dp: particles this far out count for "surrounded" ...
SURROUNDING_REACH = 4.0  # times h: ... up to this distance


@njit(cache=True)
def nearest_and_surrounded(n, start, nbr, x, kind, r_far, nearest, surrounded):
    """Distance to the nearest neighbour, and whether every direction has a moving
    neighbour at least ``r_far`` away (beyond the first shell)."""
    dim = x.shape[1]
    for i in range(n):
        if kind[i] != MOVING:
            continue
        best = np.inf
        seen = 0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            dx = x[j, 0] - x[i, 0]
            dy = x[j, 1] - x[i, 1]
            dz = x[j, 2] - x[i, 2] if dim == 3 else 0.0
            r = math.sqrt(dx * dx + dy * dy + dz * dz)
            best = min(best, r)
            if kind[j] != MOVING or r < r_far:
                continue
            if dim == 2:
                sector = int((math.atan2(dy, dx) + math.pi) / (2.0 * math.pi) * SECTORS) % SECTORS
            else:
                sector = (dx > 0.0) + 2 * (dy > 0.0) + 4 * (dz > 0.0)
            seen |= 1 << sector
        nearest[i] = best
        surrounded[i] = seen == (1 << SECTORS) - 1


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


def tensile_instability(frame, domain_lo=None, periodic_lengths=()):
    """{n, dp, clustering, inner_voids, surface, min_spacing} from ``read_frame(path, walls=True)``.

    ``periodic_lengths`` has the period of each axis (0 where not periodic),
    ``domain_lo`` the domain's lower corner.
    """
    x, kind, mass, rho = frame["x"], frame["kind"], frame["mass"], frame["rho"]
    dim = x.shape[1]
    moving = kind == MOVING
    n_moving = int(moving.sum())
    dp = float(np.median((mass[moving] / rho[moving]) ** (1.0 / dim)))
    kernel = Kernel(frame["params"].get("kernel", "wendland_c2"), frame["params"].get("h_factor", 1.3) * dp, dim)
    h = kernel.h
    order = np.argsort(~moving, kind="stable")  # moving particles first: they get lists
    x, kind, mass, rho, gid = x[order], kind[order], mass[order], rho[order], frame["gid"][order]
    if any(periodic_lengths):
        x, (kind, mass, rho, gid) = _with_periodic_images(x, [kind, mass, rho, gid], domain_lo,
                                                           periodic_lengths, kernel.support)
    n = len(x)
    start, nbr = neighbour_lists(x, gid, kind, n_moving, kernel.support, x.min(axis=0))
    div = np.zeros(n)
    position_divergence(n_moving, start, nbr, x, mass, rho, kind, kernel.params, div)
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
    }
