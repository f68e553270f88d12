"""What a material particle sees of a fixed dummy wall particle.

A wall particle j has a wall velocity v_w and an inward normal n_w. In the
pairwise sums a material particle i sees it with a mirrored velocity: the
whole relative velocity mirrored for a no-slip wall (v_j = 2 v_w - v_i),
only its normal part for a free-slip wall. The ghost-particle walls of
Morris et al. that the mu(I) scheme and the classic schemes of 002_ use (004_ Eqs. 34-36,
002_ Eq. 34; mu(I)'s corrected viscous stress keeps the mirror, physics/viscous_stress.py) scale the relative
velocity by beta = min(beta_max, 1 + d_j/d_i) instead of 2, from the
distances of the two particles to the wall surface. Densities, pressures and
stresses of the partner are chosen by each scheme (fluid: hydrostatic
pressure extrapolation; solids, the classic schemes and mu(I): the wall takes the state of
particle i).

``MorrisWalls`` is the ``configure`` step of the schemes with Morris's walls.

``wall_relative_velocity`` (mirror, beta = 2) and ``morris_relative_velocity`` both
give a wall partner's velocity through ``scaled_wall_velocity``. Pair loops
compute the plain difference v_i - v_j and call it only when j is a wall
particle, with the test written in the loop. That keeps the
common path straight-line code: moving the test and the call into one
helper, inlined or not, makes the loops slower: continuity of the 2D column
collapse at dp = 0.002 took 5.8 ms per call with an inlined helper instead of
1.3 ms.
"""

import numpy as np
from numba import njit

from ..errors import InputError
from ..particles import WALL, Field
from .density_reinit import reinitialise_density

WALL_DISTANCE = Field("wall_distance", (), np.float64, "distance behind the wall surface (walls only) [m]")


class MorrisWalls:
    """The ``configure`` of a scheme with Morris's walls (mu(I), the classic schemes): the wall
    distances to the ghosts, then the density by kernel summation where the case asks for it."""

    def configure(self, ctx):
        ctx.refresh(["wall_distance"])
        if reinitialise_density(ctx, self):
            ctx.refresh(["rho"])


def require_wall_distances(case, scheme):
    """InputError unless every wall of ``case`` gives ``Wall.distance``, which the Morris walls of
    scheme ``scheme`` (a name) read."""
    missing = [w.name for w in case.walls if w.distance is None]
    if missing:
        raise InputError(f"scheme {scheme} needs the distance of every wall particle to the wall surface "
                         f"(Wall.distance), which wall {missing[0]!r} lacks")


@njit(inline="always")
def along_wall_normal(j, normal, d0, d1, d2):
    """(d . n_j) n_j as three scalars: the pair offset d = x_i - x_j to free-slip wall particle j
    taken along the wall's normal, where the mirror image of i lies. Every scheme's pairs with a
    free-slip wall use it in the momentum and the velocity gradient (or strain rate) alike, and the
    mu(I) implicit kick in its pair directions: the wall then pushes only along its normal, and the
    pair forces do the work the strain rate stores, however irregular the wall lattice
    (physics/solid.py); on a regular flat wall the parts along it cancel anyway."""
    n2 = normal[j, 2] if normal.shape[1] == 3 else 0.0
    dn = d0 * normal[j, 0] + d1 * normal[j, 1] + d2 * n2
    return dn * normal[j, 0], dn * normal[j, 1], dn * n2


@njit(inline="always")
def wall_relative_normal(i, j, v, normal):
    """(v_i - v_w) . n_w for wall particle j."""
    s = 0.0
    for a in range(v.shape[1]):
        s += (v[i, a] - v[j, a]) * normal[j, a]
    return s


@njit(cache=True)
def scaled_wall_velocity(i, j, v, kind, normal, beta):
    """beta (v_i - v_w) for a no-slip wall particle j, beta ((v_i - v_w) . n_w) n_w for a free-slip
    one, as three scalars (the third is 0 in 2D)."""
    if kind[j] == WALL:
        u0 = beta * (v[i, 0] - v[j, 0])
        u1 = beta * (v[i, 1] - v[j, 1])
        u2 = beta * (v[i, 2] - v[j, 2]) if v.shape[1] == 3 else 0.0
    else:
        vn = beta * wall_relative_normal(i, j, v, normal)
        u0 = vn * normal[j, 0]
        u1 = vn * normal[j, 1]
        u2 = vn * normal[j, 2] if v.shape[1] == 3 else 0.0
    return u0, u1, u2


@njit(cache=True)
def wall_relative_velocity(i, j, v, kind, normal):
    """v_i - v_j as i sees wall particle j, mirrored: 2 (v_i - v_w) for a no-slip wall,
    2 ((v_i - v_w) . n_w) n_w for a free-slip wall."""
    return scaled_wall_velocity(i, j, v, kind, normal, 2.0)


@njit(cache=True)
def morris_relative_velocity(i, j, xc, v, kind, normal, wall_distance, beta_max):
    """v_i - v_j as i sees wall particle j in the ghost-particle walls of Morris et al. (004_
    Eqs. 34-36): beta (v_i - v_w) with beta = min(beta_max, 1 + d_j/d_i), d_j the wall particle's
    distance behind the wall surface (``wall_distance``) and d_i = (x_i - x_j).n_w - d_j the
    material particle's in front of it (beta_max when i is on or behind the surface); only the
    normal part for a free-slip wall."""
    return scaled_wall_velocity(i, j, v, kind, normal, morris_beta(i, j, xc, normal, wall_distance, beta_max))


@njit(cache=True)
def morris_beta(i, j, xc, normal, wall_distance, beta_max):
    """beta = min(beta_max, 1 + d_j/d_i) of 004_ Eq. 36 for wall particle j seen from i (the
    distances of ``morris_relative_velocity``; beta_max when i is on or behind the surface)."""
    d_j = wall_distance[j]
    d_i = -d_j
    for a in range(xc.shape[1]):
        d_i += (xc[i, a] - xc[j, a]) * normal[j, a]
    return min(beta_max, 1.0 + d_j / d_i) if d_i > 0.0 else beta_max
