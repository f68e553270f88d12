"""The mu(I) rheology of dense granular flow with weakly compressible grains (004_ Secs. 2, 4).

Scalar numba functions of one particle; the scheme (mu_i.py) calls them per
particle and materials.MuIGranular calls them for its start-up report.

Friction (004_ Eq. 7, and Eq. 18 with the shift I_s = 2.61 d/H):

    mu(I) = mu_s + (mu_2 - mu_s) (I + I_s) / (I + I_s + I_0)

Eq. 13 prints the fraction as 1 + I/I_0; Eq. 7, which the paper derives it
from, has 1 + I_0/I, the form used here (mu rises from mu_s to mu_2 with I).

Grain density (004_ Eqs. 6, 8, 9, 41, 43, 44). With x = rho_s/rho_s0 and
rho* = rho/rho_s0, the volume fraction phi = rho*/x, phi = phi_max -
(phi_max - phi_min) I, I = gamma_dot d sqrt(rho_s/p), p = (x - 1)/K_t and the
grain size d = d0 x^(-1/D) (D = 2: Eq. 43; D = 3: the same mass argument for
a sphere) combine into

    F(x) = (phi_max - rho*/x)^2 (x - 1) x^(2/D - 1) = gamma_dot^2 d0^2 rho_s0 K_t (phi_max - phi_min)^2

which, multiplied by x^2 / phi_max^2 in 2D, is the cubic of Eq. 44. The
physical root has phi <= phi_max and p >= 0, that is x >= x0 = max(1,
rho*/phi_max). F(x0) = 0 and, above x0, F is a product of positive
increasing factors ((x - 1) x^(-1/3) is increasing too), so there is exactly
one root above x0: ``grain_density_ratio`` finds it by Newton's method kept
inside a bracket. The other roots of Eq. 44 lie below rho*/phi_max (phi >
phi_max), the ones the paper discards. At rest (gamma_dot = 0) the root is x0:
p = max(0, rho/(phi_max rho_s0) - 1)/K_t.

Viscosity regularisation (004_ Eqs. 11, 12, 45-48, 55). The viscosity of Eq.
11, eta = mu(I) p / gamma_dot, is a Bingham form eta = eta_0 + tau_y/gamma_dot
with the yield stress tau_y = mu(0) p (Eq. 12; mu(0) = mu_s for Eq. 7) and

    eta_0 = (mu(I) - mu(0)) p / gamma_dot
          = (mu_2 - mu_s) I_0 d sqrt(p rho_s) / ((I + I_s + I_0) (I_s + I_0)).

With I_s = 0 this is Eq. 47 with (mu_2/mu_s - 1) tau_y in the numerator:
Eq. 47 prints mu_s/mu_s - 1 = 0, which would leave no residual viscosity.
The derivation above gives mu_2/mu_s, and so does the paper's Table 2, whose
eta_max = 190.3 Pa s is tau_0 m_0 + eta_0(tau_0, 0) = 190 + 0.3 only with it
(tests/test_mu_i_law.py). Eqs. 46 and 55 (m_p of the yield stress, m_p = m_0
at tau_y = tau_0) simplify, exactly, to

    eta_hat = (tau_y + eta_0 gdot) (tau_0 g + eta_0) / (tau_0 + eta_0 gdot),
    g = (1 - exp(-m_0 gdot)) / gdot  (-> m_0 as gdot -> 0),

whose relative error against eta is exp(-m_0 gdot) tau_0 / (tau_0 + eta_0
gdot), independent of tau_y: what Eqs. 51-52 ask of m_p. This form has no
logarithm of a possibly negative number and a finite limit at gdot = 0,
eta_hat_max = eta_0(tau_y, 0) + tau_y m_p(tau_y) (Eq. 53), and it is never
negative, where Eq. 55 alone gives m_p < 0 for tau_y below about eta_0/m_0.
"""

import math
from collections import namedtuple

import numpy as np
from numba import njit

# The material constants the numba loops take (materials.MuIGranular.params).
MuIParams = namedtuple("MuIParams", ("mu_s", "mu_2", "I_0", "I_s", "phi_max", "phi_min", "rho_s0", "d0", "K_t",
                                     "tau_0", "m_0"))

NEWTON_ITERATIONS = 60


@njit(cache=True)
def friction(I, m):
    """mu(I) of 004_ Eq. 7 (Eq. 18 when m.I_s > 0)."""
    a = I + m.I_s
    return m.mu_s + (m.mu_2 - m.mu_s) * a / (a + m.I_0)


@njit(cache=True)
def inertial_number(rho, rho_s, m):
    """I of a particle from its volume fraction phi = rho/rho_s (004_ Eqs. 8-9):
    (phi_max - phi)/(phi_max - phi_min), at least 0; 0 where rho_s is not set (<= 0)."""
    if rho_s <= 0.0:
        return 0.0
    return max(0.0, (m.phi_max - rho / rho_s) / (m.phi_max - m.phi_min))


@njit(cache=True)
def _excess(x, rho_star, phi_max, s):
    """F(x) and F'(x) of the module docstring, s = 2/D - 1."""
    u = phi_max - rho_star / x
    du = rho_star / (x * x)
    xs = 1.0 if s == 0.0 else x**s  # 2D: no power
    f = u * u * (x - 1.0) * xs
    df = (2.0 * u * du * (x - 1.0) + u * u) * xs + u * u * (x - 1.0) * s * xs / x
    return f, df


@njit(cache=True)
def grain_density_ratio(rho, gamma_dot, guess, dim, m):
    """x = rho_s / rho_s0 of a particle of bulk density ``rho`` and strain-rate modulus
    ``gamma_dot``: the root of F(x) = gamma_dot^2 d0^2 rho_s0 K_t (phi_max - phi_min)^2 above
    x0 = max(1, rho/(phi_max rho_s0)) (module docstring). Newton from ``guess`` (the particle's
    last value), a bisection step whenever an iterate leaves the bracket."""
    rho_star = rho / m.rho_s0
    x0 = max(1.0, rho_star / m.phi_max)
    dphi = m.phi_max - m.phi_min
    target = gamma_dot * gamma_dot * m.d0 * m.d0 * m.rho_s0 * m.K_t * dphi * dphi
    if target == 0.0:
        return x0
    s = 2.0 / dim - 1.0
    lo, hi = x0, math.inf
    x = guess if guess > x0 else x0 + 1e-6 * x0
    for _ in range(NEWTON_ITERATIONS):
        f, df = _excess(x, rho_star, m.phi_max, s)
        g = f - target
        if g == 0.0:
            return x
        if g > 0.0:
            hi = x
        else:
            lo = x
        new = x - g / df if df > 0.0 else math.inf
        if abs(new - x) <= 4e-16 * x:  # converged, before the bracket test: a step below one ulp lands on hi
            return new
        if not (lo < new < hi):
            new = 0.5 * (lo + hi) if hi < math.inf else x0 + 2.0 * (x - x0)
        x = new
    return x


@njit(cache=True)
def grain_size(x, dim, m):
    """d = d0 x^(-1/D) of grains compressed to x = rho_s / rho_s0 (004_ Eq. 43 in 2D; module docstring)."""
    return m.d0 * x ** (-1.0 / dim)


@njit(cache=True)
def residual_viscosity(p, I, rho_s, d, m):
    """eta_0 = (mu(I) - mu(0)) p / gamma_dot of the module docstring [Pa s] (004_ Eq. 47)."""
    a = m.I_s + m.I_0
    return (m.mu_2 - m.mu_s) * m.I_0 * d * math.sqrt(p * rho_s) / ((I + a) * a)


@njit(cache=True)
def regularised_viscosity(p, gamma_dot, I, rho_s, d, m):
    """eta_hat of 004_ Eqs. 46 and 55 in the closed form of the module docstring [Pa s]; zero
    where p <= 0 (no confinement, no friction)."""
    if p <= 0.0:
        return 0.0
    tau_y = friction(0.0, m) * p
    eta_0 = residual_viscosity(p, I, rho_s, d, m)
    q = m.m_0 * gamma_dot
    g = m.m_0 if q < 1e-8 else -math.expm1(-q) / gamma_dot
    e0g = eta_0 * gamma_dot
    return (tau_y + e0g) * (m.tau_0 * g + eta_0) / (m.tau_0 + e0g)


MEAN_HARMONIC, MEAN_ARITHMETIC, MEAN_SECANT = 0, 1, 2


@njit(inline="always")
def pair_viscosity(factor, eta_i, eta_j, gamma_dot_i, gamma_dot_j, mean):
    """``factor`` times the viscosity eta_ij that a pair (i, j) carries in the pair term of Eq. 27
    (eta_i + eta_j > 0), which stands for the shear flux eta (v_j - v_i) / r at the pair's midpoint:

    - MEAN_HARMONIC, 2 eta_i eta_j / (eta_i + eta_j), Eq. 37 as printed. It vanishes with either
      particle's viscosity: a grain at the free surface (p = 0, so eta = mu p / gamma_dot = 0) feels
      no shear stress from the grains under it, where the continuum has mu rho g dp/2 between the
      two, and the surface layer slides on the pile without friction.
    - MEAN_ARITHMETIC, (eta_i + eta_j) / 2: the midpoint value of a viscosity linear in the
      pressure (a hydrostatic p at one strain rate), but dominated by the larger one: next to a
      grain at rest, whose regularised viscosity is eta_max, a flowing grain is held by eta_max / 2.
    - MEAN_SECANT, (eta_i gamma_dot_i + eta_j gamma_dot_j) / (gamma_dot_i + gamma_dot_j): the mean
      shear stress of the two over their mean strain rate, the secant viscosity of the pair's mean
      state. It is eta where both agree, stays positive at the free surface (the stress below over
      the mean rate), and next to a grain at rest (a small stress eta_max gamma_dot) it is about
      the flowing grain's own; the arithmetic mean where neither is strained.
    """
    if mean == MEAN_HARMONIC:
        return factor * 2.0 * eta_i * eta_j / (eta_i + eta_j)
    if mean == MEAN_SECANT and gamma_dot_i + gamma_dot_j > 0.0:
        return factor * (eta_i * gamma_dot_i + eta_j * gamma_dot_j) / (gamma_dot_i + gamma_dot_j)
    return factor * 0.5 * (eta_i + eta_j)


@njit(cache=True)
def regularised_shear_rates(tau, p, m):
    """The shear rates at which the regularised law (``regularised_viscosity``) of incompressible
    grains (rho_s = rho_s0, d = d0) carries the shear stresses ``tau`` at the pressures ``p``: the root
    of eta_hat(gamma_dot) gamma_dot = tau, which rises with gamma_dot from 0, by bisection; 0 where
    tau <= 0 or p <= 0, inf where tau is out of the law's reach (tau >= mu_2 p). For the uniform
    flows of references.py."""
    out = np.zeros(tau.shape[0])
    for k in range(tau.shape[0]):
        if tau[k] <= 0.0 or p[k] <= 0.0:
            continue
        scale = m.d0 * math.sqrt(m.rho_s0 / p[k])  # I per unit shear rate
        hi = 1.0
        while regularised_viscosity(p[k], hi, hi * scale, m.rho_s0, m.d0, m) * hi < tau[k] and hi < 1e12:
            hi *= 2.0
        if hi >= 1e12:
            out[k] = np.inf
            continue
        lo = 0.0
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if regularised_viscosity(p[k], mid, mid * scale, m.rho_s0, m.d0, m) * mid < tau[k]:
                lo = mid
            else:
                hi = mid
        out[k] = 0.5 * (lo + hi)
    return out
