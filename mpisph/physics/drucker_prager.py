"""Drucker-Prager granular material (000_ Secs. 2.3 and 3.1.3).

The total stress is integrated with the Jaumann rate and the non-associated
flow rule (Eq. 10), the plastic multiplier rate of Eq. 13 and the constants
of Eq. 14, then returned to the yield surface f = alpha_phi I1 + sqrt(J2) - k_c
(Eq. 11) in two steps (Eq. 15 and the return mapping after Bui et al. 2008):

1. tension cut-off: if alpha_phi I1 > k_c the hydrostatic part is moved to
   the apex, I1 = k_c / alpha_phi (skipped for phi = 0, which has no apex);
2. radial scaling: if sqrt(J2) > k_c - alpha_phi I1 the deviator is scaled
   by r = (k_c - alpha_phi I1) / sqrt(J2).

Eq. 10 prints the plastic term's volumetric part as 3 K alpha_phi I, the associated flow;
the rate here takes 3 K alpha_psi I, the flow rule g = alpha_psi I1 + sqrt(J2) that Eq. 13's
denominator 9 alpha_phi K alpha_psi + G follows from, and which 002_ Eq. 28 writes with
its alpha_varphi, the dilatancy angle's (002_ Eq. 14); with psi = phi the two agree.

Plastic flow in the rate (Eq. 10) is applied only while the multiplier rate
is positive (loading); on unloading from the yield surface the rate is
elastic. The accumulated deviatoric plastic strain adds dt gamma_dot / sqrt(3)
(the equivalent measure sqrt(2/3 e:e) of the deviatoric part of
gamma_dot dg/dsigma) and, for the return mapping, sqrt(2/3) |Delta s| / 2G
(``strain_of_multiplier``, ``strain_of_return``; the classic scheme adds the same).

Stress diffusion smooths the stress over material neighbours with zeta = 0.1.
The default (``stress_diffusion = "linear"``) diffuses each component less
its local linear part, as delta-SPH's density diffusion does (Antuono et al. 2010):

    dsigma_i/dt += 2 zeta h c0 sum_j V_j (sigma_ij - (G_i + G_j) . r_ij / 2) r_ij W'_ij / (r_ij^2 + 0.01 h^2),

G = grad sigma with the correction matrix over the material neighbours, so
that G is exact and the term zero on any linear stress field; the pair term
is antisymmetric, so sum_i V_i dsigma_i/dt = 0. ``stress_diffusion =
"geostatic"`` is the form 000_ uses (Feng et al. 2021): sigma less its
geostatic part sigma_v = -rho0 g (H - y), sigma_h = (1 - sin phi) sigma_v,

    dsigma_i/dt += 2 zeta h c0 sum_j V_j (sigma_ij - sigma^geo_ij) r_ij W'_ij / (r_ij^2 + 0.01 h^2),

which, within a kernel radius of a free surface or a wall, vanishes only on
that field of a level surface; ``"none"`` leaves the stress alone. Why the
default departs from 000_: a resting deposit keeps any velocity whose
elastic stress rate the diffusion cancels while the UTVF shift holds the
grains in place, and a deposit on a slope, against a barrier
or between walls is not geostatic. On a 10^3 block jittered by 0.2 dp with
horizontal gradients of 20 kPa/m in sigma_xx and 10 kPa/m in sigma_xy over
the geostatic field, Feng's term gives up to 1.5e5 Pa/s and the linear one
1.7e-9 Pa/s; a laterally confined layer at rest under the elastic lateral
stress nu / (1 - nu) sigma_v keeps it within 10 % with the linear form and
without diffusion, where Feng's drives it from 0.43 to 0.28 sigma_v in 1 s
(tests/test_stress_diffusion.py). docs/FLUME.md has the flume with both forms.

The deviators here are 3D (the stress tensor is 3 x 3 in 2D too, plane
strain); p = -tr(sigma)/3.
"""

import math

import numpy as np
from numba import njit

from ..correction import regularised_inverse
from ..kernels import pair_dw
from ..materials import DruckerPrager
from ..neighbours import pair_distance, pair_offset
from ..particles import Field, is_wall
from ..tensors import SYM3, unpack_row
from .fluid import limited_pairs_sign
from .solid import SolidScheme, jaumann_rate, material_pressure, velocity_gradient

DIFFUSION_ZETA = 0.1
PLASTIC_STRAIN = Field("plastic_strain", (), np.float64, "accumulated deviatoric plastic strain [-]")
STRESS_GRADIENT = Field("stress_gradient", (6, "dim"), np.float64,
                        "gradient of each packed stress component (stress_diffusion=linear) [Pa/m]")
STRESS_DIFFUSIONS = ("linear", "geostatic", "none")  # the choices of the option stress_diffusion, the default first
NO_DIFFUSION = np.zeros((0, 6))  # a diffusion without rows: plastic_stress_rate adds none


@njit(cache=True)
def stress_diffusion(n, start, nbr, xc, stress, mass, rho, kind, rho0, g, k0, c0, k, rate):
    """rate_i = the diffusion term of the module docstring (vertical axis = last axis), packed
    like the stress (tensors.py).

    With f_ij the pair weight, the sum is sigma_i sum f - sum f sigma_j - (sum f dsigma^geo_ij),
    the stresses being symmetric.
    """
    dim = xc.shape[1]
    vert = dim - 1
    h = k.h
    coef0 = 2.0 * DIFFUSION_ZETA * h * c0
    for i in range(n):
        if is_wall(kind[i]):
            continue
        f_sum = geo_sum = 0.0
        s0 = s1 = s2 = s3 = s4 = s5 = 0.0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            if is_wall(kind[j]):
                continue
            r = pair_distance(xc, i, j)
            f = coef0 * mass[j] / rho[j] * r * pair_dw(k, r, i, j) / (r * r + 0.01 * h * h)
            f_sum += f
            geo_sum += f * rho0 * g * (xc[i, vert] - xc[j, vert])
            s0 += f * stress[j, 0]
            s1 += f * stress[j, 1]
            s2 += f * stress[j, 2]
            s3 += f * stress[j, 3]
            s4 += f * stress[j, 4]
            s5 += f * stress[j, 5]
        sums = (s0, s1, s2, s3, s4, s5)
        for c in range(6):
            rate[i, c] = f_sum * stress[i, c] - sums[c]
        for a in range(3):
            rate[i, a] -= geo_sum if a == vert else k0 * geo_sum


@njit(cache=True)
def stress_gradient(n, start, nbr, xc, stress, mass, rho, kind, k, out):
    """out_i[c] = L_i sum_j V_j (sigma_j - sigma_i)[c] grad_i W_ij over the material neighbours, with
    L_i = (-sum_j V_j r_ij (x) grad_i W_ij)^-1 over the same (regularised as B): exact on a linear
    stress field; zero for walls. A first pass over i's neighbours sums the nine entries of A (each
    A[a, b] -= f d_a d_b, formed in that order, not symmetrised) and keeps each material neighbour's
    f and offset; then, with L_i from A, one pass per stress component sums its three entries of S
    into three scalars, which L_i maps to out_i[c]. Every sum takes its terms in neighbour order, as
    one pass for all would: the same bits, with three accumulators a pass instead of eighteen,
    which spill from the registers."""
    dim = xc.shape[1]
    A = np.empty((dim, dim))
    L = np.empty((dim, dim))
    most = 0
    for i in range(n):
        most = max(most, start[i + 1] - start[i])
    jj = np.empty(most, np.int64)
    ff = np.empty(most)
    dd = np.empty((most, 3))
    for i in range(n):
        out[i] = 0.0
        if is_wall(kind[i]):
            continue
        a00 = a01 = a02 = a10 = a11 = a12 = a20 = a21 = a22 = 0.0
        m = 0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            if is_wall(kind[j]):
                continue
            d0, d1, d2, r = pair_offset(xc, i, j)
            f = mass[j] / rho[j] * pair_dw(k, r, i, j) / r
            a00 -= f * d0 * d0
            a01 -= f * d0 * d1
            a02 -= f * d0 * d2
            a10 -= f * d1 * d0
            a11 -= f * d1 * d1
            a12 -= f * d1 * d2
            a20 -= f * d2 * d0
            a21 -= f * d2 * d1
            a22 -= f * d2 * d2
            jj[m], ff[m] = j, f
            dd[m, 0], dd[m, 1], dd[m, 2] = d0, d1, d2
            m += 1
        A[0, 0], A[0, 1], A[1, 0], A[1, 1] = a00, a01, a10, a11
        if dim == 3:
            A[0, 2], A[1, 2], A[2, 0], A[2, 1], A[2, 2] = a02, a12, a20, a21, a22
        regularised_inverse(A, L)
        for c in range(6):
            s0 = s1 = s2 = 0.0
            sigma_i = stress[i, c]
            for q in range(m):
                g = ff[q] * (stress[jj[q], c] - sigma_i)
                s0 += g * dd[q, 0]
                s1 += g * dd[q, 1]
                s2 += g * dd[q, 2]
            for a in range(dim):
                out[i, c, a] += L[a, 0] * s0
                out[i, c, a] += L[a, 1] * s1
                if dim == 3:
                    out[i, c, a] += L[a, 2] * s2


@njit(cache=True)
def linear_stress_diffusion(n, start, nbr, xc, stress, grad, mass, rho, kind, c0, k, rate):
    """rate_i = the linear diffusion term of the module docstring over material neighbours, G = ``grad``
    (``stress_gradient``), packed like the stress. The rows of i and j are taken as views once per
    pair, not indexed in the innermost loop: a third less time."""
    dim = xc.shape[1]
    h = k.h
    coef0 = 2.0 * DIFFUSION_ZETA * h * c0
    for i in range(n):
        rate_i = rate[i]
        rate_i[:] = 0.0
        if is_wall(kind[i]):
            continue
        grad_i, stress_i = grad[i], stress[i]
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            if is_wall(kind[j]):
                continue
            d0, d1, d2, r = pair_offset(xc, i, j)
            f = coef0 * mass[j] / rho[j] * r * pair_dw(k, r, i, j) / (r * r + 0.01 * h * h)
            grad_j, stress_j = grad[j], stress[j]
            for c in range(6):
                lin = 0.0  # (G_i + G_j)[c] . r_ij
                lin += (grad_i[c, 0] + grad_j[c, 0]) * d0
                lin += (grad_i[c, 1] + grad_j[c, 1]) * d1
                if dim == 3:
                    lin += (grad_i[c, 2] + grad_j[c, 2]) * d2
                rate_i[c] += f * (stress_i[c] - stress_j[c] - 0.5 * lin)


@njit(cache=True)
def _deviator(sig, out):
    """out = sig - tr(sig)/3 I; returns (I1, sqrt(J2))."""
    i1 = sig[0, 0] + sig[1, 1] + sig[2, 2]
    j2 = 0.0
    for a in range(3):
        for b in range(3):
            out[a, b] = sig[a, b]
        out[a, a] -= i1 / 3.0
    for a in range(3):
        for b in range(3):
            j2 += 0.5 * out[a, b] * out[a, b]
    return i1, math.sqrt(j2)


@njit(cache=True)
def return_mapping(sig, alpha_phi, k_c, dev):
    """Return the 3 x 3 stress ``sig`` to the yield surface in place; returns |Delta s|."""
    i1 = sig[0, 0] + sig[1, 1] + sig[2, 2]
    if alpha_phi > 0.0 and alpha_phi * i1 > k_c:
        shift = (i1 - k_c / alpha_phi) / 3.0
        for a in range(3):
            sig[a, a] -= shift
    i1, sqrt_j2 = _deviator(sig, dev)
    limit = k_c - alpha_phi * i1
    if sqrt_j2 <= limit:
        return 0.0
    scale = max(limit, 0.0) / sqrt_j2
    for a in range(3):
        for b in range(3):
            sig[a, b] = scale * dev[a, b]
        sig[a, a] += i1 / 3.0
    return (1.0 - scale) * math.sqrt(2.0) * sqrt_j2


@njit(inline="always")
def strain_of_multiplier(gamma):
    """The accumulated deviatoric plastic strain of the plastic multiplier ``gamma`` (a rate gives a
    rate): gamma / sqrt(3), the equivalent measure sqrt(2/3 e:e) of the deviatoric part of
    gamma dg/dsigma."""
    return gamma / math.sqrt(3.0)


@njit(inline="always")
def strain_of_return(ds, G):
    """The accumulated deviatoric plastic strain of a return to the yield surface that removed
    |Delta s| = ``ds`` of the deviator (``return_mapping``): sqrt(2/3) ds / 2G."""
    return math.sqrt(2.0 / 3.0) * ds / (2.0 * G)


@njit(inline="always")
def plastic_stress_rate(L, sig, dev, diffusion, i, K, G, alpha_phi, alpha_psi, k_c, rate):
    """rate = the stress rate of 000_ Eq. 10 (002_ Eq. 28) of the 3 x 3 ``sig`` under the
    velocity gradient ``L``, plus row i of the packed ``diffusion`` when it has rows; returns the
    plastic multiplier rate (000_ Eq. 13, 002_ Eq. 29), 0 unless the stress is on the yield
    surface and loading (module docstring). ``dev`` is left holding the deviator of ``sig``."""
    i1, sqrt_j2 = _deviator(sig, dev)
    tr_d = L[0, 0] + L[1, 1] + L[2, 2]
    s_d = 0.0
    for a in range(3):
        for b in range(3):
            d_ab = 0.5 * (L[a, b] + L[b, a])
            s_d += dev[a, b] * d_ab
    jaumann_rate(L, sig, G, rate)
    with_diffusion = diffusion.shape[0] > 0
    for a in range(3):
        if with_diffusion:
            for b in range(3):
                rate[a, b] += diffusion[i, SYM3[a, b]]
        rate[a, a] += (K - 2.0 * G / 3.0) * tr_d
    gamma_dot = 0.0
    if sqrt_j2 > 0.0 and alpha_phi * i1 + sqrt_j2 - k_c >= 0.0:
        gamma_dot = (3.0 * alpha_phi * K * tr_d + G / sqrt_j2 * s_d) / (9.0 * alpha_phi * K * alpha_psi + G)
    if gamma_dot > 0.0:
        for a in range(3):
            for b in range(3):
                rate[a, b] -= gamma_dot * G / sqrt_j2 * dev[a, b]
            rate[a, a] -= gamma_dot * 3.0 * K * alpha_psi
    return max(gamma_dot, 0.0)


@njit(cache=True)
def drucker_prager_update(n, start, nbr, xc, v, mass, rho, kind, normal, wall_distance, beta_max, B, k, diffusion,
                          K, G, alpha_phi, alpha_psi, k_c, dt, stress, plastic_strain):
    """sigma += dt (Eq. 10 rate + diffusion), return mapping, accumulated plastic strain, with
    L of Eq. 23 from ``velocity_gradient`` particle by particle."""
    L = np.empty((3, 3))
    dev = np.empty((3, 3))
    rate = np.empty((3, 3))
    sig = np.empty((3, 3))
    for i in range(n):
        if is_wall(kind[i]):
            continue
        velocity_gradient(i, start, nbr, xc, v, mass, rho, kind, normal, wall_distance, beta_max, B, k, L)
        unpack_row(stress, i, sig)
        gamma_dot = plastic_stress_rate(L, sig, dev, diffusion, i, K, G, alpha_phi, alpha_psi, k_c, rate)
        for a in range(3):
            for b in range(3):
                sig[a, b] += dt * rate[a, b]
        ds = return_mapping(sig, alpha_phi, k_c, dev)
        plastic_strain[i] += strain_of_multiplier(dt * gamma_dot) + strain_of_return(ds, G)
        for a in range(3):  # sig stays symmetric to the bit: every rate term is formed symmetrically
            for b in range(a, 3):
                stress[i, SYM3[a, b]] = sig[a, b]


INITIAL_STRESSES = ("geostatic", "none", "inverted")  # the choices of geostatic_stress's profile, the default first


def geostatic_stress(x, top, soil, g, k_lateral=None, profile="geostatic", base=0.0):
    """Initial stress (n, 3, 3) at rest under the ground surface at height ``top`` (a number: level
    ground; or a function of the positions (n, dim) giving the surface's height above each, for a
    slope: each particle then carries the column of soil above it, which is at rest away from a
    steep face but not at it): sigma_v = -rho0 g (top - y) on the vertical (last) axis,
    sigma_h = K sigma_v on the others (also out of plane in 2D), K = ``k_lateral`` or, if None,
    Jaky's 1 - sin phi. Other ``profile``s: "none",
    no stress (gravity loads the body at t = 0); "inverted", sigma_v = -rho0 g (y - ``base``), zero
    at the base and largest at the top, out of equilibrium: how the authors' SPHinXsys soil cases
    start (stress_yy = -rho0 g y, for example tests/2d_examples/test_2d_cohesive_soil_failure);
    000_ does not print its initial stress."""
    stress = np.zeros((len(x), 3, 3))
    vertical = x.shape[1] - 1
    surface = top(x) if callable(top) else top
    depth = {"geostatic": surface - x[:, vertical], "none": np.zeros(len(x)), "inverted": x[:, vertical] - base}[profile]
    sv = -soil.rho0 * g * depth
    k = soil.k0 if k_lateral is None else k_lateral
    for a in range(3):
        stress[:, a, a] = sv if a == vertical else k * sv
    return stress


class RiemannGranular(SolidScheme):
    """Drucker-Prager soil: the limiter eta = 20 d on separating pairs, Eq. 16 continuity, Eq. 25
    as printed (solid.py says why). Options ``limiter``: the pairs the limiter damps,
    ``separating``, ``approaching`` or ``none``; ``stress_diffusion``: ``linear`` (module docstring),
    ``geostatic`` (Feng et al., as 000_) or ``none``."""

    name = "riemann_granular"
    materials = (DruckerPrager,)
    options = {"limiter": "separating", "stress_diffusion": STRESS_DIFFUSIONS[0]}
    riemann_continuity = 1.0  # Eq. 16
    corrected_shear_force = False  # Eq. 25 as printed
    carried_fields = ("v", "rho", "stress")

    def __init__(self, case, kernel):
        super().__init__(case, kernel)
        self.eta = 20.0 * case.dim  # 000_ Sec. 3.1.3
        self.damped = limited_pairs_sign(self)
        self.g = float(np.linalg.norm(case.gravity))
        self.diffusion = self.option_choice("stress_diffusion", STRESS_DIFFUSIONS)
        self.fields = (SolidScheme.base_fields + (PLASTIC_STRAIN,)
                       + ((STRESS_GRADIENT,) if self.diffusion == "linear" else ()))

    def initial_density(self, pressure):
        return np.full_like(pressure, self.material.rho0)

    def state(self, ctx):
        pa = ctx.particles
        material_pressure(pa.n_owned, pa.kind, pa.stress, pa.p)

    def diffusion_rate(self, ctx):
        """The stress diffusion's rate of the owned particles (n x 6, packed; a workspace scratch
        valid until the next update), or NO_DIFFUSION for ``none``."""
        pa, m = ctx.particles, self.material
        n = pa.n_owned
        if self.diffusion == "none":
            return NO_DIFFUSION
        diffusion, = ctx.workspace.scratch(((n, 6), np.float64))
        if self.diffusion == "linear":
            stress_gradient(n, ctx.start, ctx.nbr, ctx.xc, pa.stress, pa.mass, pa.rho, pa.kind, ctx.kernel.params,
                            pa.stress_gradient)
            ctx.refresh(["stress_gradient"])
            linear_stress_diffusion(n, ctx.start, ctx.nbr, ctx.xc, pa.stress, pa.stress_gradient, pa.mass, pa.rho,
                                    pa.kind, m.c0, ctx.kernel.params, diffusion)
        else:
            stress_diffusion(n, ctx.start, ctx.nbr, ctx.xc, pa.stress, pa.mass, pa.rho, pa.kind, m.rho0, self.g,
                             m.k0, m.c0, ctx.kernel.params, diffusion)
        return diffusion

    def update_stress(self, ctx, dt):
        pa, m = ctx.particles, self.material
        diffusion = self.diffusion_rate(ctx)  # first: the linear form refreshes the ghosts' gradients
        drucker_prager_update(pa.n_owned, *self.gradient_args(ctx), diffusion, m.K, m.G, m.alpha_phi, m.alpha_psi,
                              m.k_c, dt, pa.stress, pa.plastic_strain)
