"""Transport-velocity corrections: position shifts towards zero-order consistency.

Three stabilisers, selectable per case (``--set stabiliser=...``), applied
once per advection step, i.e. after the Verlet update of the previous one
(000_ Eq. 42):

- ``tvf_limited``: 001_ Eqs. 14-16 on inner particles only;
- ``tvf``: 000_ Eq. 30 on inner particles only;
- ``utvf``: 000_ Eqs. 30-37 on inner and free-surface particles alike.

With g_i = sum_j V_j grad_i W_ij, the shift of 000_ Eq. 30 is
dr_i = -2 alpha h^2 g_i, alpha = 0.2. 000_ prints the sum with a plus, and with its
own grad_i W_ij = W' e_ij, e_ij from j to i (its Sec. 3.1.1; kernels.py) g points
towards the denser side, where the printed sign would move the particle. The
minus is what 000_'s text describes (Sec. 3.3: shifted by Eq. 30, a surface
particle "will move in a direction away from other particles") and what
regularises (tests/test_transport_velocity.py: a displaced particle goes back). UTVF projects the
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

With the case parameter ``utvf_near_surface_normal = "outermost"``, a
near-surface particle i is projected in Eq. 36 not on its own normal B_i g_i
(Eq. 35) but on n = sum_j V_j W_ij n_j, the kernel-weighted mean of the Eq. 35
normals n_j = B_j g_j / |B_j g_j| of the outermost particles j within h (the
particles that make i near-surface, 000_ Sec. 3.3). The default, ``"own"``, is
Eq. 35 as printed. Why: Eq. 36 should remove the part of the shift across the
free surface, so it needs the surface's normal. The support of an outermost
particle is cut by the surface, so its g is large and points across it: h |g|
= 0.60 under the top face of a 12^3 lattice block. A near-surface particle's
support is only cut at its rim, and there h |g| = 0.035. Jittered by 0.1 dp,
the near-surface particles reach h |g| = 0.085, most of it from the disorder,
and B g is on average 52 degrees (up to 90) from the face's normal. The mean
of the outermost neighbours' normals is 2.2 degrees from it. So Eq. 36 with
the own normal removes part of the shift along the surface and keeps part of
the shift across it. On a perfect lattice both normals are the face's, so the
lattice stays in place with either. From the 12^3 block jittered by 0.3 dp, 200
shifts with utvf_edge_neighbours=kept leave 1.74 % of the particles nearer than
dp/2 to another with the own normal and 0.81 % with the outermost one
(tests/test_transport_velocity.py; with two other jitter seeds, through the
same test harness but not asserted: 1.33 / 0.46 % and 0.46 / 0.12 %).
Splashed and outermost particles keep Eq. 35. The outermost normals are a field
(``surface_normal``) so that ghosts carry them; a restart recomputes them.

With the case parameter ``utvf_splashed = "shifted"``, UTVF also shifts the
splashed particles (outermost, with no near-surface particle within h) with
div r >= 0.6 d, along their surface (Eq. 36 with their own normal, Eq. 35), as
the other outermost particles. The default, ``"kept"``, follows 000_ Sec. 3.3's
text: "when particles are splashed, transport-velocity correction is not
required". The authors' code does not exclude them: SPHinXsys's UTVF (the class
TransportVelocityCorrection of tests/2d_examples/test_2d_cohesive_soil_failure/
cohesive_soil_failure.h, the case of 000_ Sec. 5.2) projects the shift of every
particle its free-surface indicator marks, splashed ones among them, and zeroes
it only where div r < 0.6 d. A body thin enough to have no near-surface layer
(a sheet two particles thick, the tongue of a thin flow) is all splashed, so
as printed nothing regularises it (tests/test_transport_velocity.py).

The limited variant, once per advection step (001_ Eqs. 14-16):

    g_i  = 2 sum_j V_j grad_i W_ij
    beta = min(C h^2 |g_i|^2, 1)  if h^2 |g_i|^2 > 5e-4, else 0    (C = 1000)
    dr_i = -0.2 beta h^2 g_i

g_i carries the factor 2 of the transport acceleration -2 sum_j m_j p0/(rho_i rho_j)
grad W_ij (001_ Eq. 12) from which Eq. 14 is derived: with p0 = 7 rho0 |v|_ad^2 and
dt_ad = 0.25 h/|v|_ad, 1/2 a dt_ad^2 = -0.44 h^2 sum_j V_j grad W_ij, i.e. 0.2 times this
g_i (SPHinXsys applies 0.2 h^2 to the same doubled residue, in the limiter as well).

(g points towards the denser side, so the shift is against it.) It is one form
with 000_'s: 0.2 h^2 times the doubled residue is 000_ Eq. 30's 2 alpha h^2 g_i
(alpha = 0.2), so with beta = 1 the limited shift is the TVF shift, and the
limiter alone tells them apart. 001_ shifts every particle of a flow without a
free surface (Taylor-Green, the cavity), where every particle is inner. A
free-surface particle's support is cut, so its g_i is the truncation's and
large (h |g| = 0.6 at a flat face) and the shift would pull it into the body;
the limited shift therefore takes the inner particles only, as TVF does, on
fluids and solids alike (``tvf_limited`` on a solid is TVF with 001_'s limiter).
"""

import numpy as np
from numba import njit

from .. import surface
from ..kernels import pair_dw, pair_w
from ..neighbours import pair_distance, pair_offset
from ..particles import MOVING, Field, is_wall
from ..tensors import size, times_vector
from .base import Stabiliser

LIMITER_C = 1000.0
LIMITER_THRESHOLD = 5e-4
COEFFICIENT = 0.2
ALPHA = 0.2  # 000_ Eq. 30
NO_SHIFT_DIVERGENCE = 0.6  # times the dimension (000_ Sec. 3.3)
EDGE_NEIGHBOURS = ("shifted", "kept")  # the choices of utvf_edge_neighbours, the default first
SPLASHED = ("kept", "shifted")  # the choices of utvf_splashed, the default first
NEAR_SURFACE_NORMALS = ("own", "outermost")  # the choices of utvf_near_surface_normal, the default first


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
def limited_shift(n, start, nbr, xc, x, mass, rho, kind, cls, k):
    """Add the limited transport-velocity shift of 001_ Eq. 16 to the positions ``x`` of the inner
    particles (free-surface classes ``cls``)."""
    dim = xc.shape[1]
    h2 = k.h * k.h
    for i in range(n):
        if kind[i] != MOVING or cls[i] != surface.INNER:
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
def outermost_normals(n, start, nbr, xc, mass, rho, kind, div_r, B, k, out):
    """out_i = B_i g_i / |B_i g_i| (000_ Eq. 35) for the outermost particles in [0, n) (div r < 0.75 d,
    splashed ones included), 0 for the others."""
    dim = xc.shape[1]
    for i in range(n):
        out[i] = 0.0
        if is_wall(kind[i]) or div_r[i] >= surface.SURFACE_THRESHOLD * dim:
            continue
        g0, g1, g2 = kernel_gradient_sum(i, start, nbr, xc, mass, rho, k)
        m0, m1, m2 = times_vector(B, i, dim, g0, g1, g2)
        norm = np.sqrt(m0 * m0 + m1 * m1 + m2 * m2)
        if norm > 0.0:
            out[i, 0] = m0 / norm
            out[i, 1] = m1 / norm
            if dim == 3:
                out[i, 2] = m2 / norm


@njit(cache=True)
def outermost_mean_normal(i, start, nbr, xc, mass, rho, kind, div_r, normals, k):
    """sum_j V_j W_ij n_j over the outermost material neighbours j within h of i, n_j from
    ``outermost_normals`` (the normal of a near-surface particle, module docstring)."""
    threshold = surface.SURFACE_THRESHOLD * xc.shape[1]
    n0 = n1 = n2 = 0.0
    for s in range(start[i], start[i + 1]):
        j = nbr[s]
        if is_wall(kind[j]) or div_r[j] >= threshold:
            continue
        r = pair_distance(xc, i, j)
        if r < k.h:
            w = mass[j] / rho[j] * pair_w(k, r, i, j)
            n0 += w * normals[j, 0]
            n1 += w * normals[j, 1]
            if xc.shape[1] == 3:
                n2 += w * normals[j, 2]
    return n0, n1, n2


@njit(cache=True)
def consistency_shift(n, start, nbr, xc, x, mass, rho, kind, cls, div_r, B, unified, keep_edge_neighbours, k,
                      normals, shift_splashed=False):
    """Add dr of 000_ Eq. 30 (``unified`` false: inner particles only) or Eq. 37 to ``x``; with
    ``keep_edge_neighbours``, not to 3D free-surface particles beside an edge; with ``normals`` of the
    outermost particles (empty: Eq. 35 for every one), a near-surface particle's normal from
    theirs; with ``shift_splashed``, splashed particles as the other outermost ones (module
    docstring)."""
    dim = xc.shape[1]
    scale = -2.0 * ALPHA * k.h * k.h
    for i in range(n):
        if kind[i] != MOVING:
            continue
        if cls[i] != surface.INNER and (not unified or (cls[i] == surface.SPLASHED and not shift_splashed)
                                        or div_r[i] < NO_SHIFT_DIVERGENCE * dim):
            continue
        if (cls[i] != surface.INNER and keep_edge_neighbours and dim == 3
                and beside_an_edge(i, start, nbr, xc, kind, div_r, k.h)):
            continue
        g0, g1, g2 = kernel_gradient_sum(i, start, nbr, xc, mass, rho, k)
        if cls[i] != surface.INNER:  # Eq. 36: the tangential part
            if cls[i] == surface.NEAR_SURFACE and normals.shape[0] > 0:
                n0, n1, n2 = outermost_mean_normal(i, start, nbr, xc, mass, rho, kind, div_r, normals, k)
            else:
                n0, n1, n2 = times_vector(B, i, dim, g0, g1, g2)  # B g, Eq. 35
            g0, g1, g2, tangent = surface.without_normal_part(n0, n1, n2, g0, g1, g2)
            if not tangent:
                continue
        x[i, 0] += scale * g0
        x[i, 1] += scale * g1
        if dim == 3:
            x[i, 2] += scale * g2


class LimitedTransportVelocity(Stabiliser):
    """Applies ``limited_shift`` (001_ Eq. 16) to the inner particles once per advection step."""

    name = "tvf_limited"
    needs_surface = True
    shifts_positions = True

    def apply(self, ctx):
        pa = ctx.particles
        limited_shift(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.x, pa.mass, pa.rho, pa.kind, pa.surface,
                      ctx.kernel.params)


class TransportVelocity(Stabiliser):
    """000_ Eq. 30 on inner particles only."""

    name = "tvf"
    needs_surface = True
    shifts_positions = True
    unified = False
    keep_edge_neighbours = False
    outermost_normal = False
    shift_splashed = False

    def apply(self, ctx):
        pa = ctx.particles
        n = pa.n_owned
        B = ctx.correction_matrices() if self.unified else np.empty((0, size(pa.dim)))  # not read
        normals = np.empty((0, pa.dim))  # Eq. 35 for every free-surface particle
        if self.outermost_normal:
            normals = pa.surface_normal
            outermost_normals(n, ctx.start, ctx.nbr, ctx.xc, pa.mass, pa.rho, pa.kind, pa.div_r, B,
                              ctx.kernel.params, normals)
            ctx.refresh(["surface_normal"])
        consistency_shift(n, ctx.start, ctx.nbr, ctx.xc, pa.x, pa.mass, pa.rho, pa.kind, pa.surface, pa.div_r,
                          B, self.unified, self.keep_edge_neighbours, ctx.kernel.params, normals, self.shift_splashed)


class UnifiedTransportVelocity(TransportVelocity):
    """000_ Eqs. 30-37 on inner and free-surface particles; with the case's ``utvf_edge_neighbours``
    "kept", not on the 3D free-surface particles beside an edge; with ``utvf_near_surface_normal``
    "outermost", near-surface particles projected on the outermost particles' normals (module
    docstring)."""

    name = "utvf"
    unified = True

    def __init__(self, case, params):
        super().__init__(case, params)
        self.keep_edge_neighbours = params.get("utvf_edge_neighbours", EDGE_NEIGHBOURS[0]) == "kept"
        self.outermost_normal = params.get("utvf_near_surface_normal", NEAR_SURFACE_NORMALS[0]) == "outermost"
        self.shift_splashed = params.get("utvf_splashed", SPLASHED[0]) == "shifted"
        if self.outermost_normal:
            self.fields = (Field("surface_normal", ("dim",), np.float64,
                                 "unit normal B g / |B g| of an outermost free-surface particle, 0 for the others "
                                 "(000_ Eq. 35; utvf_near_surface_normal=outermost) [-]"),)
