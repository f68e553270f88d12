"""The numba updates of explicit integrators: half drifts, density half steps, the kick, and a
field advanced by its rate.

Moving particles drift and are kicked; clamped particles (held in place)
evolve their density like moving ones; wall particles never change.
"""

from numba import njit

from ..particles import MOVING, is_wall


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
    """Largest |v| over the moving particles in [0, n) (time_step.py)."""
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


@njit(cache=True)
def advance(n, kind, f, f0, rate, dt, moving_only):
    """f = f0 + dt rate, row by row (2D arrays), for the moving particles, and the clamped ones
    unless ``moving_only`` (positions and velocities move only with moving particles; densities
    and stresses evolve on clamped ones too)."""
    for i in range(n):
        if is_wall(kind[i]) or (moving_only and kind[i] != MOVING):
            continue
        for c in range(f.shape[1]):
            f[i, c] = f0[i, c] + dt * rate[i, c]


def rows(a, n):
    """The first n rows of a particle field as a 2D array (a column for a scalar field)."""
    return a[:n].reshape(n, -1)


def advance_integrated(ctx, scheme, dt):
    """The scheme's ``integrated_fields`` of the owned particles advanced by dt from their
    rates, then the scheme's constraint on them."""
    if not scheme.integrated_fields:
        return
    pa = ctx.particles
    n = pa.n_owned
    for name, rate in scheme.integrated_fields.items():
        f = rows(getattr(pa, name), n)
        advance(n, pa.kind, f, f, rows(getattr(pa, rate), n), dt, False)
    scheme.constrain(ctx)
