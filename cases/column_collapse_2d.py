"""2D granular column collapse: a cohesionless Drucker-Prager column released against a back wall (000_ Sec. 5.1, Nguyen et al. 2017)."""

import numpy as np

from mpisph.case import Body, Case, DruckerPrager, Param, Wall
from mpisph.geometry import box, box_walls
from mpisph.physics.drucker_prager import geostatic_stress

PARAMS = {
    "L": Param(0.2, "m", "length of the column (0.2 or 0.1 in the paper)", positive=True),
    "H": Param(0.1, "m", "height of the column", positive=True),
    "dp": Param(0.002, "m", "particle spacing", positive=True),
    "rho0": Param(2040.0, "kg/m^3", "bulk density", positive=True),
    "E": Param(5.84e6, "Pa", "Young's modulus", positive=True),
    "nu": Param(0.3, "-", "Poisson's ratio", positive=True),
    "cohesion": Param(0.0, "Pa", "cohesion c"),
    "phi": Param(21.9, "deg", "friction angle"),
    "psi": Param(0.0, "deg", "dilatancy angle"),
    "g": Param(9.8, "m/s^2", "gravity", positive=True),
    "stabiliser": Param("utvf", "-", "particle regularisation (000_ Eqs. 30-37)",
                        choices=("none", "tvf", "utvf")),
    "t_end": Param(1.0, "s", "simulated end time", positive=True),
    "output_interval": Param(0.05, "s", "simulated time between frames", positive=True),
}


def setup(p):
    soil = DruckerPrager(rho0=p.rho0, E=p.E, nu=p.nu, cohesion=p.cohesion, phi=p.phi, psi=p.psi)
    column = box((0.0, 0.0), (p.L, p.H), p.dp, "the column")
    floor = max(3.0 * p.L, 2.5 * p.H + p.L)  # longer than any runout of the paper's columns
    layers = int(np.ceil(2 * p.h_factor))
    wall_x, wall_n = box_walls((0.0, 0.0), (floor, 2.0 * p.H), p.dp, layers, open_sides=("+y",))
    margin = layers * p.dp
    return Case(
        dim=2,
        domain=((-margin, -margin), (floor + margin, 2.0 * p.H)),
        dp=p.dp,
        material=soil,
        bodies=[Body("column", column, stress=geostatic_stress(column, p.H, soil, p.g))],
        walls=[Wall("tank", wall_x, wall_n)],
        gravity=(0.0, -p.g),
        stabiliser=p.stabiliser,
        u_ref=float(np.sqrt(2.0 * p.g * p.H)),
    )
