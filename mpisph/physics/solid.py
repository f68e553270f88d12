"""Riemann-based SPH for solids: what elastic and granular materials share.

Stresses are full 3 x 3 Cauchy tensors, tension positive, also in 2D (plane
strain: the out-of-plane strain rate is zero, the out-of-plane stress is
not). In mpisph's sign convention (e_ij from j to i, grad_i W_ij = W' e_ij,
W' <= 0, see kernels.py):

    velocity gradient   L_i = -sum_j V_j (v_i - v_j) (x) (B_i grad_i W_ij)     (000_ Eq. 23)
    correction matrix   B_i = (-sum_j V_j r_ij (x) grad_i W_ij)^-1              (000_ Eq. 24)
    momentum            dv_i/dt = g + 1/rho_i sum_j V_j [(s_i B_i + s_j B_j) e_ij
                                  - (2 P*_ij) e_ij] W'_ij                      (000_ Eqs. 17, 22, 25-26)

(B_i = B_j = I in the momentum for granular materials, see below)

with s = sigma + p I the deviatoric (shear) stress, p = -tr(sigma)/3, the
Riemann pressure P*_ij = (p_i + p_j)/2 - beta rho_bar c0 u_jump / 2 and
u_jump = (v_i - v_j).e_ij: elastic solids take beta = 1 (000_ Sec. 3.1.2),
granular materials the limiter beta = min(eta max(-u_jump/c0, 0), 1) with
eta = 20 d (000_ Sec. 3.1.3).

One deliberate difference from the paper, for elastic solids only: Eq. 22
sums (s_i + s_j) grad W without B. The shear stress is integrated from the
corrected gradient of Eq. 23, so that force does less work than the stress
stores wherever B is not the identity (at free surfaces, where bending
stresses peak): the oscillating beam then gains about 12% of spurious strain
energy per quarter period. With B_i on the shear part the pair sum is the
exact adjoint of Eq. 23, sum_i m_i v_i . dv_i/dt = -sum_i V_i s_i : L_i
(tests/test_solid_kernels.py), so kinetic plus strain energy
is conserved by the spatial discretisation (linear momentum still is: the
pair force is antisymmetric). The pressure part stays uncorrected, the
adjoint of continuity (Eqs. 16, 21). Granular materials keep Eq. 25 as
printed: plastic flow dissipates what the mismatch would add, and with B the
cohesive cut (Sec. 5.2, dp = L/100) clusters at the toe of the sliding wedge
(0.9% of the particles closer than dp/2 at 2 s against 0.04% without).

The inverse in B is regularised where the neighbourhood is degenerate
(a free corner, a splashed particle): with A = -sum_j V_j r_ij (x) grad W,
B = (adj A + w I) / (det A + w), w = max(0, a_min - det A), which is A^-1
wherever det A >= a_min = 0.2^d and blends towards the identity below.

A wall particle takes the stress and density of the material particle it
interacts with and the mirrored velocity of walls.py (000_ Sec. 5: no-slip
walls after Bui et al. 2008).

The order of the sub-steps of one acoustic step (position-based Verlet,
000_ Eqs. 39-41) is spelled out in ``SolidScheme.acoustic_step``.
"""

import numpy as np
from numba import njit

from ..integrators import density_half, drift_half, kick
from ..kernels import dw
from ..neighbours import unit_offset
from ..particles import MOVING, Field, is_wall
from .fluid import continuity, prior_acceleration
from .walls import relative_velocity, velocity_jump

DEGENERATE_DET = 0.2  # a_min = DEGENERATE_DET ** d


@njit(cache=True)
def _regularised_inverse(A, out):
    """out = (adj A + w I) / (det A + w) for a symmetric 2 x 2 or 3 x 3 A."""
    dim = A.shape[0]
    if dim == 2:
        det = A[0, 0] * A[1, 1] - A[0, 1] * A[1, 0]
        out[0, 0] = A[1, 1]
        out[0, 1] = -A[0, 1]
        out[1, 0] = -A[1, 0]
        out[1, 1] = A[0, 0]
    else:
        for a in range(3):
            a1, a2 = (a + 1) % 3, (a + 2) % 3
            for b in range(3):
                b1, b2 = (b + 1) % 3, (b + 2) % 3
                out[b, a] = A[a1, b1] * A[a2, b2] - A[a1, b2] * A[a2, b1]
        det = A[0, 0] * out[0, 0] + A[0, 1] * out[1, 0] + A[0, 2] * out[2, 0]
    w = max(0.0, DEGENERATE_DET ** dim - det)
    for a in range(dim):
        out[a, a] += w
    for a in range(dim):
        for b in range(dim):
            out[a, b] /= det + w


@njit(cache=True)
def correction_matrix(n, start, nbr, xc, mass, rho, kind, h, sigma, kernel, B):
    """B_i of 000_ Eq. 24 (regularised) for the material particles in [0, n)."""
    dim = xc.shape[1]
    e = np.empty(dim)
    A = np.empty((dim, dim))
    for i in range(n):
        if is_wall(kind[i]):
            continue
        A[:, :] = 0.0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            r = unit_offset(xc, i, j, e)
            f = -mass[j] / rho[j] * r * dw(r, h, sigma, kernel)
            for a in range(dim):
                for b in range(dim):
                    A[a, b] += f * e[a] * e[b]
        _regularised_inverse(A, B[i])


@njit(cache=True)
def velocity_gradient(n, start, nbr, xc, v, mass, rho, kind, normal, B, h, sigma, kernel, L):
    """L_i of 000_ Eq. 23 as a 3 x 3 tensor (zero third row and column in 2D)."""
    dim = xc.shape[1]
    e = np.empty(dim)
    dv = np.empty(dim)
    g = np.empty(dim)
    for i in range(n):
        if is_wall(kind[i]):
            continue
        L[i, :, :] = 0.0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            r = unit_offset(xc, i, j, e)
            f = mass[j] / rho[j] * dw(r, h, sigma, kernel)
            relative_velocity(i, j, v, kind, normal, dim, dv)
            for a in range(dim):
                acc = 0.0
                for b in range(dim):
                    acc += B[i, a, b] * e[b]
                g[a] = f * acc
            for a in range(dim):
                for b in range(dim):
                    L[i, a, b] -= dv[a] * g[b]


@njit(cache=True)
def stress_acceleration(n, start, nbr, xc, v, rho, p, stress, B, corrected, mass, kind, normal,
                        c0, eta, h, sigma, kernel, prior, dv_dt):
    """dv/dt of the moving particles (module docstring); eta <= 0 means beta = 1; ``corrected``:
    the shear part carries B, else B = I (Eq. 22 as printed)."""
    dim = xc.shape[1]
    e = np.empty(dim)
    dv = np.empty(dim)
    be_i = np.empty(dim)
    be_k = np.empty(dim)
    for i in range(n):
        if kind[i] != MOVING:
            continue
        for a in range(dim):
            dv_dt[i, a] = prior[i, a]
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            r = unit_offset(xc, i, j, e)
            wall = is_wall(kind[j])
            k = i if wall else j
            u_jump = velocity_jump(i, j, v, kind, normal, e, dim, dv)
            beta = 1.0 if eta <= 0.0 else min(eta * max(-u_jump / c0, 0.0), 1.0)
            pressure = p[i] + p[k] - beta * 0.5 * (rho[i] + rho[k]) * c0 * u_jump
            for a in range(dim):
                if not corrected:
                    be_i[a] = be_k[a] = e[a]
                    continue
                be_i[a] = 0.0
                be_k[a] = 0.0
                for b in range(dim):
                    be_i[a] += B[i, a, b] * e[b]
                    be_k[a] += B[k, a, b] * e[b]
            f = mass[j] / rho[j] * dw(r, h, sigma, kernel) / rho[i]
            for a in range(dim):
                acc = -pressure * e[a]
                for b in range(dim):
                    acc += (stress[i, a, b] * be_i[b] + stress[k, a, b] * be_k[b])
                    if a == b:
                        acc += p[i] * be_i[b] + p[k] * be_k[b]
                dv_dt[i, a] += f * acc


@njit(cache=True)
def material_pressure(n, kind, stress, p):
    """p = -tr(sigma)/3 for the material particles."""
    for i in range(n):
        if not is_wall(kind[i]):
            p[i] = -(stress[i, 0, 0] + stress[i, 1, 1] + stress[i, 2, 2]) / 3.0


class SolidScheme:
    """The order of the solid sub-steps; the constitutive model fills in its part.

    The model (``ElasticModel`` or ``DruckerPragerModel``) provides: its
    extra fields, ``eta`` of the momentum limiter, ``corrected_shear_force``
    (B on the shear part of the momentum sum, module docstring),
    ``riemann_continuity`` (1: Eq. 16, 0: Eq. 21), ``pressure(s)`` (p and the total stress from the
    current density or stress), ``update_stress(s, L, dt)``, and the names and
    values of its own energies (``observable_names``, ``energies(pa, n)``, if any).
    """

    needs_surface = True
    acoustic_cfl = 0.4  # 000_ Eq. 38: c0 of Eq. 6 is below the P-wave speed of a solid

    base_fields = (
        Field("drho_dt", (), np.float64, "density rate [kg/m^d/s]"),
        Field("dv_dt", ("dim",), np.float64, "acceleration [m/s^2]"),
        Field("prior", ("dim",), np.float64, "gravity [m/s^2]"),
        Field("stress", (3, 3), np.float64, "Cauchy stress, tension positive [Pa]"),
        Field("B", ("dim", "dim"), np.float64, "kernel-gradient correction matrix (000_ Eq. 24)"),
    )

    def __init__(self, model, gravity, u_ref):
        self.model = model
        self.m = model.material
        self.gravity = gravity
        self.u_ref = u_ref
        self.fields = self.base_fields + model.fields
        self.L = None

    def initial_density(self, pressure):
        return self.model.initial_density(pressure)

    def speeds(self):
        """(sound speed, kinematic viscosity) for the time-step criteria."""
        return self.m.c0, 0.0

    def configure(self, s):
        """Once per advection step: correction matrices on the frozen positions (ghosts too:
        the momentum sum reads them), gravity."""
        pa, k = s.particles, s.kernel_args
        n = pa.n_owned
        pa.B[:n] = s.correction_matrices()
        if self.model.corrected_shear_force:
            s.halo.refresh(pa, ["B"])
        self.L = np.zeros((n, 3, 3))
        prior_acceleration(n, s.start, s.nbr, s.xc, pa.v, pa.rho, pa.mass, pa.kind, pa.normal,
                           self.gravity, 0.0, *k, pa.prior)

    def acoustic_step(self, s, dt):
        pa, k = s.particles, s.kernel_args
        n = pa.n_owned
        # 1. first half: positions and density to n + 1/2 (000_ Eq. 39)
        drift_half(n, pa.kind, pa.x, pa.v, pa.rho, pa.drho_dt, dt, True)
        # 2. pressure and total stress, then every field the momentum sum reads
        self.model.pressure(s)
        s.halo.refresh(pa, ["rho", "p", "stress"])
        # 3. momentum and kick (000_ Eq. 40), then the new velocities of ghosts
        stress_acceleration(n, s.start, s.nbr, s.xc, pa.v, pa.rho, pa.p, pa.stress, pa.B,
                            self.model.corrected_shear_force, pa.mass, pa.kind, pa.normal, self.m.c0,
                            self.model.eta, *k, pa.prior, pa.dv_dt)
        kick(n, pa.kind, pa.v, pa.dv_dt, dt)
        s.halo.refresh(pa, ["v"])
        # 4. second half: positions (000_ Eq. 41), velocity gradient, density, stress
        drift_half(n, pa.kind, pa.x, pa.v, pa.rho, pa.drho_dt, dt, False)
        velocity_gradient(n, s.start, s.nbr, s.xc, pa.v, pa.mass, pa.rho, pa.kind, pa.normal,
                          pa.B, *k, self.L)
        continuity(n, s.start, s.nbr, s.xc, pa.v, pa.rho, pa.p, pa.mass, pa.kind, pa.normal,
                   self.gravity, self.m.c0, self.model.riemann_continuity, *k, pa.drho_dt)
        self.model.update_stress(s, self.L, dt)  # reads rho of neighbours: before density_half
        density_half(n, pa.kind, pa.rho, pa.drho_dt, dt)

    @property
    def observable_names(self):
        return tuple(self.model.observable_names) + ("potential_energy",)

    def observables(self, pa, n):
        """Extra sums for diagnostics.csv over the owned particles [0, n): the model's energies
        and the potential energy -sum m g.x of the moving particles."""
        moving = pa.kind[:n] == MOVING
        out = self.model.energies(pa, n) if hasattr(self.model, "energies") else {}
        out["potential_energy"] = float(-np.sum(pa.mass[:n][moving] * (pa.x[:n][moving] @ self.gravity)))
        return out

    def derived_fields(self, pa, n):
        """Output-only fields of the owned particles: von Mises, vertical stress, speed."""
        sig = pa.stress[:n]
        dev = sig - np.trace(sig, axis1=1, axis2=2)[:, None, None] / 3.0 * np.eye(3)
        vertical = pa.dim - 1
        return {
            "von_mises": np.sqrt(1.5 * np.sum(dev * dev, axis=(1, 2))),
            "vertical_stress": sig[:, vertical, vertical].copy(),
            "speed": np.linalg.norm(pa.v[:n], axis=1),
        }
