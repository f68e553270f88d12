"""Still water in a tank open at the top: the pressure stays hydrostatic and the water at rest (wall check)."""

import numpy as np

from mpisph.case import Body, Case, Fluid, Param, Wall, limiter_param
from mpisph.geometry import box, box_walls, support_layers

PARAMS = {
    "width": Param(1.0, "m", "tank width", positive=True),
    "depth": Param(0.5, "m", "water depth", positive=True),
    "dp": Param(0.02, "m", "particle spacing", positive=True),
    "rho0": Param(1000.0, "kg/m^3", "water density", positive=True),
    "g": Param(9.81, "m/s^2", "gravity", positive=True),
    "limiter": limiter_param("separating"),
    "t_end": Param(2.0, "s", "simulated end time", positive=True),
    "output_interval": Param(0.5, "s", "simulated time between frames", positive=True),
}


def setup(p):
    water = box((0.0, 0.0), (p.width, p.depth), p.dp, "the water")
    u = np.sqrt(2 * p.g * p.depth)
    layers = support_layers(p.h_factor)
    wall_x, wall_n = box_walls((0.0, 0.0), (p.width, 2 * p.depth), p.dp, layers, open_sides=("+y",))
    margin = layers * p.dp
    return Case(
        dim=2,
        domain=((-margin, -margin), (p.width + margin, 2 * p.depth)),
        dp=p.dp,
        material=Fluid(rho0=p.rho0, c0=10 * u),
        scheme="riemann_fluid",
        scheme_options={"limiter": p.limiter},
        bodies=[Body("water", water, pressure=p.rho0 * p.g * (p.depth - water[:, 1]))],
        walls=[Wall("tank", wall_x, wall_n)],
        gravity=(0.0, -p.g),
        density_reinit="free_surface",
        u_ref=u,
    )
