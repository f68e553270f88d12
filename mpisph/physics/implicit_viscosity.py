"""The viscous term of the mu(I) scheme taken backward in time: a semi-implicit kick.

The regularised viscosity of 004_ reaches eta_max = tau_0 m_0 + eta_0 where the
grains rest (Eq. 53), and the viscous limit of Eq. 39, dt < 0.05 rho h^2 /
eta, then asks for steps of about 1e-6 s in Lube's columns: a million steps
per second of collapse. With ``viscous_step = implicit`` the kick solves

    v(n+1) = v(n) + dt a_other(n+1/2) + dt a_visc[v(n+1)]

for v(n+1), the viscosity, densities and positions frozen at n + 1/2 (the
state the explicit forces use), a_visc the scheme's viscous term, linear in
the velocity at a frozen viscosity:

- ``PairTerm``, the pair term of Eq. 27,
  a_visc[u]_i = sum_j m_j 2 (D + 2) eta_ij (u_ij . r_ij) grad_i W_ij / (r^2 rho_i rho_j),
  eta_ij the scheme's pair viscosity (mu_i_law.pair_viscosity), or the
  deviatoric pair term, which adds a part along u_ij (mu_i.pair_term_factors).
  On a Morris wall partner u_ij is beta (u_i - u_w) (Eqs. 34-36). On a free-slip
  wall the pair offset d is taken along the wall's normal n, as in the explicit
  form (walls.along_wall_normal): the pair force is beta (d.n)^2 (n.u) n, and
  the part along u_ij beta r^2 (n.u) n, the system stays symmetric.
- ``CorrectedStress``, the divergence of 2 eta eps B of viscous_stress.py,
  the adjoint of its gradient, walls included: an iteration takes two pair
  passes (the gradient of the search direction, then the divergence of its
  stress) and sends that stress to the ghosts.

This is backward Euler for the viscous part: first order in time for it,
stable for any dt and damping the stiffest modes (the resting grains move as a
body), so the step falls back to the acoustic limit h / c0. Multiplied by the
masses, the system m (u - dt a_visc[u]) = m b is symmetric and positive
definite (each pair, or each particle's strain, dissipates), so it is solved by
conjugate gradients with the particles' own dim x dim diagonal blocks as
preconditioner, from the first guess b + dt a, a the viscous acceleration
extrapolated linearly in time from the particle's last two kicks (fields
``viscous_acceleration`` and ``viscous_acceleration_change``; zero at the start of
a run, the last kick's alone at the second; a restart reads both from its frame):
in the 3D column (a = 0.55, the deviatoric corrected stress, m_0 = 40 s) its r.z
is about 1e-4 of the last kick's acceleration alone's, and a kick takes 14
iterations instead of 23 (docs/PERFORMANCE.md). The moving
walls' velocities enter only the first residual, from the velocities
themselves; the search directions vanish on walls, so the iterations apply the
operator alone. Its dot products are partition-independent sums
(parallel/exact_sum.py), so the iterates, the iteration count and the particles
stay bit for bit the same on any number of ranks. The iteration stops when the
preconditioned residual, as an RMS velocity sqrt(r.z / sum m), is below the
scheme's option ``viscous_tolerance`` (by default ``TOLERANCE``) times the case's
reference speed, or ``RELATIVE_TOLERANCE`` times its initial value (1e-5 leaves
the 3D column's deposit as at 1e-7 with a quarter of the iterations:
docs/PERFORMANCE.md). The run's closing lines give the iterations a kick, the
mean and the most (``summary``), and diagnostics.csv their mean since the row
before (the column ``viscous_iterations``, ``mean_since_last_row``).
"""

import math

import numpy as np
from numba import njit

from ..errors import InputError, NoConvergence
from ..kernels import pair_dw
from ..neighbours import pair_difference, pair_offset
from ..particles import MOVING, WALL_SLIP, is_wall
from ..parallel.exact_sum import global_sums
from ..tensors import IDENTITY_BLOCK, block_less_outer, block_plus_diagonal, store_scaled_inverse
from .mu_i_law import pair_viscosity
from .viscous_stress import strain_rate, stress_blocks, stress_divergence, viscous_force_tensor
from .walls import along_wall_normal, morris_beta

TOLERANCE = 1e-7  # of the reference speed, RMS over the particles
RELATIVE_TOLERANCE = 1e-8  # of the initial preconditioned residual
MAX_ITERATIONS = 2000


@njit(cache=True)
def viscous_pairs(n, start, nbr, xc, rho, eta, gamma_dot, mass, kind, normal, wall_distance, beta_max, factor,
                  radial, along, mean, k, dt, coef, inverse):
    """The viscous pair term (mu_i.momentum) as a_visc[u]_i = sum_s coef_s (radial e_s (e_s . u_ij)
    + along r_s^2 P_s u_ij) over the neighbour list, u_ij = u_i - u_j (e_s = r_ij, for a free-slip
    wall partner walls.along_wall_normal, where P_s projects on the wall's normal, the identity
    elsewhere; coef_s <= 0, beta of Eq. 36 included for wall partners), and the preconditioner:
    inverse_i, the inverse of the diagonal block m_i (I - dt d a_visc_i / d u_i) of the moving
    particles (identity elsewhere), its entries summed in scalars, not in a scratch matrix.
    Only coef is stored: the passes recompute e_s from the positions, at about the speed of
    reading three stored numbers a pair and without their 24 bytes a pair (docs/PERFORMANCE.md)."""
    dim = xc.shape[1]
    block = np.empty((dim, dim))
    adj = np.zeros((dim, dim))
    for i in range(n):
        b = IDENTITY_BLOCK
        if kind[i] == MOVING:
            for s in range(start[i], start[i + 1]):
                j = nbr[s]
                d0, d1, d2, r = pair_offset(xc, i, j)
                rho_j, eta_j, gamma_dot_j, beta = rho[j], eta[j], gamma_dot[j], 1.0
                if is_wall(kind[j]):  # off the common path: the partner takes i's state
                    rho_j, eta_j, gamma_dot_j = rho[i], eta[i], gamma_dot[i]
                    beta = morris_beta(i, j, xc, normal, wall_distance, beta_max)
                    if kind[j] == WALL_SLIP:
                        d0, d1, d2 = along_wall_normal(j, normal, d0, d1, d2)
                c = 0.0
                if eta[i] + eta_j > 0.0:
                    eta_ij = pair_viscosity(factor, eta[i], eta_j, gamma_dot[i], gamma_dot_j, mean)
                    c = mass[j] * pair_dw(k, r, i, j) / r * eta_ij / (r * r * rho[i] * rho_j) * beta
                coef[s] = c
                b = block_less_outer(b, dt * c * radial, d0, d1, d2)
                if along > 0.0:
                    c_along = dt * c * along * r * r
                    if kind[j] == WALL_SLIP:  # the wall's normal only: n n
                        n2 = normal[j, 2] if dim == 3 else 0.0
                        b = block_less_outer(b, c_along, normal[j, 0], normal[j, 1], n2)
                    else:
                        b = block_plus_diagonal(b, -c_along)
        store_scaled_inverse(b, mass[i] if kind[i] == MOVING else 1.0, block, adj, inverse[i])


@njit(cache=True)
def viscous_acceleration(n, start, nbr, xc, kind, normal, coef, radial, u, out):
    """out_i = the radial part of a_visc[u]_i of the moving particles from ``viscous_pairs``, all
    of Eq. 27's, a wall partner's u its wall velocity (zero in a search direction)."""
    dim = u.shape[1]
    for i in range(n):
        a0 = a1 = a2 = 0.0
        if kind[i] == MOVING:
            for s in range(start[i], start[i + 1]):
                j = nbr[s]
                e0, e1, e2 = pair_difference(xc, i, j)
                if kind[j] == WALL_SLIP:  # off the common path
                    e0, e1, e2 = along_wall_normal(j, normal, e0, e1, e2)
                du = (u[i, 0] - u[j, 0]) * e0 + (u[i, 1] - u[j, 1]) * e1
                if dim == 3:
                    du += (u[i, 2] - u[j, 2]) * e2
                c = coef[s] * radial * du
                a0 += c * e0
                a1 += c * e1
                a2 += c * e2
        out[i, 0] = a0
        out[i, 1] = a1
        if dim == 3:
            out[i, 2] = a2


@njit(cache=True)
def add_along_velocity(n, start, nbr, xc, kind, normal, coef, along, u, out):
    """out_i += the part of a_visc[u]_i along u_ij (the deviatoric pair term's), sum_s coef_s along
    r_s^2 P_s u_ij, on a free-slip wall P u = (n.u) n; a pass of its own, so that Eq. 27's pairs
    take ``viscous_acceleration`` alone."""
    dim = u.shape[1]
    for i in range(n):
        if kind[i] != MOVING:
            continue
        a0 = a1 = a2 = 0.0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            d0, d1, d2 = pair_difference(xc, i, j)
            w0, w1, w2 = pair_difference(u, i, j)
            if kind[j] == WALL_SLIP:  # off the common path
                w0, w1, w2 = along_wall_normal(j, normal, w0, w1, w2)
            c = coef[s] * along * (d0 * d0 + d1 * d1 + d2 * d2)
            a0 += c * w0
            a1 += c * w1
            a2 += c * w2
        out[i, 0] += a0
        out[i, 1] += a1
        if dim == 3:
            out[i, 2] += a2


@njit(inline="always")
def _precondition(i, inverse, r, z):
    """z_i = inverse_i r_i; returns r_i . z_i."""
    dim = r.shape[1]
    rz = 0.0
    for a in range(dim):
        z[i, a] = 0.0
        for b in range(dim):
            z[i, a] += inverse[i, a, b] * r[i, b]
        rz += r[i, a] * z[i, a]
    return rz


@njit(cache=True)
def first_guess(n, kind, dt, a_last, change, guess, u):
    """guess = a_last + dt change, the viscous acceleration extrapolated from the last two kicks,
    and u += dt guess on the moving particles: the first guess of the conjugate gradients."""
    for i in range(n):
        for a in range(u.shape[1]):
            guess[i, a] = 0.0
            if kind[i] == MOVING:
                guess[i, a] = a_last[i, a] + dt * change[i, a]
                u[i, a] += dt * guess[i, a]


@njit(cache=True)
def record_kick(n, kind, dt, u, b, history, a_last, change):
    """a_last = (u - b) / dt, the viscous acceleration of this kick, and change = its change from
    the last kick's over dt (0 without ``history``, the first kick of a run from t = 0)."""
    for i in range(n):
        if kind[i] != MOVING:
            continue
        for a in range(u.shape[1]):
            a_new = (u[i, a] - b[i, a]) / dt
            change[i, a] = (a_new - a_last[i, a]) / dt if history else 0.0
            a_last[i, a] = a_new


@njit(cache=True)
def residual(n, kind, mass, dt, a_visc, guess, r, inverse, z, p, terms):
    """r = m dt (a_visc[u0] - guess), the residual of the first guess u0 = b + dt guess,
    z = p = inverse r, and the terms of r . z; zero rows for particles that do not move."""
    dim = r.shape[1]
    for i in range(n):
        for a in range(dim):
            r[i, a] = mass[i] * dt * (a_visc[i, a] - guess[i, a]) if kind[i] == MOVING else 0.0
        terms[0, i] = _precondition(i, inverse, r, z)
        for a in range(dim):
            p[i, a] = z[i, a]


@njit(cache=True)
def operator(n, kind, mass, dt, p, a_visc, q, terms):
    """q = m (p - dt a_visc[p]) and the terms of p . q."""
    dim = p.shape[1]
    for i in range(n):
        terms[0, i] = 0.0
        for a in range(dim):
            q[i, a] = mass[i] * (p[i, a] - dt * a_visc[i, a]) if kind[i] == MOVING else 0.0
            terms[0, i] += p[i, a] * q[i, a]


@njit(cache=True)
def advance(n, kind, alpha, p, q, u, r, inverse, z, terms):
    """u += alpha p, r -= alpha q, z = inverse r, and the terms of r . z."""
    dim = p.shape[1]
    for i in range(n):
        terms[0, i] = 0.0
        if kind[i] != MOVING:
            continue
        for a in range(dim):
            u[i, a] += alpha * p[i, a]
            r[i, a] -= alpha * q[i, a]
        terms[0, i] = _precondition(i, inverse, r, z)


@njit(cache=True)
def new_direction(n, kind, beta, z, p):
    """p = z + beta p on the moving particles."""
    for i in range(n):
        if kind[i] == MOVING:
            for a in range(p.shape[1]):
                p[i, a] = z[i, a] + beta * p[i, a]


class PairTerm:
    """The pair term of Eq. 27 as the kick's operator (module docstring)."""

    def __init__(self, scheme):
        self.scheme = scheme
        self.coef = None

    def prepare(self, ctx, dt, inverse):
        """The pairs' coefficients on this step's state and the preconditioner's blocks."""
        pa, s = ctx.particles, self.scheme
        self.coef = ctx.workspace.get("cg_coef", len(ctx.nbr))
        viscous_pairs(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.rho, pa.eta, pa.gamma_dot, pa.mass, pa.kind,
                      pa.normal, pa.wall_distance, s.beta_max, s.viscous_factor, s.radial, s.along, s.mean,
                      ctx.kernel.params, dt, self.coef, inverse)

    def apply(self, ctx, u, out):
        """out = a_visc[u] of the owned particles, u current on the ghosts."""
        pa = ctx.particles
        s = self.scheme
        viscous_acceleration(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.kind, pa.normal, self.coef, s.radial, u, out)
        if s.along > 0.0:
            add_along_velocity(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.kind, pa.normal, self.coef, s.along, u, out)


class CorrectedStress:
    """The divergence of the corrected viscous stress as the kick's operator (module docstring):
    its stress of u is the particle field ``viscous_direction_stress``, sent to the ghosts."""

    def __init__(self, scheme):
        self.scheme = scheme

    def prepare(self, ctx, dt, inverse):
        """The preconditioner's blocks, from the neighbours' eta (a state field) and B (the field
        ``B``, computed for this configuration if it was not yet and sent here)."""
        pa = ctx.particles
        ctx.correction_matrices()
        ctx.refresh(["B"])
        stress_blocks(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.rho, pa.eta, pa.B, pa.mass, pa.kind,
                      ctx.kernel.params, self.scheme.deviatoric_stress, dt, inverse)

    def apply(self, ctx, u, out):
        """out = a_visc[u] of the owned particles, u current on the ghosts."""
        pa, s, ws = ctx.particles, self.scheme, ctx.workspace
        n, k = pa.n_owned, ctx.kernel.params
        strain, gamma_dot = ws.get("cg_strain", n, (pa.B.shape[1],)), ws.get("cg_gamma_dot", n)
        T = pa.viscous_direction_stress
        strain_rate(n, ctx.start, ctx.nbr, ctx.xc, u, pa.rho, pa.mass, pa.kind, pa.normal, pa.wall_distance,
                    s.beta_max, pa.B, k, strain, gamma_dot)
        viscous_force_tensor(n, pa.kind, strain, pa.eta, pa.B, s.deviatoric_stress, T)
        ctx.refresh(["viscous_direction_stress"])
        out[:] = 0.0
        stress_divergence(n, ctx.start, ctx.nbr, ctx.xc, pa.rho, T, pa.mass, pa.kind, pa.normal, k, out)


class ImplicitViscosity:
    """The backward-Euler viscous kick (module docstring) of a mu_i scheme ``scheme``; its search
    direction is the particle field ``viscous_direction``, sent to ghosts every iteration."""

    def __init__(self, scheme, u_ref, tolerance=TOLERANCE):
        if not u_ref > 0:
            raise InputError("scheme mu_i: viscous_step = implicit needs the case's reference speed u_ref")
        if not 0.0 < tolerance < 1.0:
            raise InputError(f"scheme mu_i: viscous_tolerance must lie between 0 and 1, not {tolerance!r}")
        self.tolerance = tolerance
        self.operator = CorrectedStress(scheme) if scheme.corrected else PairTerm(scheme)
        self.u_ref = u_ref
        self.total_mass = None
        self.iterations = 0  # the last kick's
        self.kicks = self.total_iterations = self.most_iterations = 0  # since the run's (re)start
        self.row_kicks = self.row_iterations = 0  # kicks and iterations at the last row of diagnostics.csv
        self.history = True  # the fields hold a last kick (a restart's frame); MuIScheme.start clears it

    def summary(self):
        """A closing line of the run: the kicks' conjugate-gradient iterations, the same on every rank."""
        mean = self.total_iterations / self.kicks if self.kicks else 0.0
        return (f"mu(I): the implicit viscous kick took {mean:.1f} conjugate-gradient iterations a step on "
                f"average, {self.most_iterations} at most ({self.kicks} steps)")

    def mean_since_last_row(self):
        """The column viscous_iterations of diagnostics.csv: the kicks' mean conjugate-gradient
        iterations since the last row (0 where no kick came between), the same on every rank."""
        kicks, iterations = self.kicks - self.row_kicks, self.total_iterations - self.row_iterations
        self.row_kicks, self.row_iterations = self.kicks, self.total_iterations
        return iterations / kicks if kicks else 0.0

    def kick(self, ctx, dt):
        """Replace the explicitly kicked velocities b of the owned moving particles (``v``, sent to
        the ghosts already) by the solution u of m (u - dt a_visc[u]) = m b + dt (wall terms)."""
        pa, ws, op = ctx.particles, ctx.workspace, self.operator
        n, dim, comm = pa.n_owned, pa.dim, ctx.halo.comm
        a_visc, r, z, q = (ws.get(name, n, (dim,)) for name in ("cg_a", "cg_r", "cg_z", "cg_q"))
        inverse = ws.get("cg_inverse", n, (dim, dim))
        terms = ws.get("cg_terms", n)[None, :]
        p = pa.viscous_direction
        if self.total_mass is None:
            moving = (pa.kind[:n] == MOVING)[None, :]
            self.total_mass = global_sums(comm, np.where(moving, pa.mass[:n][None, :], 0.0))[0]
        op.prepare(ctx, dt, inverse)
        b = ws.get("cg_b", n, (dim,))
        b[:] = pa.v[:n]
        a_last, change = pa.viscous_acceleration, pa.viscous_acceleration_change
        guess = ws.get("cg_guess", n, (dim,))
        first_guess(n, pa.kind, dt, a_last, change, guess, pa.v)
        ctx.refresh(["v"])
        op.apply(ctx, pa.v, a_visc)
        residual(n, pa.kind, pa.mass, dt, a_visc, guess, r, inverse, z, p, terms)
        rz = rz0 = global_sums(comm, terms)[0]
        floor = max(RELATIVE_TOLERANCE**2 * rz0, (self.tolerance * self.u_ref) ** 2 * self.total_mass)
        for iteration in range(MAX_ITERATIONS + 1):
            if rz <= floor:
                self.iterations = iteration
                self.kicks += 1
                self.total_iterations += iteration
                self.most_iterations = max(self.most_iterations, iteration)
                record_kick(n, pa.kind, dt, pa.v, b, self.history, a_last, change)
                self.history = True
                return
            ctx.refresh(["viscous_direction"])
            op.apply(ctx, p, a_visc)
            operator(n, pa.kind, pa.mass, dt, p, a_visc, q, terms)
            alpha = rz / global_sums(comm, terms)[0]
            advance(n, pa.kind, alpha, p, q, pa.v, r, inverse, z, terms)
            rz_new = global_sums(comm, terms)[0]
            new_direction(n, pa.kind, rz_new / rz, z, p)
            rz = rz_new
        raise NoConvergence(f"the implicit viscous kick did not converge in {MAX_ITERATIONS} conjugate-gradient "
                            f"iterations (RMS residual {math.sqrt(rz / self.total_mass):.3g} m/s)")
