"""Materials a case can fill its bodies with, and their derived constants.

- ``Fluid``: weakly compressible fluid (000_ Eq. 3, 001_ Eqs. 1-7);
- ``ElasticSolid``: linear elastic solid, pressure from the equation of
  state and shear stress from its rate (000_ Eqs. 4-9);
- ``DruckerPrager``: elastic-perfectly plastic granular material with the
  non-associated Drucker-Prager model (000_ Eqs. 10-15);
- ``MuIGranular``: dense granular flow with the mu(I) rheology, weakly
  compressible grains and a regularised viscosity (004_ Secs. 2, 4).

Both solids take their artificial sound speed from the bulk modulus,
c0 = sqrt(E / (3 (1 - 2 nu) rho0)) (000_ Eq. 6).
"""

import math
from dataclasses import dataclass

from .errors import InputError
from .physics.mu_i_law import MuIParams, friction, residual_viscosity


class LinearEquationOfState:
    """The pressure p = c0^2 (rho - rho0) of a fluid and of a linear elastic solid (000_ Eqs. 3, 5)."""

    def density_under(self, p):
        """The density at pressure p, rho0 + p / c0^2 [kg/m^3]."""
        return self.rho0 + p / self.c0**2


@dataclass
class Fluid(LinearEquationOfState):
    """Weakly compressible fluid (000_ Eq. 3, 001_ Eqs. 1-7)."""

    rho0: float
    c0: float
    viscosity: float = 0.0  # dynamic viscosity [Pa s]


@dataclass
class ElasticConstants:
    """Density, Young's modulus and Poisson's ratio, and the constants derived from them."""

    rho0: float
    E: float
    nu: float

    @property
    def K(self):
        """Bulk modulus [Pa]."""
        return self.E / (3.0 * (1.0 - 2.0 * self.nu))

    @property
    def G(self):
        """Shear modulus [Pa]."""
        return self.E / (2.0 * (1.0 + self.nu))

    @property
    def c0(self):
        """Sound speed of 000_ Eq. 6 [m/s]."""
        return math.sqrt(self.K / self.rho0)


@dataclass
class ElasticSolid(ElasticConstants, LinearEquationOfState):
    """Linear elastic solid: density, Young's modulus, Poisson's ratio."""


@dataclass
class DruckerPrager(ElasticConstants):
    """Drucker-Prager soil: adds cohesion c [Pa], friction and dilatancy angles [deg]."""

    cohesion: float = 0.0
    phi: float = 30.0
    psi: float = 0.0

    def __post_init__(self):
        if self.psi > self.phi:
            raise InputError(f"Drucker-Prager soil: the dilatancy angle psi ({self.psi:g} deg) must not exceed the "
                             f"friction angle phi ({self.phi:g} deg)")

    @staticmethod
    def _alpha(angle_deg):
        t = math.tan(math.radians(angle_deg))
        return t / math.sqrt(9.0 + 12.0 * t * t)

    @property
    def alpha_phi(self):
        """alpha_phi of 000_ Eq. 14."""
        return self._alpha(self.phi)

    @property
    def alpha_psi(self):
        """alpha_psi of 000_ Eq. 14."""
        return self._alpha(self.psi)

    @property
    def k_c(self):
        """k_c of 000_ Eq. 14 [Pa]."""
        t = math.tan(math.radians(self.phi))
        return 3.0 * self.cohesion / math.sqrt(9.0 + 12.0 * t * t)

    @property
    def k0(self):
        """Earth pressure coefficient at rest, 1 - sin(phi) (Jaky)."""
        return 1.0 - math.sin(math.radians(self.phi))


@dataclass
class MuIGranular:
    """Cohesionless grains in the dense regime (004_ Eqs. 7-8, 13, 41-55; physics/mu_i_law.py).

    rho_s0 [kg/m^3] and d0 [m]: grain density and size unconfined; mu_s, mu_2, I_0: the friction
    law (Eq. 7); phi_max, phi_min: the volume fractions of Eq. 8; K_t [1/Pa]: grain
    compressibility (Eq. 41); tau_0 [Pa], m_0 [s]: the regularisation's reference yield stress
    and scaling time (Eq. 55); scale_length [m]: H of Eq. 18, which adds I_s = 2.61 d0/H to I in
    the friction law (0: Eq. 7).
    """

    rho_s0: float
    d0: float
    mu_s: float
    mu_2: float
    I_0: float
    K_t: float
    tau_0: float
    m_0: float
    phi_max: float = 0.6
    phi_min: float = 0.5
    scale_length: float = 0.0

    def __post_init__(self):
        for name in ("rho_s0", "d0", "K_t", "I_0", "tau_0", "m_0"):
            if not getattr(self, name) > 0:
                raise InputError(f"mu(I) material: {name} must be positive, not {getattr(self, name)!r}")
        if not 0 <= self.mu_s < self.mu_2:
            raise InputError(f"mu(I) material: mu_2 ({self.mu_2:g}) must exceed mu_s ({self.mu_s:g}) >= 0")
        if not 0 < self.phi_min < self.phi_max <= 1:
            raise InputError(f"mu(I) material: need 0 < phi_min < phi_max <= 1, not phi_min = {self.phi_min:g}, "
                             f"phi_max = {self.phi_max:g}")
        if self.scale_length < 0:
            raise InputError(f"mu(I) material: scale_length must be >= 0, not {self.scale_length:g}")

    @property
    def params(self):
        """The constants the numba loops take (mu_i_law.MuIParams)."""
        shift = 2.61 * self.d0 / self.scale_length if self.scale_length > 0 else 0.0
        return MuIParams(self.mu_s, self.mu_2, self.I_0, shift, self.phi_max, self.phi_min, self.rho_s0, self.d0,
                         self.K_t, self.tau_0, self.m_0)

    @property
    def rho0(self):
        """Bulk density at rest and unconfined, phi_max rho_s0 [kg/m^3] (walls take it)."""
        return self.phi_max * self.rho_s0

    @property
    def c0(self):
        """Sound speed at rest, sqrt(dp/drho) = 1/sqrt(K_t phi_max rho_s0) (Eqs. 9, 41) [m/s]."""
        return 1.0 / math.sqrt(self.K_t * self.rho0)

    def density_under(self, p):
        """Bulk density of grains at rest at pressure p: phi_max rho_s0 (1 + K_t p) (Eqs. 9, 41)."""
        return self.rho0 * (1.0 + self.K_t * p)

    def eta_max(self, tau_y):
        """Largest regularised viscosity at yield stress tau_y, eta_0(tau_y, 0) + tau_y m_p(tau_y)
        (004_ Eq. 53, with m_p of Eq. 55 at gamma_dot -> 0) [Pa s]."""
        m = self.params
        p = tau_y / friction(0.0, m)
        eta_0 = residual_viscosity(p, 0.0, self.rho_s0, self.d0, m)
        return eta_0 + tau_y * (self.m_0 + eta_0 * (tau_y - self.tau_0) / (self.tau_0 * tau_y))

    def uniform_flow(self, theta_deg):
        """(I_u, phi_u) of steady uniform flow down a slope of theta degrees (004_ Sec. 5.1):
        mu(I_u) = tan(theta), phi_u from Eq. 8; ValueError when no I_u > 0 solves it (tan(theta)
        outside (mu(0), mu_2)), where no uniform flow exists."""
        t = math.tan(math.radians(theta_deg))
        m = self.params
        I_u = (m.I_0 * (t - self.mu_s) / (self.mu_2 - t) - m.I_s) if t < self.mu_2 else math.inf
        if not 0 < I_u < math.inf:
            raise ValueError(f"no uniform flow: tan(theta) = {t:.4g} is not between mu(0) and mu_2 = "
                             f"{self.mu_2:.4g}")
        return I_u, self.phi_max - (self.phi_max - self.phi_min) * I_u
