"""2D granular column collapse: a cohesionless Drucker-Prager column released against a back wall (000_ Sec. 5.1, Nguyen et al. 2017)."""

from dataclasses import replace

from mpisph.case import Front, Param
from mpisph.soil import block_on_floor, scheme_params, soil_params

PARAMS = {
    "L": Param(0.2, "m", "length of the column (0.2 or 0.1 in the paper)", positive=True),
    "H": Param(0.1, "m", "height of the column", positive=True),
    "dp": Param(0.002, "m", "particle spacing", positive=True),
    **soil_params(rho0=2040.0, E=5.84e6, nu=0.3, cohesion=0.0, phi=21.9),  # 000_ Table 2
    **scheme_params(),
    "t_end": Param(1.0, "s", "simulated end time", positive=True),
    "output_interval": Param(0.05, "s", "simulated time between frames", positive=True),
}


def setup(p):
    floor = max(3.0 * p.L, 2.5 * p.H + p.L)  # longer than any runout of the paper's columns
    return replace(block_on_floor(p, p.L, p.H, floor, "column"), front=Front((0.0, 0.0), (0,)))  # in diagnostics.csv
