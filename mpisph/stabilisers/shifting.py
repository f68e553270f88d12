"""Particle shifting: the regularisation 000_ compares UTVF against (its Figs. 6 and 9).

Once per configuration, every moving particle is moved by Xu, Stansby & Laurence's
shift (JCP 228, 2009, Eq. 35):

    dr_i = C alpha rbar_i^2 sum_j r_ij / |r_ij|^3,   alpha = |v|max dt,

with r_ij = x_i - x_j over the neighbours within the kernel support (walls
included: they stand for filled space), rbar_i the mean of those |r_ij|, C =
0.04 (Xu et al. give 0.01-0.1) and dt the advection step the configuration is
kept for (``StepContext.advection_step``; C is the case parameter
``shifting_coefficient``): the shift per unit of time is then
C |v|max rbar^2 sum r/|r|^3 however often it is applied, as Xu et al.'s per-step
shift is. The free-surface treatment is Khayyer, Gotoh & Shimizu's (JCP 332,
2017, optimised particle shifting): outermost and near-surface particles are
moved only along the surface (the normal as UTVF's, surface.tangential) and
splashed particles not at all.

A shifted particle stands for the material at its new place, so the fields it
carries (the scheme's ``carried_fields``: velocity and density, and stress for
solids) are corrected to it by a first-order Taylor expansion, as Xu et al. do:
f_i += dr_i . grad f_i with grad f_i = B_i sum_j V_j (f_j - f_i) grad_i W_ij over
the material neighbours (a wall particle's velocity and density are boundary
values of the pair terms, not samples of the material's fields). B of 000_
Eq. 24 makes the gradient of a linear field exact where the support holds
material only, the free surface included; next to a wall the sum lacks the
wall's part of the support and comes out smaller. That
correction is not antisymmetric in i and j: unlike the transport-velocity
shifts, shifting does not conserve linear momentum, which is the drift 000_
Fig. 6 shows.
"""

from numba import njit

from .. import surface
from ..integrators.updates import max_speed
from ..kernels import pair_dw
from ..neighbours import pair_offset
from ..particles import CORE_FIELDS, MOVING, is_wall
from ..schemes import SCHEMES
from ..tensors import times_vector
from .base import Stabiliser
from .transport_velocity import kernel_gradient_sum

COEFFICIENT = 0.04  # C of Xu et al. (2009), Eq. 35
CORE_NAMES = {f.name for f in CORE_FIELDS}  # sent with the halo, refreshed by whatever changes them


@njit(cache=True)
def shifts(n, start, nbr, xc, mass, rho, kind, cls, B, scale, k, out):
    """out_i = dr_i of the module docstring for the moving particles in [0, n), ``scale`` = C alpha;
    0 for the others and the splashed."""
    dim = xc.shape[1]
    for i in range(n):
        out[i, :] = 0.0
        if kind[i] != MOVING or cls[i] == surface.SPLASHED or start[i + 1] == start[i]:
            continue
        s0 = s1 = s2 = 0.0
        mean = 0.0
        for s in range(start[i], start[i + 1]):
            d0, d1, d2, r = pair_offset(xc, i, nbr[s])
            mean += r
            f = 1.0 / (r * r * r)
            s0 += f * d0
            s1 += f * d1
            s2 += f * d2
        mean /= start[i + 1] - start[i]
        c = scale * mean * mean
        s0, s1, s2 = c * s0, c * s1, c * s2
        if cls[i] != surface.INNER:
            g0, g1, g2 = kernel_gradient_sum(i, start, nbr, xc, mass, rho, k)
            s0, s1, s2, tangent = surface.tangential(i, B, dim, g0, g1, g2, s0, s1, s2)
            if not tangent:
                continue
        out[i, 0] = s0
        out[i, 1] = s1
        if dim == 3:
            out[i, 2] = s2


@njit(cache=True)
def taylor_corrections(n, start, nbr, xc, mass, rho, kind, B, k, dr, f, out):
    """out_i = dr_i . grad f_i (module docstring) for each column of ``f`` (rows: owned then ghosts)."""
    dim = xc.shape[1]
    for i in range(n):
        out[i, :] = 0.0
        if kind[i] != MOVING:
            continue
        e0, e1, e2 = times_vector(B, i, dim, dr[i, 0], dr[i, 1], dr[i, 2] if dim == 3 else 0.0)  # dr.B = B dr
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            if is_wall(kind[j]):
                continue
            d0, d1, d2, r = pair_offset(xc, i, j)
            along = (e0 * d0 + e1 * d1 + e2 * d2) * mass[j] / rho[j] * pair_dw(k, r, i, j) / r
            for c in range(f.shape[1]):
                out[i, c] += (f[j, c] - f[i, c]) * along


class ParticleShifting(Stabiliser):
    """Xu et al.'s shift with Khayyer et al.'s free-surface treatment, and the Taylor correction of
    the carried fields (module docstring)."""

    name = "shifting"
    needs_surface = True
    shifts_positions = True

    def __init__(self, case, params):
        self.coefficient = params.get("shifting_coefficient", COEFFICIENT)
        self.carried = SCHEMES[case.scheme].carried_fields

    def apply(self, ctx):
        pa = ctx.particles
        n = pa.n_owned
        scale = self.coefficient * ctx.max_over_ranks(max_speed(n, pa.kind, pa.v)) * ctx.advection_step
        dr = ctx.workspace.get("shift", n, (pa.dim,))
        B = ctx.correction_matrices()
        shifts(n, ctx.start, ctx.nbr, ctx.xc, pa.mass, pa.rho, pa.kind, pa.surface, B, scale, ctx.kernel.params, dr)
        ctx.refresh([name for name in self.carried if name not in CORE_NAMES])  # v, rho: current since the halo
        columns = [pa.arrays[name].reshape(pa.n, -1) for name in self.carried]
        corrections = [ctx.workspace.get("shift_" + name, n, (f.shape[1],)) for name, f in zip(self.carried, columns)]
        for f, correction in zip(columns, corrections):  # all from the fields before any is corrected
            taylor_corrections(n, ctx.start, ctx.nbr, ctx.xc, pa.mass, pa.rho, pa.kind, B, ctx.kernel.params, dr, f,
                               correction)
        for f, correction in zip(columns, corrections):
            f[:n] += correction
        ctx.refresh(self.carried)  # the first step's pair sums read them from ghosts
        pa.x[:n] += dr
