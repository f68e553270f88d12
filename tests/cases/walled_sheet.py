"""A sheet of the collapses' sand sliding on a free-slip floor between two side walls (tests their
friction, physics/side_walls.py): nothing but the side walls takes its momentum along x."""

import math

import numpy as np

from mpisph.case import Body, Case, Param, Wall
from mpisph.geometry import bed_layers, block, depth, lattice_layers, support_layers
from mpisph.granular_column import column_params, sand
from mpisph.granular_flow import mu_i_scheme, side_wall_params, side_walls

PARAMS = {
    "H": Param(0.00972, "m", "depth of the sheet", positive=True),
    "U": Param(1.0, "m/s", "initial speed along x", positive=True),
    **{k: v for k, v in column_params(a=2.0, dp=0.00243, m_0=1.2).items() if k != "a"},
    **side_wall_params(),
    "t_end": Param(0.02, "s", "simulated end time", positive=True),
    "output_interval": Param(0.002, "s", "simulated time between frames", positive=True),
}


def setup(p):
    material = sand(p, 20 * p.H)
    length = 8 * p.dp
    layers = support_layers(p.h_factor)
    top = lattice_layers(p.H, p.dp) * p.dp
    return Case(
        dim=2,
        dp=p.dp,
        domain=((0.0, -layers * p.dp), (length, 3.0 * p.H + 2 * layers * p.dp)),
        periodic=(True, False),
        material=material,
        **mu_i_scheme(p),
        bodies=[Body("sheet", block((0.0, 0.0), (length, p.H), p.dp, "the sheet"), velocity=np.array([p.U, 0.0]),
                     pressure=lambda x: material.rho0 * p.g * (top - x[:, 1]))],
        walls=[Wall("floor", bed_layers((0.0,), (length,), p.dp, layers), slip=True, distance=depth)],
        gravity=(0.0, -p.g),
        u_ref=math.sqrt(p.g * p.H),
        forces=side_walls(p, p.H),
    )
