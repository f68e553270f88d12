"""2D failure of a cohesive soil cut: a 4 m x 2 m Drucker-Prager block against a left wall fails under its own weight (000_ Sec. 5.2, Bui et al. 2008)."""

from mpisph.case import Param
from mpisph.soil import block_on_floor, scheme_params, soil_params

PARAMS = {
    "L": Param(4.0, "m", "length of the soil block", positive=True),
    "H": Param(2.0, "m", "height of the cut", positive=True),
    "dp": Param(0.04, "m", "particle spacing (L/100 in the paper)", positive=True),
    **soil_params(rho0=1850.0, E=1.8e6, nu=0.3, cohesion=5.0e3, phi=25.0),  # 000_ Table 2
    **scheme_params(),
    "t_end": Param(2.0, "s", "simulated end time", positive=True),
    "output_interval": Param(0.1, "s", "simulated time between frames", positive=True),
}


def setup(p):
    return block_on_floor(p, p.L, p.H, 2.5 * p.L, "soil")
