"""Smoothing kernels: Wendland C2 and the cubic B-spline, in 2D and 3D.

Both have compact support 2h. The papers use Wendland C2 with h = 1.3 dp
(000_ Sec. 4, 001_ Sec. 4). Kernels are selected by an integer id so that the
numba loops can take it as a plain argument.

Conventions used throughout mpisph: r_ij = x_i - x_j, e_ij = r_ij / |r_ij|
(pointing from j to i), grad_i W_ij = W'(r_ij) e_ij with W' <= 0.
"""

import math

from numba import njit

WENDLAND_C2 = 0
CUBIC_SPLINE = 1

KERNELS = {"wendland_c2": WENDLAND_C2, "cubic_spline": CUBIC_SPLINE}

SUPPORT_FACTOR = 2.0  # support radius = SUPPORT_FACTOR * h for every kernel here


@njit(cache=True)
def normalisation(kernel, h, dim):
    """Normalisation constant sigma_d of the kernel in `dim` dimensions."""
    if kernel == WENDLAND_C2:
        if dim == 2:
            return 7.0 / (4.0 * math.pi * h * h)
        return 21.0 / (16.0 * math.pi * h * h * h)
    if dim == 2:
        return 10.0 / (7.0 * math.pi * h * h)
    return 1.0 / (math.pi * h * h * h)


@njit(cache=True)
def w(r, h, sigma, kernel):
    """Kernel value W(r, h); sigma from `normalisation`."""
    q = r / h
    if q >= 2.0:
        return 0.0
    if kernel == WENDLAND_C2:
        t = 1.0 - 0.5 * q
        return sigma * t * t * t * t * (2.0 * q + 1.0)
    if q < 1.0:
        return sigma * (1.0 - 1.5 * q * q + 0.75 * q * q * q)
    t = 2.0 - q
    return sigma * 0.25 * t * t * t


@njit(cache=True)
def dw(r, h, sigma, kernel):
    """Radial derivative dW/dr (non-positive)."""
    q = r / h
    if q >= 2.0:
        return 0.0
    if kernel == WENDLAND_C2:
        t = 1.0 - 0.5 * q
        return -5.0 * sigma / h * q * t * t * t
    if q < 1.0:
        return sigma / h * (-3.0 * q + 2.25 * q * q)
    t = 2.0 - q
    return -0.75 * sigma / h * t * t
