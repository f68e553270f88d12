"""Free-surface detection from the divergence of the position (000_ Sec. 3.3).

div r_i = -sum_j V_j r_ij . grad_i W_ij (walls included) is close to the dimension d
inside a body and drops where the kernel support is truncated. 000_ prints Eq. 31
without the minus; with its own grad_i W_ij = W' e_ij, W' <= 0 (Sec. 3.1.1; kernels.py)
that sum is near -d, where its thresholds (0.75 d, 0.6 d) need +d. Each material particle gets
a class:

- SURFACE (outermost): div r < 0.75 d;
- NEAR_SURFACE: not outermost, but an outermost particle lies within h;
- SPLASHED: outermost with no near-surface particle within h (a particle
  that left the body: no material particle within h that is not itself
  outermost);
- INNER: the rest.

``classify(ctx)`` fills the fields ``div_r`` and ``surface`` of the owned
particles of a StepContext; the divergence of ghosts is refreshed in between.
"""

import numpy as np
from numba import njit

from .kernels import pair_dw
from .neighbours import pair_distance
from .particles import Field, is_wall
from .tensors import times_vector

SURFACE_THRESHOLD = 0.75  # times the dimension
INNER, NEAR_SURFACE, SURFACE, SPLASHED = 0, 1, 2, 3

FIELDS = (
    Field("div_r", (), np.float64, "position divergence (000_ Eq. 31) [-]"),
    Field("surface", (), np.int8, "0 inner, 1 near-surface, 2 outermost surface, 3 splashed"),
)


@njit(cache=True)
def position_divergence(n, start, nbr, x, mass, rho, kind, k, out):
    """out_i = -sum_j V_j r_ij . grad_i W_ij for the material particles in [0, n)."""
    for i in range(n):
        if is_wall(kind[i]):
            continue
        acc = 0.0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            r = pair_distance(x, i, j)
            acc -= mass[j] / rho[j] * r * pair_dw(k, r, i, j)
        out[i] = acc


@njit(cache=True)
def surface_classes(n, start, nbr, x, kind, div_r, threshold, h, out):
    """The class of each material particle in [0, n) (module docstring)."""
    for i in range(n):
        if is_wall(kind[i]):
            continue
        outermost = div_r[i] < threshold
        near_outer = False
        near_inner = False
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            if is_wall(kind[j]) or pair_distance(x, i, j) >= h:
                continue
            if div_r[j] < threshold:
                near_outer = True
            else:
                near_inner = True
        if outermost:
            out[i] = SURFACE if near_inner else SPLASHED
        else:
            out[i] = NEAR_SURFACE if near_outer else INNER


@njit(cache=True)
def tangential(i, B, dim, g0, g1, g2, v0, v1, v2):
    """(v0, v1, v2) less its part along the free-surface normal of particle i, and whether that
    normal exists. The normal is B_i g (000_ Eqs. 32-35; B packed as tensors.py): g = sum_j V_j
    grad W_ij is the colour gradient of one material, walls counting as filled space."""
    n0, n1, n2 = times_vector(B, i, dim, g0, g1, g2)
    return without_normal_part(n0, n1, n2, v0, v1, v2)


@njit(cache=True)
def without_normal_part(n0, n1, n2, v0, v1, v2):
    """(v0, v1, v2) - ((v.n) / |n|^2) n (000_ Eq. 36 for a normal n of any length), and whether n is
    not zero (if it is, v is returned as it is)."""
    norm2 = n0 * n0 + n1 * n1 + n2 * n2
    if norm2 == 0.0:
        return v0, v1, v2, False
    vn = (v0 * n0 + v1 * n1 + v2 * n2) / norm2
    return v0 - vn * n0, v1 - vn * n1, v2 - vn * n2, True


def classify(ctx):
    """Fill ``div_r`` and ``surface`` of the owned particles of the StepContext ``ctx``."""
    pa = ctx.particles
    n = pa.n_owned
    position_divergence(n, ctx.start, ctx.nbr, ctx.xc, pa.mass, pa.rho, pa.kind, ctx.kernel.params, pa.div_r)
    ctx.refresh(["div_r"])
    surface_classes(n, ctx.start, ctx.nbr, ctx.xc, pa.kind, pa.div_r, SURFACE_THRESHOLD * pa.dim, ctx.kernel.h,
                    pa.surface)
