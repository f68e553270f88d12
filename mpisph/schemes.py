"""Schemes by name: what ``Case.scheme`` selects (scheme.py says what a scheme is).

- ``riemann_fluid``: weakly compressible fluid, Riemann solver (000_ Sec. 3, 001_);
- ``riemann_elastic``: elastic solid, Riemann SPH (000_ Sec. 3.1.2);
- ``riemann_granular``: Drucker-Prager soil, Riemann SPH (000_ Sec. 3.1.3);
- ``classic_granular``: Drucker-Prager soil, classic SPH with artificial viscosity (002_ Secs. 2-3);
- ``classic_elastic``: elastic solid, the same classic SPH (Gray, Monaghan & Swift 2001);
- ``mu_i``: dense granular flow, mu(I) rheology, weakly compressible grains (004_).
"""

from .errors import InputError
from .physics.classic_granular import ClassicElastic, ClassicGranular
from .physics.drucker_prager import RiemannGranular
from .physics.elastic import RiemannElastic
from .physics.fluid import RiemannFluid
from .physics.mu_i import MuIScheme

SCHEMES = {c.name: c for c in (RiemannFluid, RiemannElastic, RiemannGranular, ClassicGranular, ClassicElastic,
                                    MuIScheme)}


def make_scheme(case, kernel):
    """The scheme ``case.scheme`` for the case's material; InputError if it does not take it."""
    cls = SCHEMES.get(case.scheme)
    if cls is None:
        raise InputError(f"scheme must be one of {', '.join(SCHEMES)}, not {case.scheme!r}")
    if type(case.material) not in cls.materials:
        takes = " or ".join(m.__name__ for m in cls.materials)
        raise InputError(f"scheme {case.scheme} takes a {takes} material, not {type(case.material).__name__}")
    return cls(case, kernel)
