"""Position-based Verlet (000_ Eqs. 39-41) and the time-step criteria.

One acoustic step of length dt:

    first half   rho += dt/2 drho/dt ; x += dt/2 v          (Eq. 39)
    kick         v += dt dv/dt                              (Eq. 40)
    second half  x += dt/2 v ; rho += dt/2 drho/dt           (Eq. 41)

where the density rate of the second half is evaluated with the new
velocity and reused in the first half of the next step.

Dual-criteria time stepping (001_ Eqs. 9-11): the neighbour configuration is
rebuilt once per advection step dt_ad = 0.25 h / |v|_ad, with
|v|_ad = max(|v|max, nu/h, U_ref), and the pressure/density field is advanced
in acoustic steps dt_ac = 0.6 h / (c + |v|max) within it. With a single
criterion the configuration is rebuilt every step of
dt = 0.4 h / (c + |v|max) (000_ Eq. 38).
"""

from numba import njit

from .particles import MOVING, is_wall

CFL_ADVECTION = 0.25
CFL_SINGLE = 0.4


@njit(cache=True)
def drift_half(n, kind, x, v, rho, drho_dt, dt, with_density):
    """x += dt/2 v (moving particles) and, if ``with_density``, rho += dt/2 drho/dt
    (moving and clamped particles)."""
    dim = x.shape[1]
    half = 0.5 * dt
    for i in range(n):
        if is_wall(kind[i]):
            continue
        if kind[i] == MOVING:
            for a in range(dim):
                x[i, a] += half * v[i, a]
        if with_density:
            rho[i] += half * drho_dt[i]


@njit(cache=True)
def density_half(n, kind, rho, drho_dt, dt):
    """rho += dt/2 drho/dt for the moving and clamped particles."""
    half = 0.5 * dt
    for i in range(n):
        if not is_wall(kind[i]):
            rho[i] += half * drho_dt[i]


@njit(cache=True)
def kick(n, kind, v, dv_dt, dt):
    """v += dt dv/dt for the moving particles (000_ Eq. 40)."""
    dim = v.shape[1]
    for i in range(n):
        if kind[i] != MOVING:
            continue
        for a in range(dim):
            v[i, a] += dt * dv_dt[i, a]


@njit(cache=True)
def max_speed(n, kind, v):
    """Largest |v| over the moving particles in [0, n)."""
    dim = v.shape[1]
    best = 0.0
    for i in range(n):
        if kind[i] != MOVING:
            continue
        s = 0.0
        for a in range(dim):
            s += v[i, a] * v[i, a]
        if s > best:
            best = s
    return best ** 0.5


def advection_dt(h, vmax, nu, u_ref):
    """001_ Eqs. 9-10."""
    return CFL_ADVECTION * h / max(vmax, nu / h, u_ref)


def acoustic_dt(h, vmax, c0, cfl):
    """001_ Eq. 11 (fluids, cfl 0.6) or 000_ Eq. 38 (solids and single stepping, cfl 0.4)."""
    return cfl * h / (c0 + vmax)
