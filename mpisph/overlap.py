"""Bodies placed where they cannot start: behind a wall's surface, or on another particle; and
walls too thin to hold them, or outside the domain, where no material reaches them.

A wall particle j stands ``wall_distance`` d_j behind the wall's surface along its inward normal
n_j (dp/2 for the first layer, assumed where the wall declares no distance), so a material
particle i lies

    depth_ij = d_j - (x_i - x_j) . n_j

behind that surface as j sees it: -dp/2 or less for a body filled dp/2 in front of it, as every
shipped case is, and above 0 for a body that reaches into the wall (or a wall whose normals point
away from the material). Only wall particles nearer than dp to i are asked, so that a wall's far
layers and other walls' particles do not judge it.

A wall is as thick, behind a particle j of its surface (no wall particle straight in front of
it, less than dp/2 off j's normal line, nor any nearer than NEAR dp in front of it: where two
parts' lattices meet, a deeper particle has the other lattice's in front of it up to dp/sqrt(2)
off its line), as dp plus the depth behind j of the deepest wall
particle k within the kernel's support, (x_j - x_k) . n_j: dp for a wall of one layer, and at an
edge or a corner the depth along j's slanted normal. A material particle at the surface sees wall
particles out to the support's reach, support_layers of them on a lattice; with fewer the wall
pushes back on a part of the kernel only, and a fast flow passes through it (a barrier of one layer
at dp = 0.1 m let soil into it on the coarse flume). Other walls' particles count: a floor under a
wall's foot fills its support too.
"""

import math

import numpy as np
from numba import njit

from .errors import InputError
from .geometry import support_layers
from .neighbours import neighbour_lists
from .particles import WALL, WALL_SLIP, is_wall

DEPTH_REFUSED = 0.25  # in dp: a body particle deeper than this behind a wall's surface is refused
THIN_SLACK = 0.5  # in dp: a wall thinner than its layers' due thickness less this is warned of
NEAR = 1.25  # in dp: a wall particle this near in front of another covers it (its lattice's diagonal is 1.41)


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


@njit(cache=True)
def wall_thickness(n, start, nbr, x, normal, dp, thickness):
    """``thickness`` [0, n) of each wall particle on its wall's surface behind it (module docstring),
    nan for the particles behind another; ``start``, ``nbr`` list the wall particles around each."""
    dim = x.shape[1]
    for i in range(n):
        deepest, covered = 0.0, False
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            r2, along = 0.0, 0.0
            for a in range(dim):
                d = x[i, a] - x[j, a]
                r2 += d * d
                along += d * normal[i, a]
            deepest = max(deepest, along)
            in_front = along < -0.5 * dp
            covered = covered or (in_front and (r2 - along * along < 0.25 * dp * dp or r2 < (NEAR * dp) ** 2))
        thickness[i] = np.nan if covered else dp + deepest


def _by_wall(comm, gids, values, id_ranges):
    """{wall name: (count, least value)} over every rank of the particles ``gids`` with ``values``,
    named by the bodies' and walls' global id ranges ``id_ranges`` (Case.id_ranges)."""
    firsts = np.array([first for _, (first, _) in id_ranges])
    owner = np.searchsorted(firsts, gids, side="right") - 1
    local = {id_ranges[k][0]: (int(np.count_nonzero(owner == k)), float(values[owner == k].min()))
             for k in np.unique(owner)}
    found = {}
    for part in comm.allgather(local):
        for name, (count, least) in part.items():
            total, smallest = found.get(name, (0, np.inf))
            found[name] = (total + count, min(smallest, least))
    return found


def outside_domain_warnings(comm, pa, domain, periodic, dp, id_ranges):
    """A warning for each wall with particles more than dp/2 outside the domain along a
    non-periodic axis, where no material can reach them (collective; the owned particles)."""
    lo, hi = (np.asarray(c, float) for c in domain)
    x, n = pa.x[:pa.n_owned], pa.n_owned
    beyond = np.maximum(lo - x, x - hi)[:, ~np.asarray(periodic, bool)].max(axis=1, initial=-np.inf)
    out = np.flatnonzero(np.isin(pa.kind[:n], (WALL, WALL_SLIP)) & (beyond > 0.5 * dp))
    box = " to ".join("(" + ", ".join(f"{c:g}" for c in corner) + ")" for corner in (lo, hi))
    return [f"wall {name!r}: {count} of its particles lie outside the domain {box}, up to {-least:.3g} m, where "
            "no material reaches them"
            for name, (count, least) in sorted(_by_wall(comm, pa.gid[out], -beyond[out], id_ranges).items())]


def thin_wall_warnings(comm, pa, dp, h_factor, support, origin, id_ranges):
    """A warning for each wall thinner than support_layers(h_factor) layers behind some of its surface
    (collective; every rank's owned wall particles, with the ghosts around them)."""
    walls = np.flatnonzero(np.isin(pa.kind[:pa.n], (WALL, WALL_SLIP)))  # the owned ones first, then the ghosts
    owned = int(np.count_nonzero(walls < pa.n_owned))
    x = np.ascontiguousarray(pa.x[walls])
    start, nbr = neighbour_lists(x, pa.gid[walls], np.zeros(len(walls), np.int8), owned, support, origin)
    thickness = np.empty(owned)
    wall_thickness(owned, start, nbr, x, pa.normal[walls], dp, thickness)
    layers = support_layers(h_factor)
    thin = np.flatnonzero(thickness < (layers - THIN_SLACK) * dp)
    found = _by_wall(comm, pa.gid[walls[thin]], thickness[thin], id_ranges)
    return [f"wall {name!r} is {least / dp:.2g} dp thick behind {count} of its surface particles, where the "
            f"kernel reaches {support / dp:.2g} dp: material can pass through it; give it {layers} layers "
            "(a thicker wall or a smaller dp)" for name, (count, least) in sorted(found.items())]
