"""Transport-velocity corrections: position shifts towards zero-order consistency.

Three stabilisers, selectable per case (``--set stabiliser=...``), applied
once per advection step, i.e. after the Verlet update of the previous one
(000_ Eq. 42):

- ``tvf_limited`` (fluids without a free surface, 001_ Eqs. 14-16);
- ``tvf``: 000_ Eq. 30 on inner particles only;
- ``utvf``: 000_ Eqs. 30-37 on inner and free-surface particles alike.

With g_i = sum_j V_j grad_i W_ij, the shift of 000_ Eq. 30 is
dr_i = -2 alpha h^2 g_i, alpha = 0.2 (the minus sign is mpisph's convention
for grad W, kernels.py: g points towards the denser side). UTVF projects the
shift of free-surface particles (outermost and near-surface, surface.py) on
the tangent plane, dr - (dr.n) n (Eq. 36), with the normal from the colour
gradient corrected by B (Eqs. 32-35; one material, walls count as filled
space, so grad C_i = g_i and n = B g / |B g|), and leaves splashed particles
and those with div r < 0.6 d unshifted.

The limited variant, once per advection step (001_ Eqs. 14-16):

    g_i  = 2 sum_j V_j grad_i W_ij
    beta = min(C h^2 |g_i|^2, 1)  if h^2 |g_i|^2 > 5e-4, else 0    (C = 1000)
    dr_i = -0.2 beta h^2 g_i

g_i carries the factor 2 of the transport acceleration -2 sum_j m_j p0/(rho_i rho_j)
grad W_ij (001_ Eq. 12) from which Eq. 14 is derived: with p0 = 7 rho0 |v|_ad^2 and
dt_ad = 0.25 h/|v|_ad, 1/2 a dt_ad^2 = -0.44 h^2 sum_j V_j grad W_ij, i.e. 0.2 times this
g_i (SPHinXsys applies 0.2 h^2 to the same doubled residue, in the limiter as well).

(g points towards the denser side, so the shift is against it.) The shift is
meant for particles with a full kernel support: it is for flows without a
free surface; the free-surface variants (TVF on inner particles, UTVF) of
000_ build on the same gradient.
"""

import numpy as np
from numba import njit

from .. import surface
from ..kernels import pair_dw
from ..neighbours import pair_offset
from ..particles import MOVING
from ..tensors import size
from .base import Stabiliser

LIMITER_C = 1000.0
LIMITER_THRESHOLD = 5e-4
COEFFICIENT = 0.2
ALPHA = 0.2  # 000_ Eq. 30
NO_SHIFT_DIVERGENCE = 0.6  # times the dimension (000_ Sec. 3.3)


@njit(cache=True)
def kernel_gradient_sum(i, start, nbr, xc, mass, rho, k):
    """g_i = sum_j V_j grad_i W_ij as three scalars (the third is 0 in 2D); called once per particle."""
    g0 = g1 = g2 = 0.0
    for s in range(start[i], start[i + 1]):
        j = nbr[s]
        d0, d1, d2, r = pair_offset(xc, i, j)
        f = mass[j] / rho[j] * pair_dw(k, r, i, j) / r
        g0 += f * d0
        g1 += f * d1
        g2 += f * d2
    return g0, g1, g2


@njit(cache=True)
def limited_shift(n, start, nbr, xc, x, mass, rho, kind, k):
    """Add the limited transport-velocity shift of 001_ Eq. 16 to the positions ``x``."""
    dim = xc.shape[1]
    h2 = k.h * k.h
    for i in range(n):
        if kind[i] != MOVING:
            continue
        g0, g1, g2 = kernel_gradient_sum(i, start, nbr, xc, mass, rho, k)
        g0, g1, g2 = 2.0 * g0, 2.0 * g1, 2.0 * g2  # the doubled residue of the module docstring
        norm2 = h2 * (g0 * g0 + g1 * g1 + g2 * g2)
        if norm2 <= LIMITER_THRESHOLD:
            continue
        c = -COEFFICIENT * min(LIMITER_C * norm2, 1.0) * h2
        x[i, 0] += c * g0
        x[i, 1] += c * g1
        if dim == 3:
            x[i, 2] += c * g2


@njit(cache=True)
def consistency_shift(n, start, nbr, xc, x, mass, rho, kind, cls, div_r, B, unified, k):
    """Add dr of 000_ Eq. 30 (``unified`` false: inner particles only) or Eq. 37 to ``x``."""
    dim = xc.shape[1]
    scale = -2.0 * ALPHA * k.h * k.h
    for i in range(n):
        if kind[i] != MOVING:
            continue
        if cls[i] != surface.INNER and (not unified or cls[i] == surface.SPLASHED
                                        or div_r[i] < NO_SHIFT_DIVERGENCE * dim):
            continue
        g0, g1, g2 = kernel_gradient_sum(i, start, nbr, xc, mass, rho, k)
        if cls[i] != surface.INNER:  # Eq. 36: the tangential part (normal B g, Eq. 35)
            g0, g1, g2, tangent = surface.tangential(i, B, dim, g0, g1, g2, g0, g1, g2)
            if not tangent:
                continue
        x[i, 0] += scale * g0
        x[i, 1] += scale * g1
        if dim == 3:
            x[i, 2] += scale * g2


class LimitedTransportVelocity(Stabiliser):
    """Applies ``limited_shift`` (001_ Eq. 16) once per advection step."""

    name = "tvf_limited"

    def apply(self, ctx):
        pa = ctx.particles
        limited_shift(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.x, pa.mass, pa.rho, pa.kind, ctx.kernel.params)


class TransportVelocity(Stabiliser):
    """000_ Eq. 30 on inner particles only."""

    name = "tvf"
    needs_surface = True
    unified = False

    def apply(self, ctx):
        pa = ctx.particles
        n = pa.n_owned
        B = ctx.correction_matrices() if self.unified else np.empty((0, size(pa.dim)))  # not read
        consistency_shift(n, ctx.start, ctx.nbr, ctx.xc, pa.x, pa.mass, pa.rho, pa.kind, pa.surface, pa.div_r,
                          B, self.unified, ctx.kernel.params)


class UnifiedTransportVelocity(TransportVelocity):
    """000_ Eqs. 30-37 on inner and free-surface particles."""

    name = "utvf"
    unified = True
