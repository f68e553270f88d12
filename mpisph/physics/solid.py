"""Riemann-based SPH for solids: what elastic and granular materials share.

Stresses are full 3 x 3 Cauchy tensors, tension positive, also in 2D (plane
strain: the out-of-plane strain rate is zero, the out-of-plane stress is
not); they and B are stored packed (tensors.py). With 000_'s convention (its
Sec. 3.1.1: e_ij from j to i, grad_i W_ij = W' e_ij, W' <= 0; kernels.py):

    velocity gradient   L_i = -sum_j V_j (v_i - v_j) (x) (B_i grad_i W_ij)     (000_ Eq. 23)
    correction matrix   B_i = (-sum_j V_j r_ij (x) grad_i W_ij)^-1              (000_ Eq. 24)
    momentum            dv_i/dt = g + 1/rho_i sum_j V_j [(s_i B_i + s_j B_j) e_ij
                                  - (2 P*_ij) e_ij] W'_ij                      (000_ Eqs. 17, 22, 25-26)

(B_i = B_j = I in the momentum for granular materials, see below)

Eq. 23 is printed without the minus. With Eq. 24's B, sum_j V_j r_ij (x) grad_i W_ij =
-B_i^-1, so for a linear field v = A x the printed sum gives -A: the minus makes Eq. 23
the gradient that Eq. 24 corrects (tests/test_solid_kernels.py: exact for a linear field).

with s = sigma + p I the deviatoric (shear) stress, p = -tr(sigma)/3, the
Riemann pressure P*_ij = (p_i + p_j)/2 - beta rho_bar c0 u_jump / 2 and
u_jump = (v_i - v_j).e_ij (> 0 for a pair moving apart): elastic solids take
beta = 1 (000_ Sec. 3.1.2), granular materials the limiter
beta = min(eta max(u_jump/c0, 0), 1) with eta = 20 d (000_ Sec. 3.1.3), which
damps pairs that move apart.

That sign is the second deliberate difference from the paper's text, and it
follows the paper's own code; fluids take the same rule (fluid.py). Eq. 20 as printed, min{eta max[(P_L + P_R)
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

B is computed by correction.py (the transport-velocity shift uses it too).

A wall particle takes the stress and density of the material particle it
interacts with and the mirrored velocity of walls.py (000_ Sec. 5: no-slip
walls after Bui et al. 2008). A free-slip wall is a mirror plane: its partner
is the mirror image of i, with velocity v_i mirrored in its normal part only
(walls.py) and stress R sigma_i R, R = I - 2 n n^T. The shear stress across
the wall (n-t) then cancels in the pair sum s_i + R s_i R and the wall pushes
only along its normal, which is what free slip means: taking s_i unmirrored,
as for a no-slip wall, left a tangential traction 2 s_nt on the particles
beside it, and in flume_3d a layer along each free-slip side wall kept
sliding at 0.2 m/s after the mass had come to rest. The pair offset to a
free-slip partner is taken along the wall's normal, g -> (g . n) n
(walls.along_wall_normal), in the momentum and in the velocity gradient: the
mirror image lies along n. With the offset itself, where the wall lattice is
not symmetric about the particle (a joint of two wall parts, a corner) the
tangential gradients g_t of the wall partners do not cancel, the wall pushed
along itself (2 sigma_tt g_t) and the shear strain rate of the normal motion
(n (x) g_t) stored work no force did: the pair power 2 V_i V_j (v_n sigma_nn g_n
+ v_t . sigma_tt g_t) against 2 V_i V_j v_n (sigma_nn g_n + sigma_nt . g_t)
(tests/test_free_slip_walls.py checks they now agree on a jittered wall).

The order of the sub-steps of a time step is the integrator's
(integrators/position_verlet.py).
"""

import numpy as np
from numba import njit

from ..forces import ForceTerm
from ..kernels import pair_dw
from ..neighbours import pair_difference, pair_offset
from ..particles import MOVING, WALL, WALL_SLIP, Field, is_wall
from ..scheme import Scheme
from ..tensors import component, full_times_vector
from .density_reinit import reinitialise_density
from .fluid import continuity
from .velocity_gradient import gradient_sum
from .walls import along_wall_normal, wall_relative_velocity


STRESS = Field("stress", (6,), np.float64, "Cauchy stress, tension positive, packed (tensors.py) [Pa]")


@njit(cache=True)
def velocity_gradient(i, start, nbr, xc, v, mass, rho, kind, normal, wall_distance, beta_max, B, k, L):
    """L_i of 000_ Eq. 23 of the material particle i into the 3 x 3 ``L`` (zero third row and
    column in 2D). The stress updates call it particle by particle, so that no n x 3 x 3 array
    of gradients is ever stored.

    B_i is the same for every pair of i, so the sum runs uncorrected,
    M_i = -sum_j V_j (v_i - v_j) (x) grad_i W_ij (velocity_gradient.gradient_sum, a wall partner at
    its own density), and L_i = M_i B_i^T; with an empty ``B`` (``B.shape[0] == 0``) L_i = M_i, the
    plain gradient of 002_ Eqs. 26-27. A wall partner's velocity is mirrored (``beta_max <= 0``) or
    Morris's (walls.py, 002_ Eq. 34, which reads ``wall_distance``).
    """
    dim = xc.shape[1]
    M = gradient_sum(i, start, nbr, xc, v, mass, rho, kind, normal, wall_distance, beta_max, False, k)
    L[:, :] = 0.0
    corrected = B.shape[0] > 0
    for a in range(dim):
        for b in range(dim):
            if not corrected:
                L[a, b] = M[a][b]
                continue
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
def tensor_times(T, k, p, dim, d0, d1, d2):
    """T_k (d0, d1, d2) as three scalars, over the in-plane block: T is T = s B (n, dim, dim),
    or the packed stress (n, 6), from which s = sigma + p I is formed."""
    if T.ndim == 2:  # packed sigma (tensors.py order xx, yy, zz, xy, yz, xz)
        pk = p[k]
        if dim == 2:
            return (T[k, 0] + pk) * d0 + T[k, 3] * d1, T[k, 3] * d0 + (T[k, 1] + pk) * d1, 0.0
        return ((T[k, 0] + pk) * d0 + T[k, 3] * d1 + T[k, 5] * d2,
                T[k, 3] * d0 + (T[k, 1] + pk) * d1 + T[k, 4] * d2,
                T[k, 5] * d0 + T[k, 4] * d1 + (T[k, 2] + pk) * d2)
    return full_times_vector(T, k, dim, d0, d1, d2)


@njit(inline="always")
def mirrored_tensor_times(T, k, p, dim, d0, d1, d2, normal, j):
    """(R T_k R) . d with R = I - 2 n n^T, the mirror in the free-slip wall of particle j (normal n):
    T_k's components across the wall (n-t) change sign, those along and normal to it stay."""
    n0, n1 = normal[j, 0], normal[j, 1]
    n2 = normal[j, 2] if dim == 3 else 0.0
    dn = d0 * n0 + d1 * n1 + d2 * n2
    y0, y1, y2 = tensor_times(T, k, p, dim, d0 - 2.0 * dn * n0, d1 - 2.0 * dn * n1, d2 - 2.0 * dn * n2)
    yn = y0 * n0 + y1 * n1 + y2 * n2
    return y0 - 2.0 * yn * n0, y1 - 2.0 * yn * n1, y2 - 2.0 * yn * n2


@njit(cache=True)
def stress_acceleration(n, start, nbr, xc, v, rho, p, T, mass, kind, normal, c0, eta, damped, k, acc):
    """acc += the stress part of dv/dt of the moving particles (module docstring); eta <= 0
    means beta = 1, else the limiter acts on the pairs whose u_jump has the sign ``damped``
    (fluid.LIMITED_PAIRS).

    The shear part takes T = s B from ``shear_force_tensor`` (corrected), or the packed
    stress itself, s = sigma + p I being formed on the fly (Eq. 25 as printed: no copy).
    T_i is the same for every pair of i and multiplies sum_j V_j e_ij W'_ij once; a wall
    partner takes the state of i, mirrored in a free-slip wall (module docstring).
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
            q = j
            mirror = False
            if is_wall(kind[j]):  # the wall takes the state of i; walls.py: off the common path
                u0, u1, u2 = wall_relative_velocity(i, j, v, kind, normal)
                q = i
                mirror = kind[j] == WALL_SLIP
                if mirror:
                    d0, d1, d2 = along_wall_normal(j, normal, d0, d1, d2)
            u_jump = (u0 * d0 + u1 * d1 + u2 * d2) / r
            beta = 1.0 if eta <= 0.0 else min(eta * max(damped * u_jump / c0, 0.0), 1.0)
            pressure = p[i] + p[q] - beta * 0.5 * (rho[i] + rho[q]) * c0 * u_jump
            f = mass[j] / rho[j] * pair_dw(k, r, i, j) / r
            if mirror:
                t0, t1, t2 = mirrored_tensor_times(T, i, p, dim, d0, d1, d2, normal, j)
            else:
                t0, t1, t2 = tensor_times(T, q, p, dim, d0, d1, d2)
            a0 += f * (t0 - pressure * d0)
            a1 += f * (t1 - pressure * d1)
            a2 += f * (t2 - pressure * d2)
            g0 += f * d0
            g1 += f * d1
            g2 += f * d2
        t0, t1, t2 = tensor_times(T, i, p, dim, g0, g1, g2)
        acc[i, 0] += (a0 + t0) / rho[i]
        acc[i, 1] += (a1 + t1) / rho[i]
        if dim == 3:
            acc[i, 2] += (a2 + t2) / rho[i]


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


def strain_energy(pa, n, deviator, material):
    """Elastic strain energy sum V (s:s/4G + p^2/2K) of the material particles among the owned
    [0, n), from their packed deviatoric stress s (rows [0, n)) and pressure p."""
    vol = pa.mass[:n] / pa.rho[:n]
    s_s = np.sum(deviator[:, :3] ** 2, axis=1) + 2.0 * np.sum(deviator[:, 3:] ** 2, axis=1)  # off-diagonals twice
    density = s_s / (4.0 * material.G) + pa.p[:n] ** 2 / (2.0 * material.K)
    return float(np.sum((vol * density)[~np.isin(pa.kind[:n], (WALL, WALL_SLIP))]))


SOLID_OUTPUT_FIELDS = (
    Field("von_mises", (), np.float64, "von Mises stress sqrt(3/2 s:s) [Pa]"),
    Field("vertical_stress", (), np.float64, "normal stress along the vertical axis (y in 2D, z in 3D), tension "
          "positive [Pa]"),
    Field("speed", (), np.float64, "speed |v| [m/s]"),
)


def solid_output_fields(stress, v, n):
    """Output-only fields of the particles [0, n) of a packed stress (n, 6) and velocity: von Mises,
    vertical stress, speed (``SOLID_OUTPUT_FIELDS``)."""
    von_mises = np.empty(n)
    speed = np.empty(n)
    output_invariants(n, stress, v, von_mises, speed)
    vertical = v.shape[1] - 1
    return {"von_mises": von_mises, "vertical_stress": stress[:n, vertical].copy(), "speed": speed}


class RiemannStress(ForceTerm):
    """The momentum sum of 000_ Eqs. 17, 22, 25-26 (module docstring)."""

    name = "riemann_stress"

    def __init__(self, c0, eta, damped, corrected):
        self.c0 = c0
        self.eta = eta
        self.damped = damped
        self.corrected = corrected

    def add(self, ctx, acc):
        pa = ctx.particles
        if self.corrected:
            T = ctx.workspace.get("shear_force", pa.n, (pa.dim, pa.dim))
            shear_force_tensor(pa.n, pa.kind, pa.stress, pa.p, pa.B, T)
        else:
            T = pa.stress
        stress_acceleration(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.v, pa.rho, pa.p, T, pa.mass, pa.kind,
                            pa.normal, self.c0, self.eta, self.damped, ctx.kernel.params, acc)


class SolidScheme(Scheme):
    """What elastic and granular schemes share; each subclass fills in its constitutive part.

    A subclass sets ``eta`` (the momentum limiter, <= 0: beta = 1; ``damped`` the sign of
    fluid.LIMITED_PAIRS it acts on),
    ``riemann_continuity`` (1: Eq. 16, 0: Eq. 21) and ``corrected_shear_force``
    (B on the shear part of the momentum sum, module docstring), and provides
    ``state(ctx)`` (p and the total stress from the density or the stress) and
    ``update_stress(ctx, dt)`` (the stress at the end of the step, from the
    velocity gradient of Eq. 23).
    """

    needs_surface = True
    derived = SOLID_OUTPUT_FIELDS
    advances_in_rates = True  # update_stress
    acoustic_cfl = 0.4  # 000_ Eq. 38: c0 of Eq. 6 is below the P-wave speed of a solid
    state_fields = ("rho", "p", "stress")
    eta = -1.0
    damped = 1.0
    riemann_continuity = 0.0
    corrected_shear_force = False

    base_fields = (
        STRESS,
        Field("B", ("sym",), np.float64, "kernel-gradient correction matrix (000_ Eq. 24), packed [-]"),
    )

    def __init__(self, case, kernel):
        super().__init__(case, kernel)
        self.gravity = case.gravity
        self._no_distance = np.zeros(0)  # mirrored walls read no wall distance

    def forces(self):
        return (RiemannStress(self.material.c0, self.eta, self.damped, self.corrected_shear_force),)

    def configure(self, ctx):
        """With ``Case.density_reinit`` the density by kernel summation (fluid.py), then the
        correction matrices on the frozen positions (ghosts too when the momentum sum reads them)."""
        if reinitialise_density(ctx, self):
            ctx.refresh(["rho"])
        ctx.correction_matrices()  # into pa.B
        if self.corrected_shear_force:
            ctx.refresh(["B"])

    def rates(self, ctx, dt):
        """Density rate, then the stress from the velocity gradient (particle by particle inside
        ``update_stress``); the stress update reads rho of neighbours, so it comes before the
        integrator's second density half step."""
        pa = ctx.particles
        continuity(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.v, pa.rho, pa.p, pa.mass, pa.kind, pa.normal,
                   self.gravity, self.material.c0, self.riemann_continuity, ctx.kernel.params, pa.drho_dt)
        self.update_stress(ctx, dt)

    def gradient_args(self, ctx):
        """The arguments of ``velocity_gradient`` after i, for the stress updates (mirrored walls,
        the corrected gradient)."""
        pa = ctx.particles
        return (ctx.start, ctx.nbr, ctx.xc, pa.v, pa.mass, pa.rho, pa.kind, pa.normal, self._no_distance, 0.0, pa.B,
                ctx.kernel.params)

    def derived_fields(self, pa, n):
        return solid_output_fields(pa.stress, pa.v, n)
