"""Dense granular flow with the mu(I) rheology (004_): the scheme and its pair loops.

The material is a weakly compressible visco-plastic fluid (mu_i_law.py gives
its pressure and viscosity). In the papers' sign convention (r_ij = x_i - x_j,
grad_i W_ij = W' r_ij / r, W' <= 0, kernels.py), with v_ij = v_i - v_j:

    strain rate    L_i = -sum_j V_j v_ij (x) grad_i W_ij,  eps = (L + L^T)/2,
                   gamma_dot = sqrt(2 eps:eps)                                 (004_ Eq. 31)
    continuity     drho_i/dt = sum_j m_j v_ij . grad_i W_ij                    (Eq. 26)
    momentum       dv_i/dt = g - sum_j m_j (p_i/rho_i^2 + p_j/rho_j^2 + Pi_ij) grad_i W_ij
                             + sum_j m_j 2 (D + 2) eta_ij (v_ij . r_ij) grad_i W_ij / (r^2 rho_i rho_j)
                                                                               (Eqs. 27, 37)
    eta_ij         2 eta_i eta_j / (eta_i + eta_j), the harmonic mean (Eq. 37), or
                   with the option viscosity_mean the arithmetic mean or the
                   secant viscosity of the pair's mean state (mu_i_law.pair_viscosity)
    Pi_ij          -alpha h c0 (v_ij . r_ij) / (rho_bar r^2)                   (Eq. 38)

Eq. 27 prints the factor 8 of the viscous term for its 2D runs: the Cleary /
Monaghan form reproduces div(eta grad v) with 2 (D + 2), which is 8 in 2D and
10 in 3D (tests/test_mu_i_law.py checks both on a lattice). Pi_ij is applied to
approaching and separating pairs alike, as Eq. 38 is printed; it dissipates
either way (its power is -alpha h c0 m_i m_j (v_ij . r_ij)^2 |W'| / (rho_bar r^3)
per pair). h_bar and c_bar of Eq. 38 are the one h and the sound speed at rest.

The option ``viscous_form = corrected_stress`` replaces the pair term of Eq.
27 by the divergence of the viscous stress 2 eta eps, eps from the gradient
corrected with B of 000_ Eq. 24 (L_i = M_i B_i) and the sum
sum_j m_j (T_i + T_j) grad_i W_ij / (rho_i rho_j) with T = 2 eta eps B, the
exact adjoint of that gradient, so that the force does the work the strain rate
dissipates, walls included (viscous_stress.py). It is exact for a quadratic
velocity on a lattice at h = 1.3 dp, where the pair term of Eq. 27 gives 81 %
(2D) and 87 % (3D) of div(eta grad v) (tests/test_mu_i_law.py), and the mu(I)
law magnifies such a deficit about eightfold in the speed of a uniform flow
(docs/VALIDATION.md). With ``Case.density_reinit`` the density is reset by
kernel summation (001_ Eq. 8, fluid.py) once per configuration.

The option ``viscous_stress = deviatoric`` takes the viscous stress as 2 eta dev(eps),
dev(eps) = eps - tr(eps) / D I: Eq. 4 with xi = 0, the fluid "with no bulk viscosity"
that 004_ says Eq. 10 is. The full stress 2 eta eps has the isotropic part
2 eta tr(eps) / D, a bulk viscosity 2 eta / D, and Eq. 27's pair term tends to
eta (lap v + 2 grad div v), a bulk viscosity (1 + 2 / D) eta (``pair_term_factors``);
below yield eta is about tau_y m_0 (Eq. 53). A released column sheds its pressure at
the face by expanding, and a bulk viscosity resists the expansion: with m_0 = 120 s
the full corrected stress starts the a = 0.5 column 0.077 s after release, the
deviatoric one at 0.054 s as at m_0 = 1.2 s; Eq. 27's pair term not within 0.1 s
(0.55 s, and sooner with stiffer grains, smaller K_t; docs/COLLAPSES.md), the
deviatoric pair term at 0.050 s, against 0.045 s at m_0 = 1.2 s and Eq. 27's 0.070 s
there (tests/test_mu_i_collapse.py). With the corrected stress the option keeps its
deviator; with the pair term it takes the pair form whose continuum limit is the
deviatoric stress's divergence at a uniform eta (``pair_term_factors``: Morris et
al.'s form in 2D), which, not being central, does not conserve angular momentum
exactly. A regularisation time long enough for a deposit to stop (m_0 = 40 s for
Lube's columns, granular_flow.DEVIATORIC_MU_I) then no longer delays the collapse.
Without the bulk part nothing damps the grains' acoustic noise: on the steady
incline the free surface erupts (docs/INCLINE.md).

The option ``pressure_form = isotropic`` replaces the pressure pairs of Eq. 27
by the same divergence of the stress T_i = -p_i s_i B_i, s_i = tr(A_i) / D with
A_i = B_i^-1 = -sum_j V_j r_ij (x) g_ij. Why: a pair sum F_ij carries across a
plane the stress of its virial, which for the pairs of Eq. 27 under a uniform
pressure is -p A_i per particle. A is a multiple of the identity only on an
isotropic arrangement; in a sheared layer the particles lie in sliding rows, A
has off-diagonal parts and the pressure pairs carry shear (0.4-0.5 % of the
normal traction on a lattice sheared by 0.3 dp per row,
tests/test_isotropic_pressure.py; 3-10 % of the weight's shear in the steady
incline, docs/INCLINE.md), where an isotropic pressure carries none in the
continuum. The stress T_i has the virial -p_i s_i B_i A_i = -p_i s_i I:
isotropic, with the trace of Eq. 27's, so that the pressure pushes as hard as
Eq. 27's on average, at a free surface (where s < 1) too. The pairs stay
antisymmetric (linear momentum is conserved); walls take the mirror image's
T_w = T_i (viscous_stress.py).

The option ``law_pressure = carried`` puts into the friction law the pressure
that the pairs carry, s_i p_i, rather than the grains' pressure p_i of Eq. 41.
Why: the law is a ratio of stresses, shear over normal, and in the discrete
balance of momentum the pairs carry the viscous stress in full (the virial of
T = 2 eta eps B is 2 eta eps B A = 2 eta eps) but only s p of the pressure,
with either pressure form (the trace of -p A). In a flowing layer s is
0.94-0.97 (docs/INCLINE.md), so the layer holds its weight only with a pressure
3-7 % above it, and a law that takes p then gives a friction that much below
tan(theta) where the continuum gives tan(theta) (d ln I / d ln mu = 8.2 turns
it into 25-45 % less shear). With s p the law's friction is the ratio of the
stresses the pairs carry; I and the dilatancy of Eq. 8 take the same pressure
(gamma_dot / sqrt(s) in Eq. 44). s is 0.974 on the square lattice at h = 1.3 dp
and lower in a disordered arrangement and near a free surface; it tends to 1
only as h / dp grows.

The option ``law_strain_rate = kernel_mean`` gives the law the modulus of the kernel mean of
the strain rate, sqrt(2 e_i : e_i) with e_i = sum_j V_j eps_j W_ij / sum_j V_j W_ij over the
moving particles j, i among them (kernel_mean.py), instead of the particle's
own gamma_dot_i. Why: a modulus is biased by noise. A particle's eps_i is the resolved strain
rate plus the particles' grain-to-grain jostle, which is not a field of the continuum and has no
mean, but adds its variance to 2 eps:eps. In simple shear the law's eta = mu p / gamma_dot then
gives the shear stress 2 eta eps_xy = mu p (2 eps_xy / gamma_dot), short of mu p by the
alignment 2 eps_xy / gamma_dot: 0.96-0.98 in the bulk of the steady incline at H/dp = 20 and
0.90-0.95 at 10 (docs/INCLINE.md), a shear deficit that the law magnifies eightfold in the
speed. The kernel mean averages the jostle out over the kernel's support (21 particles on a
square lattice at h = 1.3 dp; 0.98-0.99 on the same frames) and leaves a smooth field as it is to
second order in h. The viscous stress keeps the particle's
own eps (its divergence stays the gradient's adjoint); the mean needs eps on the ghosts (one
halo refresh per step).

The option ``law_strain_rate = deviatoric_kernel_mean`` takes the modulus of the kernel mean's
deviator e - tr(e) / D I instead. Why: 004_'s constitutive frame (Eq. 4, after Landau and
Lifshitz) puts the shear viscosity on the deviator of eps and the volume change on a bulk
viscosity; the modulus of Eq. 6 is that of the deviator wherever the flow is incompressible, as
the law was measured. The weakly compressible grains' volumetric rate div v is acoustic noise
that the law would count as shear: in the bulk of the steady incline its rms is 0.10-0.18 of the
shear rate at H/dp = 20 and 0.13-0.32 at H/dp = 40 (a pressure noise of a given size has a velocity noise
of a given size, whose gradient grows as 1/dp), and it is what the kernel mean leaves of the
misalignment (docs/INCLINE.md). The deviator is that of the model's D dimensions, whose pressure
is the mean of its D normal stresses. The viscous stress keeps the whole of eps unless
``viscous_stress = deviatoric``: its isotropic part, 2 eta div v / D, is the bulk viscosity that
damps the noise.

The option ``law_pressure = carried_mean`` gives the law the kernel mean of the carried pressure
s p (kernel_mean.py) and forms I from it (Eq. 6), where the grains' own pressure and dilatancy
(Eqs. 41-44) stay each particle's. Why: at a given strain rate the law's shear stress
mu(I) P = mu_s P + (mu_2 - mu_s) P I / (I + I_0), I proportional to P^(-1/2), is concave in P:
over a pressure that scatters by a relative variance sigma^2 about its mean it delivers the
fraction 1 - sigma^2 I_0 (3 I + I_0) / (8 (I + I_0)^2) of the mu_2 - mu_s part of the stress at the
mean pressure. The grains' pressures of the steady incline scatter by 0.35-0.76 of their layer's mean
(a grain-density scatter of 1e-3 is 63 Pa at K_t = 1.6e-5 1/Pa, where the weight at
mid-depth of the CI-sized layer is about 130 Pa), which costs the mean shear stress about
1 % at I_u, turned eightfold into shear rate by the law; the kernel mean takes the scatter out.
A continuum law takes the continuum's pressure, as it takes its strain rate. The mean needs s p on
the ghosts (one more halo refresh per step).

Walls are the ghost particles of Morris et al. (Eqs. 34-36, walls.py): a wall
partner takes the density, pressure and viscosity of particle i and the
relative velocity beta (v_i - v_w), only its normal part on a free-slip wall,
where the pair offset is taken along the wall's normal in the strain rate and
the momentum (walls.along_wall_normal, as the Riemann schemes and the implicit
kick do: the wall pushes only along its normal, however irregular its lattice).
The corrected stress sees a wall partner as a mirror image of particle i
instead (viscous_stress.py says why).

The time step is Eq. 39, CFL min(h/c0, 0.1 rho h^2/eta), 004_'s CFL 0.5. The
acoustic part comes from the time-step criteria: with the single criterion (the
mu(I) cases' default) at 000_'s CFL 0.4 (integrators/time_step.py), with dual
criteria at the scheme's ``acoustic_cfl``, 0.5. The viscous part, at CFL 0.5, is
the scheme's ``time_step_limit``, which the implicit viscous kick
(option ``viscous_step``, implicit_viscosity.py) lifts. The viscous limit takes the viscosity
of the last step's state (at the start of a run, of the initial particles' state), as the
later steps of a configuration always did: evaluating the state once more per configuration
for it cost two of the five pair passes of a step when every step has its own configuration
(docs/PERFORMANCE.md). The viscous force is evaluated every
step, so the advection criterion of 001_ Eq. 10 needs no viscous term here.
The order of the sub-steps is integrators/symplectic_verlet.py's.
"""

import math

import numpy as np
from numba import njit

from ..errors import InputError
from ..forces import ForceTerm
from ..kernels import pair_dw
from ..materials import MuIGranular
from ..neighbours import pair_difference, pair_offset
from ..particles import MOVING, WALL_SLIP, Field, is_wall
from ..scheme import Scheme
from ..tensors import adjugate, component
from ..well_posedness import well_posed_range, well_posed_window
from .implicit_viscosity import TOLERANCE, ImplicitViscosity
from .mu_i_law import (MEAN_SECANT, friction, grain_density_ratio, grain_size, inertial_number, pair_viscosity,
                       regularised_viscosity)
from .kernel_mean import kernel_mean, rate_modulus
from .mu_i_stress import granular_stress_of
from .solid import SOLID_OUTPUT_FIELDS, STRESS, solid_output_fields
from .viscous_stress import stress_divergence, strain_rate, viscous_force_tensor
from .walls import WALL_DISTANCE, MorrisWalls, along_wall_normal, morris_relative_velocity, require_wall_distances

VISCOUS_CFL = 0.5 * 0.1  # 004_ Eq. 39: CFL 0.5 times the 0.1 of the viscous limit


@njit(cache=True)
def granular_state(n, kind, rho, gamma_dot, B, carried, rho_s, p, eta, dim, m, law_p):
    """Grain density, pressure and regularised viscosity of the moving particles from their bulk
    density and strain rate (004_ Eqs. 41-44, 46-47, 55; mu_i_law.py). With ``carried`` the law
    takes the pressure the pairs carry, s p with s = tr(B^-1) / D (module docstring): I and the
    dilatancy of Eq. 8 from gamma_dot / sqrt(s), eta from s p. With ``law_p`` of length N it stores
    the law's pressure s p there instead of eta, which ``law_viscosity`` then takes from its kernel
    mean."""
    full, adj = np.empty((dim, dim)), np.empty((dim, dim))
    for i in range(n):
        if kind[i] != MOVING:
            continue
        s = carried_fraction(B, i, full, adj) if carried else 1.0
        x = grain_density_ratio(rho[i], gamma_dot[i] / math.sqrt(s), rho_s[i] / m.rho_s0, dim, m)
        rho_s[i] = x * m.rho_s0
        p[i] = (x - 1.0) / m.K_t
        if law_p.shape[0] > 0:
            law_p[i] = s * p[i]
            continue
        I = inertial_number(rho[i], rho_s[i], m)
        eta[i] = regularised_viscosity(s * p[i], gamma_dot[i], I, rho_s[i], grain_size(x, dim, m), m)


@njit(cache=True)
def law_viscosity(n, kind, rho_s, gamma_dot, law_p, eta, dim, m):
    """eta of the moving particles from the law's pressure ``law_p`` (with law_pressure = carried_mean
    the kernel mean of s p) and I = gamma_dot d / sqrt(law_p / rho_s) of 004_ Eq. 6, d the grain size
    of Eq. 43 (mu_i_law.py); zero where law_p <= 0."""
    for i in range(n):
        if kind[i] != MOVING:
            continue
        I, d = law_inertial_number(gamma_dot[i], rho_s[i], law_p[i], dim, m)
        eta[i] = regularised_viscosity(law_p[i], gamma_dot[i], I, rho_s[i], d, m)


@njit(inline="always")
def law_inertial_number(gamma_dot, rho_s, law_p, dim, m):
    """(I, d): I = gamma_dot d / sqrt(law_p / rho_s) of 004_ Eq. 6 from the law's pressure, 0 where
    law_p <= 0, and the grain size d of Eq. 43 (mu_i_law.grain_size)."""
    d = grain_size(rho_s / m.rho_s0, dim, m)
    return (gamma_dot * d * math.sqrt(rho_s / law_p) if law_p > 0.0 else 0.0), d


@njit(inline="always")
def carried_fraction(B, i, full, adj):
    """s_i = tr(B_i^-1) / D = tr(A_i) / D, A_i = -sum_j V_j r_ij (x) g_ij (000_ Eq. 24, where B is
    not regularised): the share of its pressure that a particle's pairs carry (module docstring).
    ``full`` and ``adj`` are D x D scratch."""
    dim = full.shape[0]
    for a in range(dim):
        for b in range(dim):
            full[a, b] = B[i, component(dim, a, b)]
    det = adjugate(full, adj)
    trace = 0.0
    for a in range(dim):
        trace += adj[a, a]
    return trace / (dim * det)


@njit(cache=True)
def isotropic_pressure_stress(n, kind, p, B, T):
    """T_i = -p_i s_i B_i with s_i = tr(B_i^-1) / D of the moving particles: the pressure's stress
    whose pair sum sum_j m_j (T_i + T_j) g_ij / (rho_i rho_j) has an isotropic virial (module
    docstring)."""
    dim = T.shape[1]
    full, adj = np.empty((dim, dim)), np.empty((dim, dim))
    for i in range(n):
        if kind[i] != MOVING:
            continue
        scale = -p[i] * carried_fraction(B, i, full, adj)
        for a in range(dim):
            for b in range(dim):
                T[i, a, b] = scale * full[a, b]


@njit(cache=True)
def momentum(n, start, nbr, xc, v, rho, p, eta, gamma_dot, mass, kind, normal, wall_distance, beta_max, alpha,
             c0, pair_pressure, viscous_factor, radial, along, mean, k, acc):
    """acc += the pressure, artificial-viscosity and viscous accelerations (004_ Eqs. 27, 37-38);
    ``pair_pressure`` False leaves the pressure out (to the isotropic pressure), ``viscous_factor`` 0
    the viscous part (to the corrected stress, or the implicit kick). The viscous pair force is
    eta_ij (radial (v_ij . e) e + along v_ij) m_j W' / (r rho_i rho_j), e = r_ij / r, eta_ij the pair
    viscosity (mu_i_law.pair_viscosity) times ``viscous_factor`` (``pair_term_factors``)."""
    dim = xc.shape[1]
    for i in range(n):
        if kind[i] != MOVING:
            continue
        a0 = a1 = a2 = 0.0
        rho_i2 = rho[i] * rho[i]
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            d0, d1, d2, r = pair_offset(xc, i, j)
            u0, u1, u2 = pair_difference(v, i, j)
            rho_j, p_j, eta_j, gamma_dot_j = rho[j], p[j], eta[j], gamma_dot[j]
            if is_wall(kind[j]):  # off the common path
                u0, u1, u2 = morris_relative_velocity(i, j, xc, v, kind, normal, wall_distance, beta_max)
                rho_j, p_j, eta_j, gamma_dot_j = rho[i], p[i], eta[i], gamma_dot[i]
                if kind[j] == WALL_SLIP:
                    d0, d1, d2 = along_wall_normal(j, normal, d0, d1, d2)
            rho_j2 = rho_j * rho_j
            vr_r2 = (u0 * d0 + u1 * d1 + u2 * d2) / (r * r)
            scalar = -(p[i] / rho_i2 + p_j / rho_j2) if pair_pressure else 0.0
            if alpha > 0.0:
                scalar += alpha * k.h * c0 * vr_r2 / (0.5 * (rho[i] + rho_j))  # -Pi_ij
            eta_ij = 0.0
            if viscous_factor > 0.0 and eta[i] + eta_j > 0.0:
                eta_ij = pair_viscosity(viscous_factor, eta[i], eta_j, gamma_dot[i], gamma_dot_j, mean)
                if radial > 0.0:
                    scalar += radial * eta_ij * vr_r2 / (rho[i] * rho_j)
            f = mass[j] * pair_dw(k, r, i, j) / r
            a0 += f * scalar * d0
            a1 += f * scalar * d1
            a2 += f * scalar * d2
            if along > 0.0 and eta_ij > 0.0:  # the relative velocity's own part (viscous_stress = deviatoric)
                g = f * along * eta_ij / (rho[i] * rho_j)
                a0 += g * u0
                a1 += g * u1
                a2 += g * u2
        acc[i, 0] += a0
        acc[i, 1] += a1
        if dim == 3:
            acc[i, 2] += a2


@njit(cache=True)
def continuity(n, start, nbr, xc, v, mass, kind, normal, wall_distance, beta_max, k, drho_dt):
    """drho_i/dt = sum_j m_j v_ij . grad_i W_ij of the material particles, moving and clamped (004_
    Eq. 26; the classic schemes take it too, whose clamped particles, held in place, evolve their
    density as particles.py says)."""
    for i in range(n):
        if is_wall(kind[i]):
            continue
        acc = 0.0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            d0, d1, d2, r = pair_offset(xc, i, j)
            u0, u1, u2 = pair_difference(v, i, j)
            if is_wall(kind[j]):  # off the common path
                u0, u1, u2 = morris_relative_velocity(i, j, xc, v, kind, normal, wall_distance, beta_max)
            acc += mass[j] * (u0 * d0 + u1 * d1 + u2 * d2) / r * pair_dw(k, r, i, j)
        drho_dt[i] = acc


@njit(cache=True)
def viscous_time_step(n, kind, rho, eta, h):
    """VISCOUS_CFL min_i rho_i h^2 / eta_i over the moving particles (004_ Eq. 39), inf if none
    is viscous."""
    best = np.inf
    for i in range(n):
        if kind[i] == MOVING and eta[i] > 0.0:
            best = min(best, VISCOUS_CFL * rho[i] * h * h / eta[i])
    return best


@njit(cache=True)
def inertial_number_and_friction(n, kind, rho, rho_s, gamma_dot, law_p, dim, m, I, mu):
    """For frames, the I and mu(I) (Eq. 7) the law takes: I from the volume fraction (Eq. 8), or
    with ``law_p`` of length N (law_pressure = carried_mean) from the strain rate and the law's
    pressure (``law_inertial_number``), as ``law_viscosity`` takes it (0 off the moving particles)."""
    for i in range(n):
        if law_p.shape[0] == 0:
            I[i] = inertial_number(rho[i], rho_s[i], m)
        elif kind[i] == MOVING:
            I[i] = law_inertial_number(gamma_dot[i], rho_s[i], law_p[i], dim, m)[0]
        else:
            I[i] = 0.0
        mu[i] = friction(I[i], m)


def pair_term_factors(dim, deviatoric):
    """(eta factor, radial, along) of the viscous pair force eta_ij (radial (v_ij . e) e + along v_ij)
    m_j W' / (r rho_i rho_j) (``momentum``). On a smooth velocity at a uniform eta the two parts tend
    to (radial / (D + 2)) eta (lap v + 2 grad div v) / 2 and along eta lap v / 2 (the kernel's
    second moments, sum_j V_j W' r = -D). Eq. 27 (its 8 as 2 (D + 2)) is radial = 2 (D + 2) alone: eta (lap v +
    2 grad div v), whose isotropic part is a bulk viscosity (1 + 2 / D) eta. The deviatoric
    stress's divergence eta (lap v + (1 - 2 / D) grad div v) takes radial = (D + 2)(D - 2) / D and
    along = (D + 2) / D: Morris et al.'s (1997) form alone in 2D, 5/3 of each part in 3D (the
    form of Espanol and Revenga 2003 with no bulk viscosity). Eq. 27's keeps its factor in eta_ij
    (the bits of its runs); the deviatoric one's factors stay apart."""
    if deviatoric:
        return 1.0, (dim + 2.0) * (dim - 2.0) / dim, (dim + 2.0) / dim
    return 2.0 * (dim + 2), 1.0, 0.0


# The momentum the particles' velocity fluctuations carry across a sheared layer, rho <v'v'> normal to
# it, over the pressure, per (I dp / d)^2: the particles ride over each other at about half of gamma_dot dp
# whatever the grain size d, so they add the collisional stress of grains dp large to the law's of grains
# d. Measured on uniform incline flows at dp / d = 1, 2 and 4 (two runs) without Eq. 38's artificial
# viscosity, which damps the jostle: 0.110-0.119 at I = I_u (docs/INCLINE.md, the particles' jostle).
JOSTLE_STRESS = 0.12


def jostle_inertial_number(share, grains):
    """The inertial number at which the particles' jostle carries ``share`` of the pressure (JOSTLE_STRESS)
    where they are ``grains`` = dp / d grains wide."""
    return math.sqrt(share / JOSTLE_STRESS) / grains


class GranularMomentum(ForceTerm):
    """Pressure, artificial viscosity and mu(I) viscosity in one pair sum (module docstring)."""

    name = "mu_i_momentum"

    def __init__(self, scheme):
        self.scheme = scheme

    def add(self, ctx, acc):
        self._add(ctx, acc, not self.scheme.implicit)

    def add_all(self, ctx, acc):
        self._add(ctx, acc, True)

    def _add(self, ctx, acc, viscous):
        """The pair sum, with the viscous term or without it (left to the implicit kick); the
        corrected stress's divergence is a pass of its own (viscous_stress.py)."""
        pa, s = ctx.particles, self.scheme
        pair_term = viscous and not s.corrected
        momentum(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.v, pa.rho, pa.p, pa.eta, pa.gamma_dot, pa.mass, pa.kind,
                 pa.normal, pa.wall_distance, s.beta_max, s.alpha, s.material.c0, not s.isotropic,
                 s.viscous_factor if pair_term else 0.0, s.radial, s.along, s.mean, ctx.kernel.params, acc)
        if s.isotropic:
            stress_divergence(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.rho, pa.T_pressure, pa.mass, pa.kind,
                              pa.normal, ctx.kernel.params, acc)
        if viscous and s.corrected:
            stress_divergence(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.rho, pa.T_visc, pa.mass, pa.kind, pa.normal,
                              ctx.kernel.params, acc)


VISCOUS_FORMS = ("cleary", "corrected_stress")
VISCOUS_STRESSES = ("full", "deviatoric")
VISCOUS_STEPS = ("explicit", "implicit")
VISCOSITY_MEANS = ("harmonic", "arithmetic", "secant")  # in the order of mu_i_law's MEAN_* codes
PRESSURE_FORMS = ("symmetric", "isotropic")
LAW_PRESSURES = ("state", "carried", "carried_mean")
LAW_STRAIN_RATES = ("own", "kernel_mean", "deviatoric_kernel_mean")


class MuIScheme(MorrisWalls, Scheme):
    """mu(I) granular fluid with weakly compressible grains (004_ Secs. 3-4).

    At the start of a run the state of the initial particles; per configuration:
    the wall distances on ghosts and the density reinitialisation; per step: strain rate,
    then grain density, pressure and viscosity (the state), and continuity (the
    rate). Options (``Case.scheme_options``): ``alpha`` of Eq. 38 (default 0),
    ``beta_max`` of Eq. 36 (default 1.5, Morris et al.), ``viscous_form``:
    ``cleary``, the pair term of Eq. 27 (its 8 as 2 (D + 2)), or ``corrected_stress``, the
    viscous stress 2 eta eps from the corrected gradient and its divergence with
    the correction matrix (module docstring), and ``viscous_step``: ``explicit``
    (Eq. 39's viscous limit bounds the step) or ``implicit``, the viscous term
    of either form taken backward in time in the kick (implicit_viscosity.py), and
    ``viscosity_mean``: ``harmonic`` (Eq. 37), ``arithmetic`` or ``secant``
    (mu_i_law.pair_viscosity; ghosts then need gamma_dot too), and
    ``viscous_stress``: ``full`` (2 eta eps, or Eq. 27's pair term) or ``deviatoric``
    (2 eta dev(eps), Eq. 4 with no bulk viscosity, or the pair term that tends to its divergence), and
    ``pressure_form``: ``symmetric`` (Eq. 27) or ``isotropic``, and ``law_pressure``: ``state``
    (the grains' pressure of Eq. 41), ``carried`` (the share of it the pairs carry) or
    ``carried_mean`` (its kernel mean) in the friction law, and ``law_strain_rate``: ``own`` (each
    particle's gamma_dot, Eq. 31), ``kernel_mean`` (the modulus of the kernel mean of eps) or
    ``deviatoric_kernel_mean`` (that of its deviator) in the law (module docstring), and
    ``viscous_tolerance``: where the implicit kick's iterations stop, as an RMS velocity over the
    case's reference speed (default 1e-7; implicit_viscosity.py; another value with the explicit
    step is an InputError, since it would change nothing).
    """

    name = "mu_i"
    integrator = "symplectic_verlet"  # 004_ Sec. 3.4
    materials = (MuIGranular,)
    acoustic_cfl = 0.5  # 004_ Eq. 39
    derived = (Field("inertial_number", (), np.float64, "inertial number I the law takes: from the volume fraction "
                     "(004_ Eq. 8), with law_pressure = carried_mean from gamma_dot and law_pressure (Eq. 6) [-]"),
               Field("friction", (), np.float64, "friction coefficient mu(I) of that I (004_ Eq. 7) [-]"),
               STRESS, *SOLID_OUTPUT_FIELDS)  # the stress of mu_i_stress.py
    options = {"alpha": 0.0, "beta_max": 1.5, "viscous_form": "cleary", "viscous_step": "explicit",
               "viscous_stress": "full", "viscosity_mean": "harmonic", "pressure_form": "symmetric",
               "law_pressure": "state", "law_strain_rate": "own", "viscous_tolerance": TOLERANCE}

    def __init__(self, case, kernel):
        super().__init__(case, kernel)
        self.alpha = self.option("alpha")
        self.beta_max = self.option("beta_max")
        self.corrected = self.option_choice("viscous_form", VISCOUS_FORMS) == "corrected_stress"
        self.implicit = self.option_choice("viscous_step", VISCOUS_STEPS) == "implicit"
        if not self.implicit and self.option("viscous_tolerance") != TOLERANCE:
            raise InputError(f"scheme {self.name}: viscous_tolerance sets where the implicit kick stops, "
                             "so it needs viscous_step=implicit")
        self.deviatoric_stress = self.option_choice("viscous_stress", VISCOUS_STRESSES) == "deviatoric"
        self.mean = VISCOSITY_MEANS.index(self.option_choice("viscosity_mean", VISCOSITY_MEANS))
        self.isotropic = self.option_choice("pressure_form", PRESSURE_FORMS) == "isotropic"
        law_pressure = self.option_choice("law_pressure", LAW_PRESSURES)
        self.carried = law_pressure != "state"
        self.smoothed_pressure = law_pressure == "carried_mean"
        law_strain_rate = self.option_choice("law_strain_rate", LAW_STRAIN_RATES)
        self.smoothed_rate = law_strain_rate != "own"
        self.deviatoric_rate = law_strain_rate == "deviatoric_kernel_mean"
        self.uses_B = self.corrected or self.isotropic or self.carried
        self.viscous_factor, self.radial, self.along = pair_term_factors(case.dim, self.deviatoric_stress)
        self.h, self.dp = kernel.h, case.dp
        self.params = self.material.params
        require_wall_distances(case, self.name)
        self.fields = (
            Field("strain", ("sym",), np.float64, "strain-rate tensor eps, packed (tensors.py) [1/s]"),
            Field("gamma_dot", (), np.float64,
                  "strain-rate modulus the law takes, sqrt(2 eps:eps) or that of eps's kernel mean [1/s]"),
            Field("eta", (), np.float64, "regularised viscosity [Pa s]"),
            Field("rho_s", (), np.float64, "grain density [kg/m^3]"),
            WALL_DISTANCE,
        )
        if self.smoothed_pressure:
            self.fields += (Field("law_pressure", (), np.float64,
                                  "pressure the law takes, the kernel mean of s p (law_pressure = carried_mean) [Pa]"),)
        self.state_fields = ("p", "eta") + (("gamma_dot",) if self.mean == MEAN_SECANT else ())
        if self.corrected:
            self.fields += (
                Field("B", ("sym",), np.float64, "kernel-gradient correction matrix (000_ Eq. 24), packed [-]"),
                Field("T_visc", ("dim", "dim"), np.float64, "viscous stress times B, 2 eta eps B [Pa]"))
            # the explicit divergence needs the neighbours' T, the implicit kick's preconditioner their eta
            self.state_fields = ("p", "eta") if self.implicit else ("p", "T_visc")
        if self.isotropic:
            self.fields += (Field("T_pressure", ("dim", "dim"), np.float64,
                                  "the pressure's stress times B, -p tr(B^-1) B / D [Pa]"),)
            self.state_fields += ("T_pressure",)
        if self.implicit:
            self.implicit_viscosity = ImplicitViscosity(self, case.u_ref, self.option("viscous_tolerance"))
            self.counter_names = ("viscous_iterations",)
            self.fields += (Field("viscous_direction", ("dim",), np.float64,
                                  "search direction of the implicit viscous kick [m/s]"),
                            Field("viscous_acceleration", ("dim",), np.float64,
                                  "viscous acceleration of the last implicit kick [m/s^2]"),
                            Field("viscous_acceleration_change", ("dim",), np.float64,
                                  "its change from the kick before over the step, from which the next kick's first "
                                  "guess extrapolates [m/s^3]"))
            if self.corrected:
                self.fields += (Field("viscous_direction_stress", ("dim", "dim"), np.float64,
                                      "2 eta eps B of the implicit kick's search direction [Pa]"),)
        self._no_B = np.zeros((0, 1))
        self._no_law_pressure = np.zeros(0)

    def forces(self):
        return (GranularMomentum(self),)

    def start(self, ctx):
        self.state(ctx)
        ctx.refresh(self.state_fields)
        if self.implicit:
            self.implicit_viscosity.history = False  # no kick before the first

    def state(self, ctx):
        pa = ctx.particles
        n = pa.n_owned
        B = ctx.correction_matrices() if self.uses_B else self._no_B
        strain_rate(n, ctx.start, ctx.nbr, ctx.xc, pa.v, pa.rho, pa.mass, pa.kind, pa.normal, pa.wall_distance,
                    self.beta_max, B if self.corrected else self._no_B, ctx.kernel.params, pa.strain, pa.gamma_dot)
        if self.smoothed_rate:
            ctx.refresh(["strain"])
            mean_strain = ctx.workspace.get("law_mean_strain", n, pa.strain.shape[1:])
            kernel_mean(n, ctx.start, ctx.nbr, ctx.xc, pa.rho, pa.mass, pa.kind, pa.strain, ctx.kernel.params,
                        mean_strain)
            rate_modulus(n, pa.kind, mean_strain, self.deviatoric_rate, self.dim, pa.gamma_dot)
        law_p = self._law_pressure(pa)
        granular_state(n, pa.kind, pa.rho, pa.gamma_dot, B, self.carried, pa.rho_s, pa.p, pa.eta, self.dim,
                       self.params, law_p)
        if self.smoothed_pressure:
            ctx.refresh(["law_pressure"])
            mean_p = ctx.workspace.get("law_mean_pressure", n, (1,))
            kernel_mean(n, ctx.start, ctx.nbr, ctx.xc, pa.rho, pa.mass, pa.kind, law_p.reshape(-1, 1),
                        ctx.kernel.params, mean_p)
            moving = pa.kind[:n] == MOVING  # kernel_mean leaves the other rows of mean_p unset
            law_p[:n][moving] = mean_p[moving, 0]
            law_viscosity(n, pa.kind, pa.rho_s, pa.gamma_dot, law_p, pa.eta, self.dim, self.params)
        if self.corrected:
            viscous_force_tensor(n, pa.kind, pa.strain, pa.eta, B, self.deviatoric_stress, pa.T_visc)
        if self.isotropic:
            isotropic_pressure_stress(n, pa.kind, pa.p, B, pa.T_pressure)

    def _law_pressure(self, pa):
        """The law's pressure of the particles (law_pressure = carried_mean), or an empty array."""
        return pa.law_pressure if self.smoothed_pressure else self._no_law_pressure

    def rates(self, ctx, dt):
        pa = ctx.particles
        continuity(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.v, pa.mass, pa.kind, pa.normal, pa.wall_distance,
                   self.beta_max, ctx.kernel.params, pa.drho_dt)

    def time_step_limit(self, ctx):
        if self.implicit:
            return math.inf
        pa = ctx.particles
        return viscous_time_step(pa.n_owned, pa.kind, pa.rho, pa.eta, self.h)

    def implicit_kick(self, ctx, dt):
        self.implicit_viscosity.kick(ctx, dt)

    def report(self):
        m = self.material
        window = well_posed_window(m.params)
        where = "at no I" if window is None else well_posed_range(*window)
        grains = self.dp / m.params.d0
        return (f"mu(I): sound speed at rest c0 = {m.c0:.4g} m/s; regularised viscosity at tau_y = tau_0 = "
                f"{m.tau_0:g} Pa: eta_max = {m.eta_max(m.tau_0):.4g} Pa s (004_ Eq. 53)",
                f"mu(I): the friction law is well-posed {where} (Barker et al. 2015, incompressible); a flow "
                "outside that range need not converge with the resolution (mpisph/well_posedness.py)",
                f"mu(I): the particles are dp / d = {grains:.3g} grains wide; sheared (alpha = 0), their jostle "
                f"carries about {JOSTLE_STRESS:g} (I dp / d)^2 of the pressure, a stress outside the law: 1 % at "
                f"I = {jostle_inertial_number(0.01, grains):.2g}, 10 % at I = "
                f"{jostle_inertial_number(0.1, grains):.2g} (docs/INCLINE.md)")

    def warnings(self):
        d0 = self.material.params.d0
        if self.dp >= d0:
            return ()
        return (f"mu(I): a particle (dp = {self.dp:g} m) is narrower than a grain (d = {d0:g} m): the law is a "
                "continuum's, for particles many grains wide (004_ takes dp = 10 d)",)

    def closing_report(self):
        return (self.implicit_viscosity.summary(),) if self.implicit else ()

    def counters(self):
        return {"viscous_iterations": self.implicit_viscosity.mean_since_last_row()} if self.implicit else {}

    def derived_fields(self, pa, n):
        I, mu = np.zeros(n), np.zeros(n)
        law_p = self._law_pressure(pa)
        inertial_number_and_friction(n, pa.kind, pa.rho, pa.rho_s, pa.gamma_dot, law_p, self.dim, self.params, I, mu)
        stress = granular_stress_of(self, pa, n)
        return {"inertial_number": I, "friction": mu, "stress": stress, **solid_output_fields(stress, pa.v, n)}
