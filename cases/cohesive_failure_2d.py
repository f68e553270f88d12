"""2D failure of a cohesive soil cut: a 4 m x 2 m Drucker-Prager block against a left wall fails under its own weight (000_ Sec. 5.2, Bui et al. 2008)."""

import numpy as np

from mpisph.case import Body, Case, DruckerPrager, Param, Wall
from mpisph.geometry import box, box_walls
from mpisph.physics.drucker_prager import geostatic_stress

PARAMS = {
    "L": Param(4.0, "m", "length of the soil block", positive=True),
    "H": Param(2.0, "m", "height of the cut", positive=True),
    "dp": Param(0.04, "m", "particle spacing (L/100 in the paper)", positive=True),
    "rho0": Param(1850.0, "kg/m^3", "bulk density", positive=True),
    "E": Param(1.8e6, "Pa", "Young's modulus", positive=True),
    "nu": Param(0.3, "-", "Poisson's ratio", positive=True),
    "cohesion": Param(5.0e3, "Pa", "cohesion c"),
    "phi": Param(25.0, "deg", "friction angle"),
    "psi": Param(0.0, "deg", "dilatancy angle"),
    "g": Param(9.8, "m/s^2", "gravity", positive=True),
    "stabiliser": Param("utvf", "-", "particle regularisation (000_ Eqs. 30-37)",
                        choices=("none", "tvf", "utvf")),
    "t_end": Param(2.0, "s", "simulated end time", positive=True),
    "output_interval": Param(0.1, "s", "simulated time between frames", positive=True),
}


def setup(p):
    soil = DruckerPrager(rho0=p.rho0, E=p.E, nu=p.nu, cohesion=p.cohesion, phi=p.phi, psi=p.psi)
    block = box((0.0, 0.0), (p.L, p.H), p.dp, "the soil block")
    floor = 2.5 * p.L
    layers = int(np.ceil(2 * p.h_factor))
    wall_x, wall_n = box_walls((0.0, 0.0), (floor, 1.5 * p.H), p.dp, layers, open_sides=("+y",))
    margin = layers * p.dp
    return Case(
        dim=2,
        domain=((-margin, -margin), (floor + margin, 1.5 * p.H)),
        dp=p.dp,
        material=soil,
        bodies=[Body("soil", block, stress=geostatic_stress(block, p.H, soil, p.g))],
        walls=[Wall("ground and back wall", wall_x, wall_n)],
        gravity=(0.0, -p.g),
        stabiliser=p.stabiliser,
        u_ref=float(np.sqrt(2.0 * p.g * p.H)),
    )
