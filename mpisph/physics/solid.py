"""Riemann-based SPH for solids: what elastic and granular materials share.

Stresses are full 3 x 3 Cauchy tensors, tension positive, also in 2D (plane
strain: the out-of-plane strain rate is zero, the out-of-plane stress is
not); they and B are stored packed (tensors.py). In mpisph's sign convention
(e_ij from j to i, grad_i W_ij = W' e_ij, W' <= 0, see kernels.py):

    velocity gradient   L_i = -sum_j V_j (v_i - v_j) (x) (B_i grad_i W_ij)     (000_ Eq. 23)
    correction matrix   B_i = (-sum_j V_j r_ij (x) grad_i W_ij)^-1              (000_ Eq. 24)
    momentum            dv_i/dt = g + 1/rho_i sum_j V_j [(s_i B_i + s_j B_j) e_ij
                                  - (2 P*_ij) e_ij] W'_ij                      (000_ Eqs. 17, 22, 25-26)

(B_i = B_j = I in the momentum for granular materials, see below)

with s = sigma + p I the deviatoric (shear) stress, p = -tr(sigma)/3, the
Riemann pressure P*_ij = (p_i + p_j)/2 - beta rho_bar c0 u_jump / 2 and
u_jump = (v_i - v_j).e_ij (> 0 for a pair moving apart): elastic solids take
beta = 1 (000_ Sec. 3.1.2), granular materials the limiter
beta = min(eta max(u_jump/c0, 0), 1) with eta = 20 d (000_ Sec. 3.1.3), which
damps pairs that move apart.

That sign is the second deliberate difference from the paper's text, and it
follows the paper's own code. Eq. 20 as printed, min{eta max[(P_L + P_R)
(U_L - U_R)/(rho_L c_L + rho_R c_R), 0], 1}, is not dimensionless, and its
text ("a compression wave, U_L >= U_R", said of fluids) would damp
approaching pairs. SPHinXsys, which the paper cites for its code, damps
separating pairs in its granular step: u_jump = (v_i - v_j).e_ij with e_ij
from j to i, in TruncatedLinear(20 d) min(eta max(u_jump, 0)/c0, 1). With
approaching pairs damped, the 2D column collapse of Sec. 5.1 (dp = 0.002)
runs out to 0.401 m without a stabiliser and 0.413 m with UTVF, beyond the
0.32-0.38 m that planar-collapse scalings give, and grains slide ahead of the
deposit. With separating pairs damped it runs out to 0.363 m and 0.375 m, at
rest, with no grains ahead (docs/VALIDATION.md).

The first deliberate difference from the paper, for elastic solids only: Eq. 22
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
from ..neighbours import pair_difference, pair_offset
from ..particles import MOVING, Field, is_wall
from ..tensors import component
from .fluid import continuity
from .walls import wall_relative_velocity

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
    """B_i of 000_ Eq. 24 (regularised, packed) for the material particles in [0, n); zero for
    walls. The inverse of a symmetric A is symmetric to the bit (its cofactors are the same
    products)."""
    dim = xc.shape[1]
    A = np.empty((dim, dim))
    inverse = np.empty((dim, dim))
    for i in range(n):
        if is_wall(kind[i]):
            B[i, :] = 0.0
            continue
        a00 = a01 = a02 = a11 = a12 = a22 = 0.0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            d0, d1, d2, r = pair_offset(xc, i, j)
            f = -mass[j] / rho[j] * dw(r, h, sigma, kernel) / r  # -V_j r_ij (x) grad W = f d (x) d
            a00 += f * d0 * d0
            a01 += f * d0 * d1
            a02 += f * d0 * d2
            a11 += f * d1 * d1
            a12 += f * d1 * d2
            a22 += f * d2 * d2
        A[0, 0], A[0, 1], A[1, 0], A[1, 1] = a00, a01, a01, a11
        if dim == 3:
            A[0, 2], A[2, 0], A[1, 2], A[2, 1], A[2, 2] = a02, a02, a12, a12, a22
        _regularised_inverse(A, inverse)
        for a in range(dim):
            for b in range(a, dim):
                B[i, component(dim, a, b)] = inverse[a, b]


@njit(cache=True)
def velocity_gradient(i, start, nbr, xc, v, mass, rho, kind, normal, B, h, sigma, kernel, L):
    """L_i of 000_ Eq. 23 of the material particle i into the 3 x 3 ``L`` (zero third row and
    column in 2D). The stress updates call it particle by particle, so that no n x 3 x 3 array
    of gradients is ever stored.

    B_i is the same for every pair of i, so the sum runs uncorrected,
    M_i = -sum_j V_j (v_i - v_j) (x) grad_i W_ij, and L_i = M_i B_i^T.
    """
    dim = xc.shape[1]
    m00 = m01 = m02 = m10 = m11 = m12 = m20 = m21 = m22 = 0.0
    for s in range(start[i], start[i + 1]):
        j = nbr[s]
        d0, d1, d2, r = pair_offset(xc, i, j)
        u0, u1, u2 = pair_difference(v, i, j)
        if is_wall(kind[j]):  # walls.py: the wall call stays off the common path
            u0, u1, u2 = wall_relative_velocity(i, j, v, kind, normal)
        f = -mass[j] / rho[j] * dw(r, h, sigma, kernel) / r
        m00 += f * u0 * d0
        m01 += f * u0 * d1
        m02 += f * u0 * d2
        m10 += f * u1 * d0
        m11 += f * u1 * d1
        m12 += f * u1 * d2
        m20 += f * u2 * d0
        m21 += f * u2 * d1
        m22 += f * u2 * d2
    M = ((m00, m01, m02), (m10, m11, m12), (m20, m21, m22))
    L[:, :] = 0.0
    for a in range(dim):
        for b in range(dim):
            acc = 0.0
            for c in range(dim):
                acc += M[a][c] * B[i, component(dim, b, c)]
            L[a, b] = acc


@njit(cache=True)
def jaumann_rate(L, sig, G, rate):
    """rate = 2 G D + sig W^T + W sig, D and W the symmetric and skew parts of the 3 x 3 L
    (000_ Eqs. 8 and 10 without their volumetric terms, which each material adds). Each term is
    formed symmetrically, so the rate of a symmetric sig is symmetric to the bit."""
    for a in range(3):
        for b in range(3):
            d_ab = 0.5 * (L[a, b] + L[b, a])
            r = 2.0 * G * d_ab
            for c in range(3):
                w_ac = 0.5 * (L[a, c] - L[c, a])
                w_bc = 0.5 * (L[b, c] - L[c, b])
                r += sig[a, c] * w_bc + w_ac * sig[c, b]
            rate[a, b] = r


@njit(cache=True)
def shear_force_tensor(n, kind, stress, p, B, T):
    """T_i = s_i B_i, the in-plane block (not symmetric), with s = sigma + p I, for the material
    particles in [0, n), ghosts included: the shear part of the corrected momentum sum (elastic
    solids)."""
    dim = T.shape[1]
    for i in range(n):
        if is_wall(kind[i]):
            continue
        for a in range(dim):
            for b in range(dim):
                acc = p[i] * B[i, component(dim, a, b)]
                for c in range(dim):
                    acc += stress[i, component(3, a, c)] * B[i, component(dim, c, b)]
                T[i, a, b] = acc


@njit  # not inlined by numba: its branch on T.ndim is pruned only in a function of its own
def _tensor_times(T, k, p, dim, d0, d1, d2):
    """T_k (d0, d1, d2) as three scalars, over the in-plane block: T is T = s B (n, dim, dim),
    or the packed stress (n, 6), from which s = sigma + p I is formed."""
    if T.ndim == 2:  # packed sigma (tensors.py order xx, yy, zz, xy, yz, xz)
        pk = p[k]
        if dim == 2:
            return (T[k, 0] + pk) * d0 + T[k, 3] * d1, T[k, 3] * d0 + (T[k, 1] + pk) * d1, 0.0
        return ((T[k, 0] + pk) * d0 + T[k, 3] * d1 + T[k, 5] * d2,
                T[k, 3] * d0 + (T[k, 1] + pk) * d1 + T[k, 4] * d2,
                T[k, 5] * d0 + T[k, 4] * d1 + (T[k, 2] + pk) * d2)
    if dim == 2:
        return T[k, 0, 0] * d0 + T[k, 0, 1] * d1, T[k, 1, 0] * d0 + T[k, 1, 1] * d1, 0.0
    return (T[k, 0, 0] * d0 + T[k, 0, 1] * d1 + T[k, 0, 2] * d2,
            T[k, 1, 0] * d0 + T[k, 1, 1] * d1 + T[k, 1, 2] * d2,
            T[k, 2, 0] * d0 + T[k, 2, 1] * d1 + T[k, 2, 2] * d2)


@njit(cache=True)
def stress_acceleration(n, start, nbr, xc, v, rho, p, T, mass, kind, normal,
                        c0, eta, h, sigma, kernel, gravity, dv_dt):
    """dv/dt of the moving particles (module docstring); eta <= 0 means beta = 1.

    The shear part takes T = s B from ``shear_force_tensor`` (corrected), or the packed
    stress itself, s = sigma + p I being formed on the fly (Eq. 25 as printed: no copy).
    T_i is the same for every pair of i and multiplies sum_j V_j e_ij W'_ij once; a wall
    partner takes the state of i.
    """
    dim = xc.shape[1]
    for i in range(n):
        if kind[i] != MOVING:
            continue
        a0 = a1 = a2 = 0.0
        g0 = g1 = g2 = 0.0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            d0, d1, d2, r = pair_offset(xc, i, j)
            u0, u1, u2 = pair_difference(v, i, j)
            k = j
            if is_wall(kind[j]):  # the wall takes the state of i; walls.py: off the common path
                u0, u1, u2 = wall_relative_velocity(i, j, v, kind, normal)
                k = i
            u_jump = (u0 * d0 + u1 * d1 + u2 * d2) / r
            beta = 1.0 if eta <= 0.0 else min(eta * max(u_jump / c0, 0.0), 1.0)
            pressure = p[i] + p[k] - beta * 0.5 * (rho[i] + rho[k]) * c0 * u_jump
            f = mass[j] / rho[j] * dw(r, h, sigma, kernel) / r
            t0, t1, t2 = _tensor_times(T, k, p, dim, d0, d1, d2)
            a0 += f * (t0 - pressure * d0)
            a1 += f * (t1 - pressure * d1)
            a2 += f * (t2 - pressure * d2)
            g0 += f * d0
            g1 += f * d1
            g2 += f * d2
        t0, t1, t2 = _tensor_times(T, i, p, dim, g0, g1, g2)
        dv_dt[i, 0] = gravity[0] + (a0 + t0) / rho[i]
        dv_dt[i, 1] = gravity[1] + (a1 + t1) / rho[i]
        if dim == 3:
            dv_dt[i, 2] = gravity[2] + (a2 + t2) / rho[i]


@njit(cache=True)
def material_pressure(n, kind, stress, p):
    """p = -tr(sigma)/3 for the material particles."""
    for i in range(n):
        if not is_wall(kind[i]):
            p[i] = -(stress[i, 0] + stress[i, 1] + stress[i, 2]) / 3.0


@njit(cache=True)
def output_invariants(n, stress, v, von_mises, speed):
    """von Mises stress sqrt(3/2 s:s) and speed |v| of the particles in [0, n), for frames."""
    dim = v.shape[1]
    for i in range(n):
        mean = (stress[i, 0] + stress[i, 1] + stress[i, 2]) / 3.0
        ss = 0.0
        for a in range(3):
            for b in range(3):
                s_ab = stress[i, component(3, a, b)] - (mean if a == b else 0.0)
                ss += s_ab * s_ab
        von_mises[i] = np.sqrt(1.5 * ss)
        vv = 0.0
        for a in range(dim):
            vv += v[i, a] * v[i, a]
        speed[i] = np.sqrt(vv)


class SolidScheme:
    """The order of the solid sub-steps; the constitutive model fills in its part.

    The model (``ElasticModel`` or ``DruckerPragerModel``) provides: its
    extra fields, ``eta`` of the momentum limiter, ``corrected_shear_force``
    (B on the shear part of the momentum sum, module docstring),
    ``riemann_continuity`` (1: Eq. 16, 0: Eq. 21), ``pressure(s)`` (p and the
    total stress from the current density or stress), ``update_stress(s,
    gradient, dt)`` (``gradient``: the arguments of ``velocity_gradient`` after
    i), and the names and values of its own energies (``observable_names``,
    ``energies(pa, n)``, if any).
    """

    needs_surface = True
    acoustic_cfl = 0.4  # 000_ Eq. 38: c0 of Eq. 6 is below the P-wave speed of a solid

    base_fields = (
        Field("drho_dt", (), np.float64, "density rate [kg/m^d/s]"),
        Field("stress", (6,), np.float64, "Cauchy stress, tension positive, packed (tensors.py) [Pa]"),
        Field("B", ("sym",), np.float64, "kernel-gradient correction matrix (000_ Eq. 24), packed"),
    )

    def __init__(self, model, gravity, u_ref):
        self.model = model
        self.m = model.material
        self.gravity = gravity
        self.u_ref = u_ref
        self.fields = self.base_fields + model.fields

    def initial_density(self, pressure):
        return self.model.initial_density(pressure)

    def speeds(self):
        """(sound speed, kinematic viscosity) for the time-step criteria."""
        return self.m.c0, 0.0

    def configure(self, s):
        """Once per advection step: correction matrices on the frozen positions (ghosts too
        when the momentum sum reads them)."""
        s.correction_matrices()  # into pa.B
        if self.model.corrected_shear_force:
            s.halo.refresh(s.particles, ["B"])

    def acoustic_step(self, s, dt):
        pa, k = s.particles, s.kernel_args
        n = pa.n_owned
        # 1. first half: positions and density to n + 1/2 (000_ Eq. 39)
        drift_half(n, pa.kind, pa.x, pa.v, pa.rho, pa.drho_dt, dt, True)
        # 2. pressure and total stress, then every field the momentum sum reads
        self.model.pressure(s)
        s.halo.refresh(pa, ["rho", "p", "stress"])
        # 3. momentum and kick (000_ Eq. 40), then the new velocities of ghosts
        if self.model.corrected_shear_force:
            T = s.workspace.get("shear_force", pa.n, (pa.dim, pa.dim))
            shear_force_tensor(pa.n, pa.kind, pa.stress, pa.p, pa.B, T)
        else:
            T = pa.stress
        dv_dt, = s.workspace.scratch(((n, pa.dim), np.float64))  # the acceleration lives until the kick
        stress_acceleration(n, s.start, s.nbr, s.xc, pa.v, pa.rho, pa.p, T, pa.mass, pa.kind, pa.normal,
                            self.m.c0, self.model.eta, *k, self.gravity, dv_dt)
        kick(n, pa.kind, pa.v, dv_dt, dt)
        s.halo.refresh(pa, ["v"])
        # 4. second half: positions (000_ Eq. 41), density rate, stress from the velocity
        #    gradient (Eq. 23, particle by particle inside the model's update), density
        drift_half(n, pa.kind, pa.x, pa.v, pa.rho, pa.drho_dt, dt, False)
        continuity(n, s.start, s.nbr, s.xc, pa.v, pa.rho, pa.p, pa.mass, pa.kind, pa.normal,
                   self.gravity, self.m.c0, self.model.riemann_continuity, *k, pa.drho_dt)
        gradient = (s.start, s.nbr, s.xc, pa.v, pa.mass, pa.rho, pa.kind, pa.normal, pa.B, *k)
        self.model.update_stress(s, gradient, dt)  # reads rho of neighbours: before density_half
        density_half(n, pa.kind, pa.rho, pa.drho_dt, dt)

    @property
    def observable_names(self):
        return tuple(self.model.observable_names)

    def observables(self, pa, n):
        """Extra sums for diagnostics.csv over the owned particles [0, n): the model's energies."""
        return self.model.energies(pa, n) if hasattr(self.model, "energies") else {}

    def derived_fields(self, pa, n):
        """Output-only fields of the owned particles: von Mises, vertical stress, speed."""
        von_mises = np.empty(n)
        speed = np.empty(n)
        output_invariants(n, pa.stress, pa.v, von_mises, speed)
        vertical = pa.dim - 1
        return {"von_mises": von_mises, "vertical_stress": pa.stress[:n, vertical].copy(), "speed": speed}
