"""Detection of a blown-up state: a non-finite value, a non-positive density, a moving particle
outside the domain, or two particles at the same place (which no pair sum can divide by)."""

import math

import numpy as np
from numba import njit

from .particles import MOVING

NON_FINITE, OUTSIDE, NON_POSITIVE_DENSITY, COINCIDENT = 1, 2, 3, 4
PROBLEMS = {NON_FINITE: "a non-finite value", OUTSIDE: "a particle left the domain",
            NON_POSITIVE_DENSITY: "a non-positive density", COINCIDENT: "two particles at the same place"}


@njit(cache=True)
def first_bad_particle(n, kind, x, v, rho, lo, hi, periodic):
    """(index, problem) of the first moving particle in [0, n) with a non-finite position, velocity
    or density (NON_FINITE), a density <= 0 (NON_POSITIVE_DENSITY), or outside [lo, hi) on a
    non-periodic axis (OUTSIDE); (-1, 0) if none."""
    dim = x.shape[1]
    for i in range(n):
        if kind[i] != MOVING:
            continue
        if not math.isfinite(rho[i]):
            return i, NON_FINITE
        if rho[i] <= 0.0:
            return i, NON_POSITIVE_DENSITY
        for a in range(dim):
            if not (math.isfinite(x[i, a]) and math.isfinite(v[i, a])):
                return i, NON_FINITE
        for a in range(dim):
            if not periodic[a] and not (lo[a] <= x[i, a] < hi[a]):
                return i, OUTSIDE
    return -1, 0


@njit(inline="always")
def _squared_distance(x, i, j):
    d0, d1 = x[i, 0] - x[j, 0], x[i, 1] - x[j, 1]
    d2 = x[i, 2] - x[j, 2] if x.shape[1] == 3 else 0.0
    return d0 * d0 + d1 * d1 + d2 * d2


@njit(cache=True)
def first_coincident_pair(n, start, nbr, x):
    """(i, j) of the first owned particle i in [0, n) with a neighbour j at distance 0, whose pair
    terms would divide by it; (-1, -1) if none. The pass that finds the pair runs only when the
    smallest squared distance over the lists, a plain reduction, is 0."""
    closest = np.inf
    for i in range(n):
        for s in range(start[i], start[i + 1]):
            closest = min(closest, _squared_distance(x, i, nbr[s]))
    if closest > 0.0:
        return -1, -1
    for i in range(n):
        for s in range(start[i], start[i + 1]):
            if _squared_distance(x, i, nbr[s]) == 0.0:
                return i, nbr[s]
    return -1, -1
