"""Weakly compressible fluid with the linearised Riemann solver.

Equation of state p = c0^2 (rho - rho0) (000_ Eq. 3). Pairwise interface
states from the linearised Riemann solver with dissipation limiter
(001_ Eqs. 4-6; the acoustic form of 000_ Eqs. 18-20 when rho_L c_L equals
rho_R c_R):

    U*  = (U_l + U_r)/2 + (p_l - p_r) / (2 rho_bar c)
    P*  = (p_l + p_r)/2 + beta rho_bar c (U_l - U_r) / 2
    beta = min(eta max(u_jump/c, 0), 1),   eta = 3

In the papers' sign convention (e_ij from j to i, see kernels.py) the
compression speed U_l - U_r (U = velocity along the axis from i to j, 000_
Eq. 19) equals -u_jump with u_jump = (v_i - v_j).e_ij, so the dissipative
part of P* is -beta rho_bar c u_jump / 2: its pair power,
beta rho_bar c m_i m_j u_jump^2 W'_ij / (rho_i rho_j), is never positive,
whichever pairs beta selects. Continuity (000_ Eq. 16 / 001_ Eq. 3) and
pressure acceleration (000_ Eq. 17) then read

    drho_i/dt = rho_i sum_j V_j [u_jump + (p_i - p_j)/(rho_bar c)] W'_ij
    dv_i/dt   = -2/rho_i sum_j V_j P* W'_ij e_ij

The limiter acts on separating pairs (u_jump > 0), the one rule for fluids
and granular materials (solid.py): it is what the authors' code, SPHinXsys,
does in the density relaxation of its fluid and plastic-continuum steps
(``DissipativePJump(u_jump) = rho0 c0 u_jump limiter(max(u_jump, 0))``,
u_jump = (v_i - v_j).e_ij, e_ij from j to i), and what 001_ Eq. 6 gives with
its U_l = v_i.e_ij (001_ writes e_ij = -r_ij / r_ij without the direction of r_ij;
its momentum, Eq. 3, repels a pair under pressure only with e_ij from j to i, and
then U_l - U_r = u_jump). 000_'s text (a compression wave, U_L >= U_R, with
U_L = -v_i.e_ij) would damp approaching pairs instead; the scheme option
``limiter = approaching`` runs that reading, ``limiter = none`` leaves out the
dissipation of the momentum (SPHinXsys's "NoRiemann" density relaxation). Energy cannot decide between them
(both dissipate); on the drop and the dam break's early front they differ by
less than 1 %, on its late speed by 2 % (docs/REMEDIES.md,
scripts/limiter_study.py).

and the viscous acceleration is 001_ Eq. 7,
2/rho_i sum_j V_j mu v_ij / (r_ij + 0.01 h) W'_ij, where Eq. 7 prints v_ij / r_ij: the
0.01 h, as in the authors' code (SPHinXsys's ViscousAcceleration), keeps a close pair's
term finite.

Walls are fixed dummy particles. A wall neighbour j takes the fluid
particle's density, a pressure extrapolated hydrostatically,
p_i + rho_i max(0, -g.r_ij), and a mirrored velocity 2 v_w - v_i (no-slip,
kind WALL) or one with only the normal component mirrored (free-slip, kind
WALL_SLIP). The viscous term uses v_i - v_w (no-slip) or its normal part
(free-slip). A free-slip partner's pressure acts along the wall's normal
(walls.along_wall_normal: the continuity sees only the mirrored normal
velocity, so only that direction keeps the pressure's work equal to what the
density stores; solid.py gives the derivation).
"""

from numba import njit

from ..forces import ForceTerm
from ..kernels import pair_dw
from ..materials import Fluid
from ..neighbours import pair_difference, pair_distance, pair_offset
from ..particles import MOVING, WALL_SLIP, is_wall
from ..scheme import Scheme
from .density_reinit import reinitialise_density
from .walls import along_wall_normal, wall_relative_normal, wall_relative_velocity

RIEMANN_ETA = 3.0
# The pairs the dissipation limiter damps (the schemes' option ``limiter``): the sign of u_jump
# that makes beta positive, beta = min(eta max(sign u_jump / c0, 0), 1); none: beta = 0.
LIMITED_PAIRS = {"approaching": -1.0, "separating": 1.0, "none": 0.0}


def limited_pairs_sign(scheme):
    """The sign of LIMITED_PAIRS for the option ``limiter`` of ``scheme``; InputError if unknown."""
    return LIMITED_PAIRS[scheme.option_choice("limiter", LIMITED_PAIRS)]


@njit(inline="always")
def linear_pressure(rho, rho0, c0):
    """p = c0^2 (rho - rho0) (000_ Eqs. 3, 5; materials.LinearEquationOfState)."""
    return c0 * c0 * (rho - rho0)


@njit(cache=True)
def equation_of_state(n, kind, rho, p, rho0, c0):
    """p = c0^2 (rho - rho0) for the moving particles in [0, n) (000_ Eq. 3)."""
    for i in range(n):
        if kind[i] == MOVING:
            p[i] = linear_pressure(rho[i], rho0, c0)


@njit(cache=True)
def _wall_state(i, j, xc, rho, p, gravity):
    """(rho_j, p_j) as particle i sees wall particle j: the density of i and the pressure of i
    extrapolated hydrostatically, p_i + rho_i max(0, -g.r_ij)."""
    gr = 0.0
    for a in range(xc.shape[1]):
        gr -= gravity[a] * (xc[i, a] - xc[j, a])
    return rho[i], p[i] + rho[i] * max(0.0, gr)


@njit(cache=True)
def pressure_acceleration(n, start, nbr, xc, v, rho, p, mass, kind, normal, gravity, c0, damped, k, acc):
    """acc += -2/rho_i sum_j V_j P* W'_ij e_ij (000_ Eq. 17, 001_ Eqs. 5-6), the limiter on the
    pairs whose u_jump has the sign ``damped`` (LIMITED_PAIRS)."""
    dim = xc.shape[1]
    for i in range(n):
        if kind[i] != MOVING:
            continue
        a0 = a1 = a2 = 0.0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            d0, d1, d2, r = pair_offset(xc, i, j)
            u0, u1, u2 = pair_difference(v, i, j)
            rho_j, p_j = rho[j], p[j]
            if is_wall(kind[j]):  # off the common path
                u0, u1, u2 = wall_relative_velocity(i, j, v, kind, normal)
                rho_j, p_j = _wall_state(i, j, xc, rho, p, gravity)
                if kind[j] == WALL_SLIP:
                    d0, d1, d2 = along_wall_normal(j, normal, d0, d1, d2)
            u_jump = (u0 * d0 + u1 * d1 + u2 * d2) / r
            beta = min(RIEMANN_ETA * max(damped * u_jump / c0, 0.0), 1.0)
            p_star = 0.5 * (p[i] + p_j) - 0.25 * beta * (rho[i] + rho_j) * c0 * u_jump
            f = -2.0 * mass[j] / rho[j] * p_star * pair_dw(k, r, i, j) / r
            a0 += f * d0
            a1 += f * d1
            a2 += f * d2
        acc[i, 0] += a0 / rho[i]
        acc[i, 1] += a1 / rho[i]
        if dim == 3:
            acc[i, 2] += a2 / rho[i]


@njit(cache=True)
def continuity(n, start, nbr, xc, v, rho, p, mass, kind, normal, gravity, c0, riemann, k, drho_dt):
    """drho/dt = rho_i sum_j V_j [u_jump + riemann (p_i - p_j)/(rho_bar c0)] W'_ij.

    ``riemann`` = 1: 000_ Eq. 16 (fluids, granular materials); 0: Eq. 21
    (elastic solids, no Riemann dissipation). Moving and clamped particles.
    """
    for i in range(n):
        if is_wall(kind[i]):
            continue
        acc = 0.0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            d0, d1, d2, r = pair_offset(xc, i, j)
            u0, u1, u2 = pair_difference(v, i, j)
            rho_j, p_j = rho[j], p[j]
            if is_wall(kind[j]):  # off the common path
                u0, u1, u2 = wall_relative_velocity(i, j, v, kind, normal)
                rho_j, p_j = _wall_state(i, j, xc, rho, p, gravity)
            u_jump = (u0 * d0 + u1 * d1 + u2 * d2) / r
            dissipation = riemann * (p[i] - p_j) / (0.5 * (rho[i] + rho_j) * c0)
            acc += mass[j] / rho[j] * (u_jump + dissipation) * pair_dw(k, r, i, j)
        drho_dt[i] = rho[i] * acc


@njit(cache=True)
def viscous_acceleration(n, start, nbr, xc, v, rho, mass, kind, normal, viscosity, k, acc):
    """acc += the viscous acceleration of 001_ Eq. 7, pair by pair."""
    dim = xc.shape[1]
    for i in range(n):
        if kind[i] != MOVING:
            continue
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            r = pair_distance(xc, i, j)
            f = 2.0 * viscosity * mass[j] / rho[j] / rho[i] * pair_dw(k, r, i, j) / (r + 0.01 * k.h)
            if kind[j] == WALL_SLIP:
                vn = wall_relative_normal(i, j, v, normal)
                for a in range(dim):
                    acc[i, a] += f * vn * normal[j, a]
            else:
                for a in range(dim):
                    acc[i, a] += f * (v[i, a] - v[j, a])


class Viscosity(ForceTerm):
    """001_ Eq. 7 from the velocities of the configuration (frozen over it)."""

    name = "viscosity"
    frozen = True

    def __init__(self, viscosity):
        self.viscosity = viscosity

    def add(self, ctx, acc):
        if self.viscosity == 0.0:
            return
        pa = ctx.particles
        viscous_acceleration(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.v, pa.rho, pa.mass, pa.kind, pa.normal,
                             self.viscosity, ctx.kernel.params, acc)


class RiemannPressure(ForceTerm):
    """The pressure acceleration with the Riemann interface pressure P* (module docstring)."""

    name = "riemann_pressure"

    def __init__(self, c0, gravity, damped):
        self.c0 = c0
        self.gravity = gravity
        self.damped = damped

    def add(self, ctx, acc):
        pa = ctx.particles
        pressure_acceleration(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.v, pa.rho, pa.p, pa.mass, pa.kind,
                              pa.normal, self.gravity, self.c0, self.damped, ctx.kernel.params, acc)


class RiemannFluid(Scheme):
    """Weakly compressible fluid with the Riemann solver (000_ Sec. 3, 001_ Sec. 2).

    Per configuration: the optional density reinitialisation (001_ Eq. 8) and
    the pressure from it; per step: the pressure from the density (the state),
    and continuity (the rate). Option ``limiter``: the pairs the limiter damps,
    ``separating`` (the module docstring says why), ``approaching`` or ``none``.
    """

    name = "riemann_fluid"
    materials = (Fluid,)
    state_fields = ("rho", "p")
    acoustic_cfl = 0.6  # 001_ Eq. 11
    options = {"limiter": "separating"}

    def __init__(self, case, kernel):
        super().__init__(case, kernel)
        self.damped = limited_pairs_sign(self)
        self.gravity = case.gravity

    @property
    def kinematic_viscosity(self):
        return self.material.viscosity / self.material.rho0

    def forces(self):
        return (Viscosity(self.material.viscosity), RiemannPressure(self.material.c0, self.gravity, self.damped))

    def configure(self, ctx):
        pa, m = ctx.particles, self.material
        if reinitialise_density(ctx, self):
            equation_of_state(pa.n_owned, pa.kind, pa.rho, pa.p, m.rho0, m.c0)
            ctx.refresh(["rho", "p"])

    def state(self, ctx):
        pa, m = ctx.particles, self.material
        equation_of_state(pa.n_owned, pa.kind, pa.rho, pa.p, m.rho0, m.c0)

    def rates(self, ctx, dt):
        pa = ctx.particles
        continuity(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.v, pa.rho, pa.p, pa.mass, pa.kind, pa.normal,
                   self.gravity, self.material.c0, 1.0, ctx.kernel.params, pa.drho_dt)
