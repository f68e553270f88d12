"""The adaptive B-spline kernel with pressure zones (002_ Sec. 4).

Each particle's kernel is the cubic B-spline of kernels.py with its own knot
a (002_ Eq. 31, b = 2): the peak of |W'| sits at r = a b h / (a + b). Beyond
it W'' > 0, inside it W'' < 0, and Swegle's criterion (unstable where
sigma W'' > 0, tension positive) makes an interaction stable in compression
beyond that peak (002_'s zone II) and stable in tension inside it (zone I).
Once per configuration, before any pair sum
(``prepare``), the knot of each moving particle i follows from the pressures of
its immediate neighbours (Sec. 4.3), the material particles within r_i, the
estimated distance of the farthest immediate neighbour:

- all of them in compression (p_j > 0): a = 0.2, so that the immediate
  neighbours lie beyond the peak (at 0.18 h);
- otherwise (one of them in tension): a = b r_i / (b h - r_i), which puts the
  peak at r_i, so that they all lie inside it; at most b (r_i >= b h / 2).

Wall (and clamped) particles keep a = 1 (the cubic spline): a wall's pressure
is a boundary value, not a state of the material. r_i comes from the deformation of the
particle's initial lattice cell (Sec. 4.4): Eqs. 32-33 follow the two sides of
a square cell of side dp under the strain rate and take the longer diagonal
of the deformed cell. Here the cell deforms with the displacement gradient H
(the field ``displacement_gradient``, F = I + H), integrated once per
configuration over the advection step (``apply``):

    H <- H + L (I + H) dt,   L_i = sum_j V_j (v_j - v_i) (x) grad_i W_ij   (Eq. 32),

and r_i = dp max |F d| over the cell's diagonals d: (1, +-1) in 2D, which are
Eq. 33's S_1 and S_2, and (1, +-1, +-1) in 3D, the extension to three
dimensions. Eqs. 32-33 build F from the strain rate, the symmetric part of L;
a material line element dx = F dX changes as d(dx)/dt = L dx, and the spin
part of L, which changes no length at once, turns the cell so that later
stretching acts along other sides of it: L is the exact rate, and for a
deformation without rotation both agree.

The density is the continuity equation's: a case with ``density_reinit`` other than none is
refused, since density summation divides by the fixed spline's lattice sum, which the knots change
(tests/test_adaptive_kernel.py).
"""

import math

import numpy as np
from numba import njit

from ..errors import InputError
from ..kernels import KNOT_SUPPORT, knot_coefficients, pair_dw
from ..neighbours import pair_offset
from ..particles import MOVING, Field, is_wall
from .base import Stabiliser

COMPRESSION_KNOT = 0.2  # 002_ Sec. 4.3
WALL_KNOT = 1.0  # the cubic spline
IMMEDIATE_TOLERANCE = 1.01  # a neighbour at the estimated distance, up to round-off, is immediate


@njit(cache=True)
def farthest_immediate(i, H, dp):
    """r_i: dp times the longest diagonal of the deformed unit cell, F = I + H (module docstring)."""
    dim = H.shape[1]
    longest = 0.0
    for s1 in (1.0, -1.0):
        for s2 in (1.0, -1.0):
            if dim == 2 and s2 < 0.0:
                break
            d = (1.0, s1, s2)  # its third component unread in 2D
            length2 = 0.0
            for a in range(dim):
                component = d[a]
                for c in range(dim):
                    component += H[i, a, c] * d[c]
                length2 += component * component
            longest = max(longest, length2)
    return dp * math.sqrt(longest)


@njit(cache=True)
def pressure_zone_knots(n, start, nbr, xc, kind, p, H, dp, h, out):
    """The knot a of each particle in [0, n) by the pressure-zone rule of the module docstring."""
    b = KNOT_SUPPORT
    for i in range(n):
        if kind[i] != MOVING:
            out[i] = WALL_KNOT
            continue
        r_far = farthest_immediate(i, H, dp)
        compression = True
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            if is_wall(kind[j]):
                continue
            if pair_offset(xc, i, j)[3] <= IMMEDIATE_TOLERANCE * r_far and not p[j] > 0.0:
                compression = False
                break
        if compression:
            out[i] = COMPRESSION_KNOT
        elif r_far >= 0.5 * b * h:
            out[i] = b
        else:
            out[i] = b * r_far / (b * h - r_far)


@njit(cache=True)
def fill_coefficients(n, knot, h, dim, out):
    """The factors of each particle's kernel (kernels.knot_coefficients) for the particles in [0, n)."""
    for i in range(n):
        out[i, 0], out[i, 1] = knot_coefficients(knot[i], h, dim)


@njit(cache=True)
def deform_cells(n, start, nbr, xc, v, mass, rho, kind, k, dt, H):
    """H <- H + L (I + H) dt with L of Eq. 32, for the moving particles in [0, n). A wall partner
    enters with its own velocity, as a particle at rest would, not mirrored as in the schemes'
    velocity gradients (physics/velocity_gradient.py): L here tracks the particles' lattice cell,
    not the continuum's strain rate at the wall."""
    dim = xc.shape[1]
    L = np.empty((dim, dim))
    for i in range(n):
        if kind[i] != MOVING:
            continue
        L[:, :] = 0.0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            d0, d1, d2, r = pair_offset(xc, i, j)
            f = mass[j] / rho[j] * pair_dw(k, r, i, j) / r
            g = (f * d0, f * d1, f * d2)
            for a in range(dim):
                for c in range(dim):
                    L[a, c] += (v[j, a] - v[i, a]) * g[c]
        F = H[i].copy()
        for a in range(dim):
            F[a, a] += 1.0
        for a in range(dim):
            for c in range(dim):
                rate = 0.0
                for m in range(dim):
                    rate += L[a, m] * F[m, c]
                H[i, a, c] += rate * dt


class AdaptiveKernel(Stabiliser):
    """``adaptive_kernel``: the knots of 002_'s B-spline from the pressure zones (module docstring)."""

    name = "adaptive_kernel"
    adapts_kernel = True
    fields = (Field("displacement_gradient", ("dim", "dim"), np.float64,
                    "H = F - I of the particle's initial lattice cell (002_ Sec. 4.4, adaptive_kernel) [-]"),)

    def __init__(self, case, params):
        if case.density_reinit != "none":
            raise InputError(f"adaptive_kernel needs density_reinit=none, not {case.density_reinit!r}: the summed "
                             "density divides by the lattice sum of the fixed spline, and the knots change it (a "
                             "lattice at rest with a = 0.2 would sum to 4.3 % above rho0 in 2D, 2.8 % in 3D)")
        self.dp = case.dp

    def prepare(self, ctx):
        pa = ctx.particles
        ctx.refresh(["p"])
        pressure_zone_knots(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.kind, pa.p, pa.displacement_gradient,
                            self.dp, ctx.kernel.h, pa.knot)
        fill_coefficients(pa.n_owned, pa.knot, ctx.kernel.h, pa.dim, pa.knot_coefficients)
        ctx.refresh(["knot", "knot_coefficients"])

    def apply(self, ctx):
        pa = ctx.particles
        deform_cells(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.v, pa.mass, pa.rho, pa.kind, ctx.kernel.params,
                     ctx.advection_step, pa.displacement_gradient)
