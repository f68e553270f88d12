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

With the case parameter ``utvf_edge_neighbours = "kept"``, UTVF in 3D also
leaves unshifted the free-surface particles that have a material neighbour
with div r < 0.6 d within h. The default, ``"shifted"``, is Eq. 37 as
printed. Why the option: a perfect lattice is regular, so a regularising
shift should leave it in place. In 2D, Eq. 37 does. A flat face's particles have g along
n, and the face particle beside a corner has div r = 1.19 < 0.6 d = 1.2
(Wendland C2, h = 1.3 dp). In 3D it does not. The face particle beside an edge has
div r = 1.93-1.98 > 1.8, and its support is cut off along the edge's other
face as well, so its tangent plane holds a truncation gradient. With
B_i^-1 = -sum_j V_j r_ij (x) grad W anisotropic within that plane (eigenvalues 0.72 and 0.77), B g is not
parallel to g. The projection of Eq. 36 then leaves 0.0067 dp per shift,
pointing off the face towards the edge. The edge particles themselves
(div r = 1.33-1.38) are not shifted. Nothing restores the face particles,
since the stress does not see a shift. Repeated alone 200 times on a 10^3
block, the shift moves particles by up to 0.11 dp and brings pairs to
0.89 dp. The particles within h of an edge are exactly those cut off along
a second direction, so excluding them leaves the block in place. From the
block jittered by 0.3 dp, 1.8 % of its particles nearer than dp/2 to
another, the same 200 shifts leave 1.6 % with the rule and 2.0 % without
it (tests/test_transport_velocity.py).
The rule is not applied in 2D, where Eq. 37 already leaves the lattice in
place. There it would also stop the shift beside thin jets: on the rotating
patch at L/100 it raises the clustering at t = 1.9 s from 1.72 % to 4.52 %.
It is not the default because it does not help every flow. On the cube of
000_ Sec. 5.3 it removes the crowding at the edges, but on the flume it
leaves the rough free surface of the thin flow unregularised, and more
particles cluster there. docs/PRODUCTION_3D.md has both runs of both cases.

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
from ..neighbours import pair_distance, pair_offset
from ..particles import MOVING, is_wall
from ..tensors import size
from .base import Stabiliser

LIMITER_C = 1000.0
LIMITER_THRESHOLD = 5e-4
COEFFICIENT = 0.2
ALPHA = 0.2  # 000_ Eq. 30
NO_SHIFT_DIVERGENCE = 0.6  # times the dimension (000_ Sec. 3.3)
EDGE_NEIGHBOURS = ("shifted", "kept")  # the choices of utvf_edge_neighbours, the default first


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
def beside_an_edge(i, start, nbr, xc, kind, div_r, h):
    """Whether a material neighbour of i within h has div r < 0.6 d: a free-surface edge or corner,
    where 000_ Sec. 3.3 finds the normal inaccurate (module docstring)."""
    threshold = NO_SHIFT_DIVERGENCE * xc.shape[1]
    for s in range(start[i], start[i + 1]):
        j = nbr[s]
        if not is_wall(kind[j]) and div_r[j] < threshold and pair_distance(xc, i, j) < h:
            return True
    return False


@njit(cache=True)
def consistency_shift(n, start, nbr, xc, x, mass, rho, kind, cls, div_r, B, unified, keep_edge_neighbours, k):
    """Add dr of 000_ Eq. 30 (``unified`` false: inner particles only) or Eq. 37 to ``x``; with
    ``keep_edge_neighbours``, not to 3D free-surface particles beside an edge (module docstring)."""
    dim = xc.shape[1]
    scale = -2.0 * ALPHA * k.h * k.h
    for i in range(n):
        if kind[i] != MOVING:
            continue
        if cls[i] != surface.INNER and (not unified or cls[i] == surface.SPLASHED
                                        or div_r[i] < NO_SHIFT_DIVERGENCE * dim):
            continue
        if (cls[i] != surface.INNER and keep_edge_neighbours and dim == 3
                and beside_an_edge(i, start, nbr, xc, kind, div_r, k.h)):
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
    keep_edge_neighbours = False

    def apply(self, ctx):
        pa = ctx.particles
        n = pa.n_owned
        B = ctx.correction_matrices() if self.unified else np.empty((0, size(pa.dim)))  # not read
        consistency_shift(n, ctx.start, ctx.nbr, ctx.xc, pa.x, pa.mass, pa.rho, pa.kind, pa.surface, pa.div_r,
                          B, self.unified, self.keep_edge_neighbours, ctx.kernel.params)


class UnifiedTransportVelocity(TransportVelocity):
    """000_ Eqs. 30-37 on inner and free-surface particles; with the case's ``utvf_edge_neighbours``
    "kept", not on the 3D free-surface particles beside an edge (module docstring)."""

    name = "utvf"
    unified = True

    def __init__(self, case, params):
        super().__init__(case, params)
        self.keep_edge_neighbours = params.get("utvf_edge_neighbours", EDGE_NEIGHBOURS[0]) == "kept"
