"""The SPH velocity gradient's pair sum, shared by the solids' stress updates (solid.py) and the
mu(I) strain rate (viscous_stress.py).

With the papers' r_ij = x_i - x_j and g_ij = grad_i W_ij = W' r_ij / r (kernels.py) it is

    M_i = -sum_j V_j (v_i - v_j) (x) g_ij,   V_j = m_j / rho_j,

the gradient of 004_ Eq. 31 and of 000_ Eq. 23 (printed there without the minus: solid.py
says why it is needed), which each caller multiplies by B_i (000_ Eq. 24) or takes as it is.
"""

from numba import njit

from ..kernels import pair_dw
from ..neighbours import pair_difference, pair_offset
from ..particles import WALL_SLIP, is_wall
from .walls import along_wall_normal, morris_relative_velocity, wall_relative_velocity


@njit(inline="always")
def gradient_sum(i, start, nbr, xc, v, mass, rho, kind, normal, wall_distance, beta_max, wall_density_of_i, k):
    """M_i of the module docstring as three rows of three scalars (the z row and column stay zero in
    2D). A wall partner j is seen from i:

    - its velocity mirrored (``beta_max <= 0``: 2 (v_i - v_w)) or Morris's (walls.py, 004_
      Eqs. 34-36), only the normal part on a free-slip wall;
    - its pair offset on a free-slip wall along the wall normal (walls.along_wall_normal);
    - its volume m_j / rho_j at its own density, or at i's with ``wall_density_of_i`` (the mu(I)
      scheme's walls, which carry i's state in every pair term, mu_i.momentum).
    """
    dim = xc.shape[1]
    m00 = m01 = m02 = m10 = m11 = m12 = m20 = m21 = m22 = 0.0
    for s in range(start[i], start[i + 1]):
        j = nbr[s]
        d0, d1, d2, r = pair_offset(xc, i, j)
        u0, u1, u2 = pair_difference(v, i, j)
        rho_j = rho[j]
        if is_wall(kind[j]):  # off the common path
            if beta_max > 0.0:
                u0, u1, u2 = morris_relative_velocity(i, j, xc, v, kind, normal, wall_distance, beta_max)
            else:
                u0, u1, u2 = wall_relative_velocity(i, j, v, kind, normal)
            if wall_density_of_i:
                rho_j = rho[i]
            if kind[j] == WALL_SLIP:
                d0, d1, d2 = along_wall_normal(j, normal, d0, d1, d2)
        f = -mass[j] / rho_j * pair_dw(k, r, i, j) / r
        m00 += f * u0 * d0
        m01 += f * u0 * d1
        m10 += f * u1 * d0
        m11 += f * u1 * d1
        if dim == 3:
            m02 += f * u0 * d2
            m12 += f * u1 * d2
            m20 += f * u2 * d0
            m21 += f * u2 * d1
            m22 += f * u2 * d2
    return (m00, m01, m02), (m10, m11, m12), (m20, m21, m22)
