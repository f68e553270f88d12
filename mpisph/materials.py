"""Materials a case can fill its bodies with, and their derived constants.

- ``Fluid``: weakly compressible fluid (000_ Eq. 3, 001_ Eqs. 1-7);
- ``ElasticSolid``: linear elastic solid, pressure from the equation of
  state and shear stress from its rate (000_ Eqs. 4-9);
- ``DruckerPrager``: elastic-perfectly plastic granular material with the
  non-associated Drucker-Prager model (000_ Eqs. 10-15).

Both solids take their artificial sound speed from the bulk modulus,
c0 = sqrt(E / (3 (1 - 2 nu) rho0)) (000_ Eq. 6).
"""

import math
from dataclasses import dataclass


@dataclass
class Fluid:
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
class ElasticSolid(ElasticConstants):
    """Linear elastic solid: density, Young's modulus, Poisson's ratio."""


@dataclass
class DruckerPrager(ElasticConstants):
    """Drucker-Prager soil: adds cohesion c [Pa], friction and dilatancy angles [deg]."""

    cohesion: float = 0.0
    phi: float = 30.0
    psi: float = 0.0

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
