"""The strain rate of the mu(I) scheme and the divergence of its corrected viscous stress.

In the papers' sign convention (r_ij = x_i - x_j, g_ij = grad_i W_ij = W' r_ij / r),
the velocity gradient of 004_ Eq. 31 and the corrected gradient of 000_ Eq. 24 are

    M_i[u] = -sum_j V_j (u_i - u_j) (x) g_ij,   V_j = m_j / rho_j,   L_i = M_i B_i,

eps the symmetric part of L and gamma_dot = sqrt(2 eps:eps) (004_ Eqs. 6, 31).
With ``viscous_form = corrected_stress`` the viscous force is the divergence of
the stress 2 eta eps, carried as T_i = 2 eta_i eps_i B_i (with ``viscous_stress =
deviatoric``, of 2 eta dev(eps), dev(eps) = eps - tr(eps) / D I), in the form that is
the exact adjoint of the gradient above between material particles:

    a_i[u] = sum_j m_j (T_i + T_j) g_ij / (rho_i rho_j),

so that sum_i m_i w_i . a_i[u] = -sum_i V_i 2 eta_i eps_i[u] : eps_i[w] for any
two velocity fields u and w that the walls do not enter (docs/COLLAPSES.md
derives it): the force does the work the strain rate dissipates. The deviator is
a symmetric projection, dev(eps[u]) : eps[w] = dev(eps[u]) : dev(eps[w]), so the
deviatoric stress keeps that symmetry and dissipates 2 eta dev(eps) : dev(eps). The form
sum_j m_j (T_i / rho_i^2 + T_j / rho_j^2) g_ij of the solids (solid.py) differs
from it by the grains' compression, rho_i / rho_j - 1.

Walls. The pair term of Eq. 27 and its strain rate see a wall partner w as
Morris et al. do (004_ Eqs. 34-36): the relative velocity beta (u_i - u_w),
extrapolated to the wall particle's depth. The corrected form sees it as the
solids do (solid.py), as a mirror image of particle i: the relative velocity
2 (u_i - u_w) in the gradient, the stress T_w = T_i in the divergence,
2 m_w T_i g_iw / rho_i^2, on a free-slip wall both taken along the wall normal n
(walls.along_wall_normal: a free-slip wall carries no shear). That pair is the
adjoint above with the walls included, and a uniform stress pushes nothing next
to a wall either (the kernel sums of the particles and of the wall balance).
Morris's beta cannot have both: the adjoint of the gradient's
-(m_w / rho_i) beta (u_i - u_w) (x) g_iw is beta m_w T_i g_iw / rho_i^2, a wall
that carries beta / 2 of the stress at its surface (three quarters at 004_'s
beta_max = 1.5, a floor holding a quarter less than mu p), and the stress
T_w = T_i with beta in the gradient is not symmetric, which the implicit kick
needs (docs/COLLAPSES.md, tests/test_implicit_viscosity.py). The mirror's price
is the strain rate next to a wall: the wall particles deeper than i get the
velocity of i's mirror image, not the one on i's profile.
"""

import numpy as np
from numba import njit

from ..kernels import pair_dw
from ..neighbours import pair_offset
from ..particles import MOVING, WALL_SLIP, is_wall
from ..tensors import (IDENTITY_BLOCK, block_less_outer, block_plus_diagonal, component, full_times_vector,
                       store_scaled_inverse, times_vector)
from .velocity_gradient import gradient_sum
from .walls import along_wall_normal


@njit(cache=True)
def strain_rate(n, start, nbr, xc, v, rho, mass, kind, normal, wall_distance, beta_max, B, k, strain, gamma_dot):
    """eps_i (packed, tensors.py) and gamma_dot_i = sqrt(2 eps_i : eps_i) of the moving particles
    (004_ Eqs. 6, 31), a wall partner seen as Morris et al. do. With B of 000_ Eq. 24
    (``B.shape[0] > 0``) the gradient is the corrected L_i = M_i B_i, M_i the sum of Eq. 31, a wall
    partner seen as a mirror image (module docstring)."""
    dim = xc.shape[1]
    corrected = B.shape[0] > 0
    wall_beta_max = 0.0 if corrected else beta_max  # a mirrored wall partner (gradient_sum)
    for i in range(n):
        if kind[i] != MOVING:
            continue
        M = gradient_sum(i, start, nbr, xc, v, mass, rho, kind, normal, wall_distance, wall_beta_max, True, k)
        norm = 0.0
        for a in range(dim):
            for b in range(a, dim):
                if corrected:
                    l_ab = l_ba = 0.0
                    for c in range(dim):
                        l_ab += M[a][c] * B[i, component(dim, c, b)]
                        l_ba += M[b][c] * B[i, component(dim, c, a)]
                else:
                    l_ab, l_ba = M[a][b], M[b][a]
                e = 0.5 * (l_ab + l_ba)
                strain[i, component(dim, a, b)] = e
                norm += e * e if a == b else 2.0 * e * e
        gamma_dot[i] = np.sqrt(2.0 * norm)


@njit(cache=True)
def viscous_force_tensor(n, kind, strain, eta, B, deviatoric, T):
    """T_i = 2 eta_i eps_i B_i, the viscous stress times the correction matrix (not symmetric),
    of the moving particles; with ``deviatoric``, 2 eta_i (eps_i - tr(eps_i) / D I) B_i."""
    dim = T.shape[1]
    for i in range(n):
        if kind[i] != MOVING:
            continue
        mean = 0.0
        if deviatoric:
            for a in range(dim):
                mean += strain[i, component(dim, a, a)] / dim
        for a in range(dim):
            for b in range(dim):
                acc = -mean * B[i, component(dim, a, b)]
                for c in range(dim):
                    acc += strain[i, component(dim, a, c)] * B[i, component(dim, c, b)]
                T[i, a, b] = 2.0 * eta[i] * acc


@njit(cache=True)
def stress_divergence(n, start, nbr, xc, rho, T, mass, kind, normal, k, acc):
    """acc_i += sum_j m_j (T_i + T_j) g_ij / (rho_i rho_j) of the moving particles, a wall
    partner's term 2 m_w T_i g_iw / rho_i^2, only its normal part on a free-slip wall (module
    docstring)."""
    dim = xc.shape[1]
    for i in range(n):
        if kind[i] != MOVING:
            continue
        a0 = a1 = a2 = 0.0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            d0, d1, d2, r = pair_offset(xc, i, j)
            f = mass[j] * pair_dw(k, r, i, j) / r
            if is_wall(kind[j]):  # off the common path: the mirror image's T_i
                f *= 2.0 / (rho[i] * rho[i])
                if kind[j] == WALL_SLIP:
                    d0, d1, d2 = along_wall_normal(j, normal, d0, d1, d2)
                t0, t1, t2 = full_times_vector(T, i, dim, d0, d1, d2)
                if kind[j] == WALL_SLIP:
                    t0, t1, t2 = along_wall_normal(j, normal, t0, t1, t2)
            else:
                f /= rho[i] * rho[j]
                t0, t1, t2 = full_times_vector(T, i, dim, d0, d1, d2)
                s0, s1, s2 = full_times_vector(T, j, dim, d0, d1, d2)
                t0, t1, t2 = t0 + s0, t1 + s1, t2 + s2
            a0 += f * t0
            a1 += f * t1
            a2 += f * t2
        acc[i, 0] += a0
        acc[i, 1] += a1
        if dim == 3:
            acc[i, 2] += a2


@njit(cache=True)
def stress_blocks(n, start, nbr, xc, rho, eta, B, mass, kind, k, deviatoric, dt, inverse):
    """inverse_i: the inverse of m_i (I - dt J_i), J_i = d a_i / d u_i the diagonal block of the
    stress divergence at frozen eta and B, of the moving particles (identity elsewhere): the
    preconditioner of the implicit kick. u_i enters the gradient of each neighbour j, whose stress
    then acts on i: J_i u = -sum_j (m_i m_j / (rho_i^2 rho_j)) 2 eta_j E(u, c_j) with
    c_j = B_j g_ij; and its own gradient through H_i = sum_j V_j g_ij + 2 sum_w (m_w / rho_i) g_iw (no-slip walls):
    -(2 eta_i / rho_i) E(u, c_i) with c_i = B_i H_i. E(u, c) = sym(u (x) c) c = (|c|^2 u + (c . u) c) / 2,
    with ``deviatoric`` dev(sym(u (x) c)) c = |c|^2 u / 2 + (1 / 2 - 1 / D) (c . u) c. The free-slip
    wall partners' part of the latter is left out (the preconditioner only needs to be symmetric
    positive definite). Needs eta and B on the ghosts."""
    dim = xc.shape[1]
    outer = 1.0 - 2.0 / dim if deviatoric else 1.0  # 2 E's coefficient of (c . u) c
    block = np.zeros((dim, dim))
    adj = np.zeros((dim, dim))
    for i in range(n):
        b = IDENTITY_BLOCK
        if kind[i] == MOVING:
            h0 = h1 = h2 = 0.0
            for s in range(start[i], start[i + 1]):
                j = nbr[s]
                d0, d1, d2, r = pair_offset(xc, i, j)
                f = pair_dw(k, r, i, j) / r
                if is_wall(kind[j]):  # off the common path
                    if kind[j] != WALL_SLIP:
                        w = 2.0 * mass[j] / rho[i] * f
                        h0, h1, h2 = h0 + w * d0, h1 + w * d1, h2 + w * d2
                    continue
                w = mass[j] / rho[j] * f
                h0, h1, h2 = h0 + w * d0, h1 + w * d1, h2 + w * d2
                c0, c1, c2 = times_vector(B, j, dim, f * d0, f * d1, f * d2)
                b = _plus_sym(b, dt * mass[i] * mass[j] / (rho[i] * rho[i] * rho[j]) * eta[j], outer, c0, c1, c2)
            c0, c1, c2 = times_vector(B, i, dim, h0, h1, h2)
            b = _plus_sym(b, dt * eta[i] / rho[i], outer, c0, c1, c2)
        store_scaled_inverse(b, mass[i] if kind[i] == MOVING else 1.0, block, adj, inverse[i])


@njit(inline="always")
def _plus_sym(b, w, outer, c0, c1, c2):
    """The block b (tensors.IDENTITY_BLOCK) plus w 2 E(., c) = w (|c|^2 I + outer c (x) c)
    (``stress_blocks``)."""
    return block_less_outer(block_plus_diagonal(b, w * (c0 * c0 + c1 * c1 + c2 * c2)), -w * outer, c0, c1, c2)
