"""A sheet of the collapses' sand sliding over their rough floor, mu(I) rheology: how hard the floor holds a thin layer.

A layer H deep, periodic along x, starts at a uniform speed U over the
no-slip floor of lube_collapse_2d (Morris ghost particles, 004_ Eqs. 34-36)
under its own hydrostatic pressure, and is brought to rest by the floor. A
frictional layer loses speed at mu g, with mu between mu_s and mu_2 of the
sand (004_ Eq. 7), whatever its depth: the grip of the discretised floor on
a layer a few particles deep is what this case measures (docs/COLLAPSES.md;
the mean speed is momentum_x / mass of diagnostics.csv). The sand and its
K_t and tau_0 are those of the planar column of height ``H_0``
(granular_column.py). With ``floor=free_slip`` and side walls
(``channel_width``) only the walls hold the sheet back (tests/test_side_walls.py).
"""

import math

import numpy as np

from mpisph.case import Body, Case, Param, Wall
from mpisph.geometry import bed_layers, block, depth, lattice_layers, support_layers
from mpisph.granular_column import column_params, sand
from mpisph.granular_flow import mu_i_scheme, side_wall_params, side_walls

PARAMS = {
    "H": Param(0.00972, "m", "depth of the sheet", positive=True),
    "U": Param(1.0, "m/s", "initial speed along x", positive=True),
    "H_0": Param(0.1944, "m", "height of the column whose sand this is (K_t, tau_0): lube_collapse_2d at a = 2",
                 positive=True),
    "columns": Param(16, "-", "particles along the periodic x (its length is columns * dp)", positive=True),
    "floor": Param("no_slip", "-", "the floor: no_slip, the collapses' rough floor, or free_slip, along which "
                   "nothing but side walls (if any) holds the sheet", choices=("no_slip", "free_slip")),
    **{k: v for k, v in column_params(a=2.0, dp=0.00243, m_0=1.2).items() if k != "a"},
    **side_wall_params(),
    "t_end": Param(0.25, "s", "simulated end time", positive=True),
    "output_interval": Param(0.01, "s", "simulated time between frames", positive=True),
}


def setup(p):
    material = sand(p, p.H_0)
    length = p.columns * p.dp
    layers = support_layers(p.h_factor)
    sheet = block((0.0, 0.0), (length, p.H), p.dp, "the sheet")
    top = lattice_layers(p.H, p.dp) * p.dp
    return Case(
        dim=2,
        dp=p.dp,
        domain=((0.0, -layers * p.dp), (length, 3.0 * p.H + 2 * layers * p.dp)),
        periodic=(True, False),
        material=material,
        **mu_i_scheme(p),
        bodies=[Body("sheet", sheet, velocity=np.array([p.U, 0.0]),
                     pressure=lambda x: material.rho0 * p.g * (top - x[:, 1]))],
        walls=[Wall("floor", bed_layers((0.0,), (length,), p.dp, layers), slip=p.floor == "free_slip",
                    distance=depth)],
        gravity=(0.0, -p.g),
        u_ref=math.sqrt(p.g * p.H_0),
        density_reinit=p.density_reinit,
        forces=side_walls(p, p.H),
    )
