"""What a material particle sees of a fixed dummy wall particle.

A wall particle j has a wall velocity v_w and an inward normal n_w. In the
pairwise sums a material particle i sees it with a mirrored velocity: the
whole relative velocity mirrored for a no-slip wall (v_j = 2 v_w - v_i),
only its normal part for a free-slip wall. Densities, pressures and stresses
of the partner are chosen by each material (fluid: hydrostatic pressure
extrapolation; solids: the wall takes the stress of particle i).
"""

from numba import njit

from ..particles import WALL, is_wall


@njit(cache=True)
def wall_relative_normal(i, j, v, normal, dim):
    """(v_i - v_w) . n_w for wall particle j."""
    s = 0.0
    for a in range(dim):
        s += (v[i, a] - v[j, a]) * normal[j, a]
    return s


@njit(cache=True)
def relative_velocity(i, j, v, kind, normal, dim, out):
    """out = v_i - v_j, with the mirrored wall velocity when j is a wall particle."""
    if not is_wall(kind[j]):
        for a in range(dim):
            out[a] = v[i, a] - v[j, a]
    elif kind[j] == WALL:
        for a in range(dim):
            out[a] = 2.0 * (v[i, a] - v[j, a])
    else:
        vn = wall_relative_normal(i, j, v, normal, dim)
        for a in range(dim):
            out[a] = 2.0 * vn * normal[j, a]


@njit(cache=True)
def velocity_jump(i, j, v, kind, normal, e, dim, dv):
    """u_jump = (v_i - v_j) . e_ij, the wall's mirrored velocity when j is a wall; ``dv`` gets v_i - v_j."""
    relative_velocity(i, j, v, kind, normal, dim, dv)
    s = 0.0
    for a in range(dim):
        s += dv[a] * e[a]
    return s
