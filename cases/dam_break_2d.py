"""2D dam break: a water column L x 2L collapsing in a tank 4L wide (Koshizuka & Oka 1996)."""

import numpy as np

from mpisph.case import (Body, Case, Fluid, Front, Param, Wall, density_reinit_param, fluid_stabiliser_params,
                         limiter_param)
from mpisph.geometry import box, box_walls, support_layers

PARAMS = {
    "L": Param(1.0, "m", "width of the water column (its height is 2L)", positive=True),
    "dp": Param(0.02, "m", "particle spacing", positive=True),
    "rho0": Param(1000.0, "kg/m^3", "water density", positive=True),
    "g": Param(9.81, "m/s^2", "gravity", positive=True),
    "wall": Param("no_slip", "-", "tank wall condition", choices=("no_slip", "free_slip")),
    "density_reinit": density_reinit_param("free_surface", ("none", "free_surface")),
    "limiter": limiter_param("separating"),
    **fluid_stabiliser_params("none"),
    "t_end": Param(0.8, "s", "simulated end time", positive=True),
    "output_interval": Param(0.02, "s", "simulated time between frames", positive=True),
}


def setup(p):
    H, W = 2 * p.L, 4 * p.L
    water = box((0.0, 0.0), (p.L, H), p.dp, "the water column")
    pressure = p.rho0 * p.g * (H - water[:, 1])
    u = np.sqrt(2 * p.g * H)
    layers = support_layers(p.h_factor)
    wall_x, wall_n = box_walls((0.0, 0.0), (W, 1.5 * H), p.dp, layers, open_sides=("+y",))
    margin = layers * p.dp
    return Case(
        dim=2,
        domain=((-margin, -margin), (W + margin, 1.5 * H)),
        dp=p.dp,
        material=Fluid(rho0=p.rho0, c0=10 * u),
        scheme="riemann_fluid",
        scheme_options={"limiter": p.limiter},
        bodies=[Body("water", water, pressure=pressure)],
        walls=[Wall("tank", wall_x, wall_n, slip=p.wall == "free_slip")],
        gravity=(0.0, -p.g),
        density_reinit=p.density_reinit,
        stabilisers=p.stabiliser,
        u_ref=u,
        front=Front((0.0, 0.0), (0,)),  # the surge front in diagnostics.csv (measure.surge_front adds dp / 2)
    )
