"""Free-surface detection from the divergence of the position (000_ Eq. 31).

div r_i = -sum_j V_j r_ij . grad_i W_ij (mpisph's sign convention, see
kernels.py) is close to the dimension d inside a body and drops where the
kernel support is truncated; particles with div r < 0.75 d are on the free
surface (000_ Sec. 3.3).
"""

from numba import njit

from .kernels import dw
from .neighbours import pair_distance
from .particles import MOVING

SURFACE_THRESHOLD = 0.75  # times the dimension


@njit(cache=True)
def position_divergence(n, start, nbr, x, mass, rho, kind, h, sigma, kernel, out):
    """out_i = -sum_j V_j r_ij . grad_i W_ij for the moving particles in [0, n)."""
    for i in range(n):
        if kind[i] != MOVING:
            continue
        acc = 0.0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            r = pair_distance(x, i, j)
            acc -= mass[j] / rho[j] * r * dw(r, h, sigma, kernel)
        out[i] = acc
