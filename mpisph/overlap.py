"""Bodies placed where they cannot start: behind a wall's surface, or on another particle.

A wall particle j stands ``wall_distance`` d_j behind the wall's surface along its inward normal
n_j (dp/2 for the first layer, assumed where the wall declares no distance), so a material
particle i lies

    depth_ij = d_j - (x_i - x_j) . n_j

behind that surface as j sees it: -dp/2 or less for a body filled dp/2 in front of it, as every
shipped case is, and above 0 for a body that reaches into the wall (or a wall whose normals point
away from the material). Only wall particles nearer than dp to i are asked, so that a wall's far
layers and other walls' particles do not judge it.
"""

import math

import numpy as np
from numba import njit

from .errors import InputError
from .particles import is_wall

DEPTH_REFUSED = 0.25  # in dp: a body particle deeper than this behind a wall's surface is refused


@njit(cache=True)
def behind_walls(n, start, nbr, x, kind, normal, wall_distance, dp):
    """(count, i, j, depth): how many material particles in [0, n) lie deeper than DEPTH_REFUSED dp
    behind the surface of a wall particle nearer than dp, and of those the deepest (the first on a
    tie) with that wall particle and its depth; (0, -1, -1, 0.0) if none."""
    dim = x.shape[1]
    count, deepest_i, deepest_j, deepest = 0, -1, -1, 0.0
    for i in range(n):
        if is_wall(kind[i]):
            continue
        worst, worst_j = -math.inf, -1
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            if not is_wall(kind[j]):
                continue
            r2, along = 0.0, 0.0
            for a in range(dim):
                d = x[i, a] - x[j, a]
                r2 += d * d
                along += d * normal[j, a]
            if r2 >= dp * dp:
                continue
            behind = wall_distance[j] if math.isfinite(wall_distance[j]) else 0.5 * dp
            if behind - along > worst:
                worst, worst_j = behind - along, j
        if worst > DEPTH_REFUSED * dp:
            count += 1
            if worst > deepest:
                deepest_i, deepest_j, deepest = i, worst_j, worst
    return count, deepest_i, deepest_j, deepest


def check_start(comm, pa, start, nbr, xc, dp, coincident, name_of):
    """Raise InputError on every rank if any rank's material particles start behind a wall's surface
    or two particles start at the same place (``coincident``: first_coincident_pair's (i, j)).
    ``name_of`` gives the body or wall a global id belongs to."""
    distance = pa.arrays["wall_distance"] if "wall_distance" in pa.arrays else np.full(pa.n, np.nan)  # fluids: none
    count, i, j, depth = behind_walls(pa.n_owned, start, nbr, xc, pa.kind, pa.normal, distance, dp)
    local = (count, depth, None if i < 0 else (int(pa.gid[i]), int(pa.gid[j]), np.round(xc[i], 6).tolist()))
    reports = comm.allgather((local, None if coincident[0] < 0 else
                              tuple(int(pa.gid[k]) for k in coincident) + (np.round(xc[coincident[0]], 6).tolist(),)))
    total = sum(c for (c, _, _), _ in reports)
    if total:
        _, depth, (gi, gj, pos) = max((r for r, _ in reports if r[0]), key=lambda r: r[1])
        raise InputError(f"{total} particles of {name_of(gi)!r} start behind the surface of wall {name_of(gj)!r}, "
                         f"the deepest {depth / dp:.2f} dp (particle {gi} at {pos}): the body overlaps the wall, "
                         "or the wall's normals point away from the material")
    same = [c for _, c in reports if c is not None]
    if same:
        a, b, pos = same[0]
        raise InputError(f"particles {a} of {name_of(a)!r} and {b} of {name_of(b)!r} start at the same place, "
                         f"{pos}: two bodies, or a body and a wall, overlap")
