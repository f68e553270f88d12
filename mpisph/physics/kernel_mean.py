"""Kernel means of the moving particles' fields: the smoothing that the mu(I) law's inputs take
with the options law_strain_rate and law_pressure (mu_i.py says why).

    q_bar_i = sum_j V_j q_j W_ij / sum_j V_j W_ij,   V_j = m_j / rho_j,

over the moving particles j, i among them (the walls hold no grains). The mean keeps a uniform
field exactly and a smooth one to second order in h; it is a low-pass filter that takes out the
grain-to-grain scatter of a field, which is not a field of the continuum
(tests/test_law_strain_rate.py).
"""

import numpy as np
from numba import njit

from ..kernels import pair_w
from ..neighbours import pair_distance
from ..particles import MOVING


@njit(cache=True)
def kernel_mean(n, start, nbr, xc, rho, mass, kind, q, k, out):
    """out_i = the kernel mean of the rows q_j (q of shape (N, c)) of the moving particles i (module
    docstring); the other rows of ``out`` are left alone. Needs q on the ghosts."""
    size = q.shape[1]
    for i in range(n):
        if kind[i] != MOVING:
            continue
        w = mass[i] / rho[i] * pair_w(k, 0.0, i, i)
        total = w
        for c in range(size):
            out[i, c] = w * q[i, c]
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            if kind[j] != MOVING:
                continue
            w = mass[j] / rho[j] * pair_w(k, pair_distance(xc, i, j), i, j)
            total += w
            for c in range(size):
                out[i, c] += w * q[j, c]
        for c in range(size):
            out[i, c] /= total


@njit(cache=True)
def rate_modulus(n, kind, strain, deviatoric, dim, gamma_dot):
    """gamma_dot_i = sqrt(2 e_i : e_i) of the packed strain rates e_i (tensors.py: the diagonal first)
    of the moving particles, with ``deviatoric`` of the deviator e_i - tr(e_i) / D I instead."""
    size = strain.shape[1]
    for i in range(n):
        if kind[i] != MOVING:
            continue
        mean_normal = 0.0
        if deviatoric:
            for c in range(dim):
                mean_normal += strain[i, c]
            mean_normal /= dim
        norm = 0.0
        for c in range(size):
            if c < dim:
                e = strain[i, c] - mean_normal
                norm += e * e
            else:
                norm += 2.0 * strain[i, c] * strain[i, c]
        gamma_dot[i] = np.sqrt(2.0 * norm)
