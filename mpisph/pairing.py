"""Pairing told apart from the flow's squeeze: how many clustered particles the flow did not bring together.

instability.py's clustering counts particles nearer than dp/2 to another. Particles that follow the
material (no shift) have such neighbours wherever the flow has squeezed the material to less than
half its size along some direction: a collapsing soil cube does so without any instability
(docs/REMEDIES.md). This module compares each clustered pair with what the flow made of it. Around
each particle, the deformation gradient F since the run's first frame is fitted by least squares to
the separations of the material neighbours it then had within 1.5 dp (instability.py's link), as Falk
and Langer (1998) fit the affine part of a local rearrangement. A pair of moving particles nearer than
dp/2 is *paired* when its distance is below half of |F X_0|, the image of its first separation X_0
under the pair's mean F: the same factor one half that clustering applies to the lattice spacing.

The fit needs the first-frame neighbourhoods to survive, as they do in solids and soils; in a fluid
that has mixed they do not, and the measure says nothing.
"""

import numpy as np
from numba import njit

from .instability import CLUSTER_DISTANCE, LINK_DISTANCE, spacing
from .materials import ElasticConstants
from .neighbours import neighbour_lists
from .particles import MOVING

PAIRED_RATIO = 0.5  # a pair nearer than this share of its deformed first separation is paired


def applies(case):
    """Whether the measure means something for ``case``: an elastic solid or a soil (their particles
    keep their neighbours) on a domain without periodic axes (whose wraps the fit would see as jumps)."""
    return isinstance(case.material, ElasticConstants) and not any(case.periodic)


def _moving(frame):
    """(positions, global ids, kinds, spacing dp) of the moving particles of ``frame``."""
    moving = frame["kind"] == MOVING
    return frame["x"][moving], frame["gid"][moving], frame["kind"][moving], spacing(frame)


@njit(cache=True)
def nearest_partners(n, start, nbr, x, out):
    """``out[i]``: the nearest of the listed neighbours of each particle i in [0, n), -1 if none."""
    for i in range(n):
        best, out[i] = np.inf, -1
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            d = 0.0
            for a in range(x.shape[1]):
                d += (x[j, a] - x[i, a]) ** 2
            if d < best:
                best, out[i] = d, j


@njit(cache=True)
def separation_moments(rows, start, nbr, x0, x, XX, XY):
    """For particle i = rows[k]: ``XX[k]`` = sum_j X (x) X and ``XY[k]`` = sum_j X (x) Y over its
    listed neighbours j, X = x0[j] - x0[i] its first separation and Y = x[j] - x[i] the one now
    (rows of x and x0 alike); the least-squares F with F X ~ Y solves XX F^T = XY."""
    dim = x0.shape[1]
    for k in range(len(rows)):
        i = rows[k]
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            for a in range(dim):
                for b in range(dim):
                    XX[k, a, b] += (x0[j, a] - x0[i, a]) * (x0[j, b] - x0[i, b])
                    XY[k, a, b] += (x0[j, a] - x0[i, a]) * (x[j, b] - x[i, b])


def _rows_of(gids, among):
    """The index in ``among`` of each global id of ``gids`` (all of them in ``among``)."""
    order = np.argsort(among, kind="stable")
    return order[np.searchsorted(among, gids, sorter=order)]


def clustered_pairs(frame, walls=False):
    """(i, j): each moving particle of ``frame`` with another moving particle (or, with ``walls``, any
    particle) nearer than dp/2, and that nearest one, as indices into ``frame``."""
    moving = frame["kind"] == MOVING
    rows = np.flatnonzero(moving)
    n = len(rows)
    if walls:
        rows = np.concatenate([rows, np.flatnonzero(~moving)])  # moving first: they get lists
    x = frame["x"][rows]
    start, nbr = neighbour_lists(x, frame["gid"][rows], frame["kind"][rows], n, CLUSTER_DISTANCE * spacing(frame),
                                 x.min(axis=0))
    partner = np.empty(n, np.int64)
    nearest_partners(n, start, nbr, x, partner)
    mine = np.flatnonzero(partner >= 0)
    return rows[mine], rows[partner[mine]]


def fitted_deformation(frame, first, rows):
    """The deformation gradient F since ``first`` (the run's first frame) of each particle of ``rows``
    (indices into ``frame``, moving particles): the least-squares F that maps its first-frame
    separations to the moving particles then within 1.5 dp onto their separations now."""
    x0, gid0, kind0, dp = _moving(first)
    start, nbr = neighbour_lists(x0, gid0, kind0, len(x0), LINK_DISTANCE * dp, x0.min(axis=0))
    now = frame["x"][_rows_of(gid0, frame["gid"])]  # the first frame's moving particles, where they are now
    XX, XY = (np.zeros((len(rows), x0.shape[1], x0.shape[1])) for _ in range(2))
    separation_moments(_rows_of(frame["gid"][rows], gid0), start, nbr, x0, now, XX, XY)
    return np.linalg.solve(XX, XY).transpose(0, 2, 1)


def pair_deformations(frame, first, i, j):
    """The ``fitted_deformation`` of each end of the pairs (``i``, ``j``): (F_i, F_j), each particle fitted once."""
    ends, which = np.unique(np.concatenate([i, j]), return_inverse=True)
    F = fitted_deformation(frame, first, ends)[which]
    return F[:len(i)], F[len(i):]


def affine_ratio(frame, first, i, j, deformations=None):
    """(ratio, |X_0|) of each pair (``i``, ``j``) of moving particles of ``frame``: its distance over
    |F X_0|, X_0 its separation in ``first`` and F the mean of the pair's ``fitted_deformation``
    (``deformations``: ``pair_deformations``' result, if at hand). Near 1: the pair is as close as the
    flow around it made it; below 1/2: paired."""
    F_i, F_j = pair_deformations(frame, first, i, j) if deformations is None else deformations
    F = 0.5 * (F_i + F_j)
    i0, j0 = (_rows_of(frame["gid"][k], first["gid"]) for k in (i, j))
    separation = first["x"][j0] - first["x"][i0]
    image = np.einsum("kab,kb->ka", F, separation)
    return (np.linalg.norm(frame["x"][j] - frame["x"][i], axis=1) / np.linalg.norm(image, axis=1),
            np.linalg.norm(separation, axis=1))


def paired_share(frame, first):
    """The share of the moving particles of ``frame`` that are paired (module docstring): nearer
    than dp/2 to another moving particle and than half their deformed first separation."""
    i, j = clustered_pairs(frame)
    n = int(np.sum(frame["kind"] == MOVING))
    if not len(i):
        return 0.0
    return float(np.sum(affine_ratio(frame, first, i, j)[0] < PAIRED_RATIO)) / n
