"""Weakly compressible fluid with the linearised Riemann solver.

Equation of state p = c0^2 (rho - rho0) (000_ Eq. 3). Pairwise interface
states from the linearised Riemann solver with dissipation limiter
(001_ Eqs. 4-6; the acoustic form of 000_ Eqs. 18-20 when rho_L c_L equals
rho_R c_R):

    U*  = (U_l + U_r)/2 + (p_l - p_r) / (2 rho_bar c)
    P*  = (p_l + p_r)/2 + beta rho_bar c (U_l - U_r) / 2
    beta = min(eta max((U_l - U_r)/c, 0), 1),   eta = 3

In mpisph's sign convention (e_ij from j to i, see kernels.py) the
compression speed U_l - U_r equals -u_jump with u_jump = (v_i - v_j).e_ij.
Continuity (000_ Eq. 16 / 001_ Eq. 3) and pressure acceleration
(000_ Eq. 17) then read

    drho_i/dt = rho_i sum_j V_j [u_jump + (p_i - p_j)/(rho_bar c)] W'_ij
    dv_i/dt   = -2/rho_i sum_j V_j P* W'_ij e_ij

and the viscous acceleration is 001_ Eq. 7,
2/rho_i sum_j V_j mu v_ij / (r_ij + 0.01 h) W'_ij.

Walls are fixed dummy particles. A wall neighbour j takes the fluid
particle's density, a pressure extrapolated hydrostatically,
p_i + rho_i max(0, -g.r_ij), and a mirrored velocity 2 v_w - v_i (no-slip,
kind WALL) or one with only the normal component mirrored (free-slip, kind
WALL_SLIP). The viscous term uses v_i - v_w (no-slip) or its normal part
(free-slip).
"""

import numpy as np
from numba import njit

from ..integrators import density_half, drift_half, kick
from ..kernels import dw, w
from ..neighbours import pair_difference, pair_distance, pair_offset
from ..particles import MOVING, WALL_SLIP, Field, is_wall
from .walls import wall_relative_normal, wall_relative_velocity

RIEMANN_ETA = 3.0


@njit(cache=True)
def equation_of_state(n, kind, rho, p, rho0, c0):
    """p = c0^2 (rho - rho0) for the moving particles in [0, n) (000_ Eq. 3)."""
    for i in range(n):
        if kind[i] == MOVING:
            p[i] = c0 * c0 * (rho[i] - rho0)


@njit(cache=True)
def _wall_state(i, j, xc, rho, p, gravity):
    """(rho_j, p_j) as particle i sees wall particle j: the density of i and the pressure of i
    extrapolated hydrostatically, p_i + rho_i max(0, -g.r_ij)."""
    gr = 0.0
    for a in range(xc.shape[1]):
        gr -= gravity[a] * (xc[i, a] - xc[j, a])
    return rho[i], p[i] + rho[i] * max(0.0, gr)


@njit(cache=True)
def pressure_acceleration(n, start, nbr, xc, v, rho, p, mass, kind, normal, gravity,
                          c0, h, sigma, kernel, prior, dv_dt):
    """dv/dt = prior - 2/rho_i sum_j V_j P* W'_ij e_ij (000_ Eq. 17, 001_ Eqs. 5-6)."""
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
            if is_wall(kind[j]):  # walls.py: the wall call stays off the common path
                u0, u1, u2 = wall_relative_velocity(i, j, v, kind, normal)
                rho_j, p_j = _wall_state(i, j, xc, rho, p, gravity)
            u_jump = (u0 * d0 + u1 * d1 + u2 * d2) / r
            beta = min(RIEMANN_ETA * max(-u_jump / c0, 0.0), 1.0)
            p_star = 0.5 * (p[i] + p_j) - 0.25 * beta * (rho[i] + rho_j) * c0 * u_jump
            f = -2.0 * mass[j] / rho[j] * p_star * dw(r, h, sigma, kernel) / r
            a0 += f * d0
            a1 += f * d1
            a2 += f * d2
        dv_dt[i, 0] = prior[i, 0] + a0 / rho[i]
        dv_dt[i, 1] = prior[i, 1] + a1 / rho[i]
        if dim == 3:
            dv_dt[i, 2] = prior[i, 2] + a2 / rho[i]


@njit(cache=True)
def continuity(n, start, nbr, xc, v, rho, p, mass, kind, normal, gravity,
               c0, riemann, h, sigma, kernel, drho_dt):
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
            if is_wall(kind[j]):  # walls.py: the wall call stays off the common path
                u0, u1, u2 = wall_relative_velocity(i, j, v, kind, normal)
                rho_j, p_j = _wall_state(i, j, xc, rho, p, gravity)
            u_jump = (u0 * d0 + u1 * d1 + u2 * d2) / r
            dissipation = riemann * (p[i] - p_j) / (0.5 * (rho[i] + rho_j) * c0)
            acc += mass[j] / rho[j] * (u_jump + dissipation) * dw(r, h, sigma, kernel)
        drho_dt[i] = rho[i] * acc


@njit(cache=True)
def prior_acceleration(n, start, nbr, xc, v, rho, mass, kind, normal, gravity,
                       viscosity, h, sigma, kernel, prior):
    """Gravity plus the viscous acceleration of 001_ Eq. 7, once per advection step."""
    dim = xc.shape[1]
    for i in range(n):
        if kind[i] != MOVING:
            continue
        for a in range(dim):
            prior[i, a] = gravity[a]
        if viscosity == 0.0:
            continue
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            r = pair_distance(xc, i, j)
            f = 2.0 * viscosity * mass[j] / rho[j] / rho[i] * dw(r, h, sigma, kernel) / (r + 0.01 * h)
            if kind[j] == WALL_SLIP:
                vn = wall_relative_normal(i, j, v, normal)
                for a in range(dim):
                    prior[i, a] += f * vn * normal[j, a]
            else:
                for a in range(dim):
                    prior[i, a] += f * (v[i, a] - v[j, a])


@njit(cache=True)
def density_summation(n, start, nbr, xc, kind, mass, rho, rho0, h, sigma, kernel, lattice_sum, free_surface):
    """Density reinitialisation by kernel summation (001_ Eq. 8).

    rho_i = sum_j m_j W_ij / (V0 sum_j W_ij^0), self term included, with V0 =
    dp^d and sum W^0 the sum over a full lattice (``lattice_sum`` is their
    product). With equal masses m = rho0 V0 this is Eq. 8, rho0 sum W / sum W^0;
    weighting by mass keeps an initial pressure field (masses set from it).
    With ``free_surface`` the summed density only replaces the evolved one
    where it is larger; below it the evolved excess is kept in proportion,
    rho = rho_sum + max(0, rho* - rho_sum) rho0 / rho*, so that particles
    with a truncated kernel near a free surface are not dragged below rho0.
    """
    for i in range(n):
        if kind[i] != MOVING:
            continue
        acc = mass[i] * w(0.0, h, sigma, kernel)
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            acc += mass[j] * w(pair_distance(xc, i, j), h, sigma, kernel)
        rho_sum = acc / lattice_sum
        if free_surface:
            rho[i] = rho_sum + max(0.0, rho[i] - rho_sum) * rho0 / rho[i]
        else:
            rho[i] = rho_sum


def lattice_kernel_sum(dim, dp, h, sigma, kernel):
    """V0 sum_j W_ij (self included) over a full square/cubic lattice of spacing dp, V0 = dp^d."""
    m = int(np.ceil(2.0 * h / dp)) + 1
    axis = np.arange(-m, m + 1) * dp
    grids = np.meshgrid(*([axis] * dim), indexing="ij")
    r = np.sqrt(sum(g.ravel() ** 2 for g in grids))
    return dp**dim * float(sum(w(ri, h, sigma, kernel) for ri in r))


class FluidScheme:
    """The order of the fluid sub-steps; kernels above do the work.

    Per advection step: optional density reinitialisation, then gravity and
    viscosity as a prior acceleration. Per acoustic step (000_ Eqs. 39-41):
    half drift with density, pressure from the EOS, ghost refresh of rho and
    p, pressure acceleration and kick, ghost refresh of v, half drift, and
    the density rate for the next half step.
    """

    acoustic_cfl = 0.6  # 001_ Eq. 11

    fields = (
        Field("drho_dt", (), np.float64, "density rate [kg/m^d/s]"),
        Field("prior", ("dim",), np.float64, "gravity + viscous acceleration [m/s^2]"),
    )

    def __init__(self, material, gravity, density_reinit, u_ref, lattice_sum):
        self.m = material
        self.gravity = gravity
        self.density_reinit = density_reinit
        self.u_ref = u_ref
        self.lattice_sum = lattice_sum

    def initial_density(self, pressure):
        """Density that gives ``pressure`` through the EOS."""
        return self.m.rho0 + pressure / self.m.c0**2

    def speeds(self):
        """(sound speed, kinematic viscosity) for the time-step criteria."""
        return self.m.c0, self.m.viscosity / self.m.rho0

    def configure(self, s):
        """Once per advection step, after the neighbour lists are built."""
        pa, k = s.particles, s.kernel_args
        n = pa.n_owned
        if self.density_reinit != "none":
            density_summation(n, s.start, s.nbr, s.xc, pa.kind, pa.mass, pa.rho, self.m.rho0, *k,
                              self.lattice_sum, self.density_reinit == "free_surface")
            equation_of_state(n, pa.kind, pa.rho, pa.p, self.m.rho0, self.m.c0)
            s.halo.refresh(pa, ["rho", "p"])
        prior_acceleration(n, s.start, s.nbr, s.xc, pa.v, pa.rho, pa.mass, pa.kind, pa.normal,
                           self.gravity, self.m.viscosity, *k, pa.prior)

    def acoustic_step(self, s, dt):
        pa, k = s.particles, s.kernel_args
        n = pa.n_owned
        drift_half(n, pa.kind, pa.x, pa.v, pa.rho, pa.drho_dt, dt, True)
        equation_of_state(n, pa.kind, pa.rho, pa.p, self.m.rho0, self.m.c0)
        s.halo.refresh(pa, ["rho", "p"])
        dv_dt, = s.workspace.scratch(((n, pa.dim), np.float64))  # the acceleration lives until the kick
        pressure_acceleration(n, s.start, s.nbr, s.xc, pa.v, pa.rho, pa.p, pa.mass, pa.kind,
                              pa.normal, self.gravity, self.m.c0, *k, pa.prior, dv_dt)
        kick(n, pa.kind, pa.v, dv_dt, dt)
        s.halo.refresh(pa, ["v"])
        drift_half(n, pa.kind, pa.x, pa.v, pa.rho, pa.drho_dt, dt, False)
        continuity(n, s.start, s.nbr, s.xc, pa.v, pa.rho, pa.p, pa.mass, pa.kind, pa.normal,
                   self.gravity, self.m.c0, 1.0, *k, pa.drho_dt)
        density_half(n, pa.kind, pa.rho, pa.drho_dt, dt)
