"""The kernel-gradient correction matrix B of 000_ Eq. 24.

    B_i = (-sum_j V_j r_ij (x) grad_i W_ij)^-1

It corrects the velocity gradient of the Riemann solids (000_ Eq. 23) and
mu(I)'s strain rate and corrected viscous stress, gives the free-surface normal
of the unified transport-velocity shift (000_ Eq. 35), and corrects the
gradients by which particle shifting carries fields to a shifted place.
The inverse is regularised where the neighbourhood is degenerate (a free
corner, a splashed particle): with A = -sum_j V_j r_ij (x) grad W,
B = (adj A + w I) / (det A + w), w = max(0, a_min - det A), which is A^-1
wherever det A >= a_min = 0.2^d and blends towards the identity below.
B is stored packed (tensors.py).
"""

import numpy as np
from numba import njit

from .kernels import pair_dw
from .neighbours import pair_offset
from .particles import is_wall
from .tensors import adjugate, component

DEGENERATE_DET = 0.2  # a_min = DEGENERATE_DET ** d


@njit(cache=True)
def regularised_inverse(A, out):
    """out = (adj A + w I) / (det A + w) for a symmetric 2 x 2 or 3 x 3 A."""
    dim = A.shape[0]
    det = adjugate(A, out)
    w = max(0.0, DEGENERATE_DET ** dim - det)
    for a in range(dim):
        out[a, a] += w
    for a in range(dim):
        for b in range(dim):
            out[a, b] /= det + w


@njit(cache=True)
def correction_matrix(n, start, nbr, xc, mass, rho, kind, k, B):
    """B_i of 000_ Eq. 24 (regularised, packed) for the material particles in [0, n); zero for
    walls. The inverse of a symmetric A is symmetric to the bit (its cofactors are the same
    products)."""
    dim = xc.shape[1]
    A = np.empty((dim, dim))
    inverse = np.empty((dim, dim))
    for i in range(n):
        if is_wall(kind[i]):
            B[i, :] = 0.0
            continue
        a00 = a01 = a02 = a11 = a12 = a22 = 0.0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            d0, d1, d2, r = pair_offset(xc, i, j)
            f = -mass[j] / rho[j] * pair_dw(k, r, i, j) / r  # -V_j r_ij (x) grad W = f d (x) d
            a00 += f * d0 * d0
            a01 += f * d0 * d1
            a02 += f * d0 * d2
            a11 += f * d1 * d1
            a12 += f * d1 * d2
            a22 += f * d2 * d2
        A[0, 0], A[0, 1], A[1, 0], A[1, 1] = a00, a01, a01, a11
        if dim == 3:
            A[0, 2], A[2, 0], A[1, 2], A[2, 1], A[2, 2] = a02, a02, a12, a12, a22
        regularised_inverse(A, inverse)
        for a in range(dim):
            for b in range(a, dim):
                B[i, component(dim, a, b)] = inverse[a, b]
