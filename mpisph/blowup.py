"""Detection of a blown-up state: a non-finite value, a non-positive density or a moving particle
outside the domain."""

import math

from numba import njit

from .particles import MOVING

NON_FINITE, OUTSIDE, NON_POSITIVE_DENSITY = 1, 2, 3
PROBLEMS = {NON_FINITE: "a non-finite value", OUTSIDE: "a particle left the domain",
            NON_POSITIVE_DENSITY: "a non-positive density"}


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
