"""Linear stability of a uniform shear flow of 004_'s grains, at frozen coefficients (as Barker et
al. 2015 and Heyman et al. 2017 analyse mu(I)): how fast a plane wave of the velocity and the density
grows, against its wavenumber, for each of the solver's viscous stresses.

The base state is the simple shear eps_0 (eps_xy = gamma_dot_0 / 2) at inertial number I and
pressure p: grain density x = 1 + K_t p, volume fraction phi(I) (004_ Eq. 8), bulk density rho_0 =
phi x rho_s0, gamma_dot_0 = I sqrt(p / rho_s) / d. The law gives p = P(rho, gamma_dot) and mu =
M(rho, gamma_dot) through the solver's grain density (mu_i_law.grain_density_ratio, Eq. 44), whose
partial derivatives are taken by central differences. The stress -p I + 2 eta S(eps), eta = mu p /
gamma_dot, S(e) = dev(e) + c_b tr(e) I with the bulk part c_b of the viscous stress
(well_posedness.bulk_part),
linearised about the base state:

    sigma' = -(P_g g' + P_rho rho') I + 2 eps_0 (eta_g g' + eta_rho rho') + 2 eta_0 S(eps'),
    g' = 2 eps_0 : eps' / gamma_dot_0,   eps' = sym(i v' (x) k),

and with continuity, rho_0 lambda v' = i sigma' k and lambda rho' = -i rho_0 k . v', an eigenproblem
of size D + 1 for each wave vector k (the base flow's advection of k left out, as in those papers).

What it shows for the sand (docs/COLLAPSES.md): long waves grow as k^2 wherever the incompressible
law is ill-posed (well_posedness.ill_posedness); where the compressible equations are well-posed for
short waves (well_posedness.compressible_bulk_friction_bound) the growth levels off at a plateau, and
``handover_wavelength`` says where; where they are not, it grows as k^2 without bound.
"""

import math

import numpy as np

from .physics.mu_i_law import friction, grain_density_ratio, inertial_number

STEP = 1e-6  # relative step of the central differences of P and M


def shear_state(I, p, dim, m):
    """(rho_0, gamma_dot_0, x) of the uniform shear at inertial number ``I`` and pressure ``p`` of the
    law ``m`` (mu_i_law.MuIParams)."""
    x = 1.0 + m.K_t * p
    rho = (m.phi_max - (m.phi_max - m.phi_min) * I) * x * m.rho_s0
    return rho, I * math.sqrt(p / (x * m.rho_s0)) / (m.d0 * x ** (-1.0 / dim)), x


def law(rho, gamma_dot, dim, m, guess):
    """(P, M) = the pressure and friction of grains of bulk density ``rho`` sheared at ``gamma_dot``."""
    x = grain_density_ratio(rho, gamma_dot, guess, dim, m)
    return (x - 1.0) / m.K_t, friction(inertial_number(rho, x * m.rho_s0, m), m)


class LinearisedShear:
    """The tangent J[i, j, a, b] = d sigma_ij / d (d v_a / d x_b) at fixed density and R = d sigma /
    d rho at a fixed velocity gradient, of the base state at (I, p) with the bulk part ``c_b``."""

    def __init__(self, I, p, dim, m, c_b):
        rho, g, x = shear_state(I, p, dim, m)
        self.dim, self.rho = dim, rho
        P, M = law(rho, g, dim, m, x)
        dr, dg = STEP * rho, STEP * g
        P_r, M_r = (np.subtract(law(rho + dr, g, dim, m, x), law(rho - dr, g, dim, m, x))) / (2.0 * dr)
        P_g, M_g = (np.subtract(law(rho, g + dg, dim, m, x), law(rho, g - dg, dim, m, x))) / (2.0 * dg)
        eta = M * P / g
        eta_g = (M_g * P + M * P_g) / g - eta / g
        eta_r = (M_r * P + M * P_r) / g
        eps0 = np.zeros((dim, dim))
        eps0[0, 1] = eps0[1, 0] = 0.5 * g
        identity = np.eye(dim)
        self.J = np.zeros((dim, dim, dim, dim))
        for a in range(dim):
            for b in range(dim):
                e = 0.5 * (np.outer(identity[a], identity[b]) + np.outer(identity[b], identity[a]))
                g1 = 2.0 * (eps0 * e).sum() / g
                shear = e - np.trace(e) / dim * identity + c_b * np.trace(e) * identity
                self.J[:, :, a, b] = -P_g * g1 * identity + 2.0 * eps0 * eta_g * g1 + 2.0 * eta * shear
        self.R = -P_r * identity + 2.0 * eps0 * eta_r

    def growth(self, k, directions):
        """The largest real part of lambda for waves of wavenumber ``k`` along each of the unit
        vectors ``directions`` (rows)."""
        dim, K = self.dim, k * np.asarray(directions)
        A = np.zeros((len(K), dim + 1, dim + 1), dtype=complex)
        A[:, :dim, :dim] = -np.einsum("ijab,nj,nb->nia", self.J, K, K) / self.rho
        A[:, :dim, dim] = 1j * (K @ self.R.T) / self.rho
        A[:, dim, :dim] = -1j * self.rho * K
        return np.linalg.eigvals(A).real.max(axis=1)


def directions(dim, count=721):
    """Unit vectors over half a circle (2D) or a hemisphere (3D, about ``count`` of them)."""
    if dim == 2:
        t = np.linspace(0.0, math.pi, count)
        return np.column_stack([np.cos(t), np.sin(t)])
    side = int(math.sqrt(count / 2.0)) + 1
    a, b = np.meshgrid(np.linspace(0.0, math.pi / 2, side), np.linspace(0.0, 2 * math.pi, 2 * side), indexing="ij")
    return np.column_stack([(np.sin(a) * np.cos(b)).ravel(), (np.sin(a) * np.sin(b)).ravel(), np.cos(a).ravel()])


def growth_curve(lin, wavenumbers, dirs):
    """The largest growth rate over ``dirs`` at each of ``wavenumbers``."""
    return np.array([lin.growth(k, dirs).max() for k in wavenumbers])


def handover_wavelength(wavenumbers, rates):
    """2 pi / k where the growth rates (ascending wavenumbers) first reach half their value at the
    largest wavenumber, on a growth that levels off there; None where the last rate is not positive
    or still rises as k^2 (above 0.9 of the rate at the wavenumber before times their ratio squared)."""
    k, s = np.asarray(wavenumbers), np.asarray(rates)
    if not s[-1] > 0.0 or s[-1] > 0.9 * s[-2] * (k[-1] / k[-2]) ** 2:
        return None
    i = int(np.argmax(s >= 0.5 * s[-1]))
    if i == 0:
        return 2.0 * math.pi / k[0]
    half = math.exp(np.interp(0.5 * s[-1], s[i - 1:i + 1], np.log(k[i - 1:i + 1])))
    return 2.0 * math.pi / half
