"""Monaghan's artificial stress: a short-range repulsion between particles in tension (Monaghan
2000; Gray, Monaghan & Swift 2001, Eqs. 25-29 of the latter), for solids and fluids.

Each material particle gets a tensor R_i from its principal stresses: in the principal frame,
R'_aa = -epsilon sigma'_aa / rho_i^2 where sigma'_aa > 0 (tension, positive in mpisph) and 0
where it is compressive, rotated back, R_i = Q R' Q^T. The acceleration

    dv_i/dt += sum_j m_j f_ij^n (R_i + R_j) . grad_i W_ij,     f_ij = W_ij(r_ij) / W_ij(dp),

is repulsive for a pair in tension, largest for pairs nearer than dp, and antisymmetric in i
and j, so it conserves linear momentum. f_ij is the pair's kernel over its value at the initial
spacing, so f_ij = 1 at r_ij = dp: with the adaptive kernel (002_ Sec. 4) both use the pair's
knots (kernels.pair_w). The fixed spline's W(dp) in the denominator would scale the repulsion by
(W(dp; a) / W(dp; 1))^n: at h = 1.5 dp, for the knot that a neighbour in tension gives an
undeformed cell (a = 1.78 in 2D, the cap a = b in 3D), 0.49 in 2D and 0.15 in 3D.

n = 4 and, by default, epsilon = 0.3, as Gray et al. use them; a case sets epsilon with its
parameter ``artificial_stress_epsilon`` (case.py's ARTIFICIAL_STRESS_PARAMS: every solid case, the
dam break, drop, patch and Taylor-Green).

In 2D (plane strain) the principal stresses are those of the in-plane block, as Gray et al.
have them; in 3D those of the whole tensor, from an eigen-decomposition per particle (beyond
what the papers ran). A wall particle takes R of the particle it interacts with, mirrored in a
free-slip wall, as the stress of solid.py's walls.

A fluid's stress is -p I, so all its principal stresses are -p: in tension (p < 0)
R_i = epsilon p_i / rho_i^2 I, else 0. That is Monaghan 2000's term for fluids, R_i =
epsilon |p_i| / rho_i^2 added to the pressure term of particles under negative pressure
(mpisph adds R to the acceleration with the opposite sign of a pressure, hence p, not |p|).
"""

import numpy as np
from numba import njit

from ..errors import InputError
from ..forces import ForceTerm
from ..kernels import pair_dw, pair_w
from ..materials import Fluid
from ..neighbours import pair_offset
from ..particles import MOVING, WALL_SLIP, is_wall
from ..physics.solid import mirrored_tensor_times, tensor_times
from ..tensors import component
from .base import Stabiliser

EPSILON = 0.3  # Gray, Monaghan & Swift 2001, Sec. 6
EXPONENT = 4


@njit(cache=True)
def symmetric_eigen(A, V):
    """Eigen-decomposition of the small symmetric matrix A in place by cyclic Jacobi rotations:
    on return A is diagonal (the eigenvalues) and the columns of V are the eigenvectors. (numba's
    np.linalg.eigh needs SciPy's LAPACK, which the project does without.)"""
    dim = A.shape[0]
    for a in range(dim):
        for b in range(dim):
            V[a, b] = 1.0 if a == b else 0.0
    scale = 0.0
    for a in range(dim):
        for b in range(dim):
            scale += A[a, b] * A[a, b]
    for _ in range(50):
        off = 0.0
        for p in range(dim):
            for q in range(p + 1, dim):
                off += A[p, q] * A[p, q]
        if off <= 1e-32 * scale:
            return
        for p in range(dim):
            for q in range(p + 1, dim):
                if A[p, q] == 0.0:
                    continue
                theta = (A[q, q] - A[p, p]) / (2.0 * A[p, q])
                t = 1.0 / (abs(theta) + np.sqrt(theta * theta + 1.0))
                if theta < 0.0:
                    t = -t
                c = 1.0 / np.sqrt(t * t + 1.0)
                s = t * c
                for k in range(dim):  # A J, then J^T (A J), V J: J rotates columns p and q
                    akp, akq = A[k, p], A[k, q]
                    A[k, p], A[k, q] = c * akp - s * akq, s * akp + c * akq
                for k in range(dim):
                    apk, aqk = A[p, k], A[q, k]
                    A[p, k], A[q, k] = c * apk - s * aqk, s * apk + c * aqk
                for k in range(dim):
                    vkp, vkq = V[k, p], V[k, q]
                    V[k, p], V[k, q] = c * vkp - s * vkq, s * vkp + c * vkq


@njit(cache=True)
def artificial_stress_tensors(n, kind, stress, rho, epsilon, dim, R):
    """R_i (packed, tensors.py order) of the material particles in [0, n) (module docstring); zero
    on walls."""
    S = np.zeros((dim, dim))
    Q = np.zeros((dim, dim))
    for i in range(n):
        for c in range(6):
            R[i, c] = 0.0
        if is_wall(kind[i]):
            continue
        for a in range(dim):
            for b in range(dim):
                S[a, b] = stress[i, component(3, a, b)]
        symmetric_eigen(S, Q)
        scale = -epsilon / (rho[i] * rho[i])
        for e in range(dim):
            if S[e, e] <= 0.0:
                continue
            r = scale * S[e, e]
            for a in range(dim):
                for b in range(a, dim):
                    R[i, component(3, a, b)] += r * Q[a, e] * Q[b, e]


@njit(cache=True)
def pressure_artificial_stress_tensors(n, kind, p, rho, epsilon, dim, R):
    """R_i (packed) of the fluid particles in [0, n) from their pressure (module docstring); zero on
    walls and under compression."""
    for i in range(n):
        for c in range(6):
            R[i, c] = 0.0
        if is_wall(kind[i]) or p[i] >= 0.0:
            continue
        r = epsilon * p[i] / (rho[i] * rho[i])
        for a in range(dim):
            R[i, component(3, a, a)] = r


@njit(cache=True)
def artificial_stress_acceleration(n, start, nbr, xc, mass, kind, normal, R, dp, exponent, k, acc):
    """acc += sum_j m_j f_ij^n (R_i + R_j) . grad_i W_ij for the moving particles in [0, n)."""
    dim = xc.shape[1]
    zero = np.zeros(len(kind))  # tensor_times adds p I to a packed tensor: R has none
    for i in range(n):
        if kind[i] != MOVING:
            continue
        a0 = a1 = a2 = 0.0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            d0, d1, d2, r = pair_offset(xc, i, j)
            f = (pair_w(k, r, i, j) / pair_w(k, dp, i, j)) ** exponent * mass[j] * pair_dw(k, r, i, j) / r
            t0, t1, t2 = tensor_times(R, i, zero, dim, d0, d1, d2)
            if kind[j] == WALL_SLIP:
                u0, u1, u2 = mirrored_tensor_times(R, i, zero, dim, d0, d1, d2, normal, j)
            else:
                u0, u1, u2 = tensor_times(R, i if is_wall(kind[j]) else j, zero, dim, d0, d1, d2)
            a0 += f * (t0 + u0)
            a1 += f * (t1 + u1)
            a2 += f * (t2 + u2)
        acc[i, 0] += a0
        acc[i, 1] += a1
        if dim == 3:
            acc[i, 2] += a2


class ArtificialStressForce(ForceTerm):
    """The repulsion of the module docstring, evaluated at every step from the current stress, or,
    for a fluid (``from_pressure``), the current pressure."""

    name = "artificial_stress"

    def __init__(self, dp, epsilon, from_pressure=False):
        self.dp = dp
        self.epsilon = epsilon
        self.from_pressure = from_pressure
        self.ghost_fields = ("p",) if from_pressure else ("stress",)

    def add(self, ctx, acc):
        pa = ctx.particles
        R = ctx.workspace.get("artificial_stress", pa.n, (6,))
        if self.from_pressure:
            pressure_artificial_stress_tensors(pa.n, pa.kind, pa.p, pa.rho, self.epsilon, pa.dim, R)
        elif "stress" in pa.arrays:
            artificial_stress_tensors(pa.n, pa.kind, pa.stress, pa.rho, self.epsilon, pa.dim, R)
        else:
            raise InputError("the artificial_stress stabiliser needs a fluid or a solid scheme (a stress field)")
        artificial_stress_acceleration(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.mass, pa.kind, pa.normal, R,
                                       self.dp, EXPONENT, ctx.kernel.params, acc)


class ArtificialStress(Stabiliser):
    """``artificial_stress``: the force term of the module docstring; it shifts nothing."""

    name = "artificial_stress"

    def __init__(self, case, params):
        self.dp = case.dp
        self.epsilon = params.get("artificial_stress_epsilon", EPSILON)
        self.from_pressure = isinstance(case.material, Fluid)

    def forces(self):
        return (ArtificialStressForce(self.dp, self.epsilon, from_pressure=self.from_pressure),)
