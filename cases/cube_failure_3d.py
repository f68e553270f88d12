"""3D failure of a cohesive soil cube: a 2 m Drucker-Prager cube collapses under its own weight on a floor (000_ Sec. 5.3).

Recorded beside the energies (diagnostics.csv): the spread, as the largest distance of a particle
from the cube's vertical axis (front), and the displacement of the particle nearest the middle of
the top face (top_ux, top_uy, top_uz: its settlement). The plastic strain on the diagonal plane ABC
is scripts/production.py's slice.
"""

from mpisph.case import Front, Param
from mpisph.soil import cube_on_floor, scheme_params, soil_params

PARAMS = {
    "edge": Param(2.0, "m", "edge length of the soil cube", positive=True),
    "floor": Param(5.0, "m", "side of the square floor the cube stands on", positive=True),
    "dp": Param(0.04, "m", "particle spacing (0.04 in the paper: 125000 particles)", positive=True),
    **soil_params(rho0=1850.0, E=1.8e6, nu=0.3, cohesion=5.0e3, phi=25.0),  # 000_ Table 2, as Sec. 5.2
    **scheme_params(),
    "t_end": Param(1.0, "s", "simulated end time", positive=True),
    "output_interval": Param(0.1, "s", "simulated time between frames", positive=True),
}


def setup(p):
    return cube_on_floor(p, p.edge, p.floor, "soil cube", front=Front(origin=(0.0, 0.0, 0.0), axes=(0, 1)),
                         probes={"top": (0.0, 0.0, p.edge)})
