"""Transport-velocity correction scaled by the smoothing length, with limiter.

Once per advection step every moving particle is shifted towards a state of
zero-order consistency (001_ Eqs. 14-16):

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

from numba import njit

from ..kernels import dw
from ..particles import MOVING

LIMITER_C = 1000.0
LIMITER_THRESHOLD = 5e-4
COEFFICIENT = 0.2


@njit(cache=True)
def limited_shift(n, start, nbr, xc, x, mass, rho, kind, h, sigma, kernel):
    """Add the limited transport-velocity shift of 001_ Eq. 16 to the positions ``x``."""
    dim = xc.shape[1]
    h2 = h * h
    for i in range(n):
        if kind[i] != MOVING:
            continue
        g0 = 0.0
        g1 = 0.0
        g2 = 0.0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            d0 = xc[i, 0] - xc[j, 0]
            d1 = xc[i, 1] - xc[j, 1]
            d2 = xc[i, 2] - xc[j, 2] if dim == 3 else 0.0
            r = (d0 * d0 + d1 * d1 + d2 * d2) ** 0.5
            f = 2.0 * mass[j] / rho[j] * dw(r, h, sigma, kernel) / r
            g0 += f * d0
            g1 += f * d1
            g2 += f * d2
        norm2 = h2 * (g0 * g0 + g1 * g1 + g2 * g2)
        if norm2 <= LIMITER_THRESHOLD:
            continue
        c = -COEFFICIENT * min(LIMITER_C * norm2, 1.0) * h2
        x[i, 0] += c * g0
        x[i, 1] += c * g1
        if dim == 3:
            x[i, 2] += c * g2


class LimitedTransportVelocity:
    """Stabiliser object: applies ``limited_shift`` once per advection step."""

    name = "tvf_limited"

    def apply(self, s):
        pa = s.particles
        limited_shift(pa.n_owned, s.start, s.nbr, s.xc, pa.x, pa.mass, pa.rho, pa.kind, *s.kernel_args)


class NoStabiliser:
    name = "none"

    def apply(self, s):
        pass


STABILISERS = {"none": NoStabiliser, "tvf_limited": LimitedTransportVelocity}
