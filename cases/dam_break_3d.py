"""3D dam break: the 2D dam break's water column L x 2L, L deep, collapsing in a tank 4L long and L deep (Koshizuka & Oka 1996 in 3D)."""

import numpy as np

from mpisph.case import Body, Case, Fluid, Param, Wall, density_reinit_param, limiter_param
from mpisph.geometry import block, support_layers, walls_around

PARAMS = {
    "L": Param(1.0, "m", "length and depth of the water column (its height is 2L)", positive=True),
    "dp": Param(0.05, "m", "particle spacing", positive=True),
    "rho0": Param(1000.0, "kg/m^3", "water density", positive=True),
    "g": Param(9.81, "m/s^2", "gravity", positive=True),
    "density_reinit": density_reinit_param("free_surface", ("none", "free_surface")),
    "limiter": limiter_param("separating"),
    "t_end": Param(0.8, "s", "simulated end time", positive=True),
    "output_interval": Param(0.02, "s", "simulated time between frames", positive=True),
}


def setup(p):
    H, W = 2 * p.L, 4 * p.L
    water = block((0.0, 0.0, 0.0), (p.L, p.L, H), p.dp, "the water column")
    u = np.sqrt(2 * p.g * H)
    layers = support_layers(p.h_factor)
    tank = walls_around((0.0, 0.0, 0.0), (W, p.L, 1.5 * H), p.dp, layers, open_sides=("+z",))
    margin = layers * p.dp
    return Case(
        dim=3,
        domain=((-margin, -margin, -margin), (W + margin, p.L + margin, 1.5 * H)),
        dp=p.dp,
        material=Fluid(rho0=p.rho0, c0=10 * u),
        scheme="riemann_fluid",
        scheme_options={"limiter": p.limiter},
        bodies=[Body("water", water, pressure=lambda x: p.rho0 * p.g * (H - x[:, 2]))],
        walls=[Wall("tank", tank)],
        gravity=(0.0, 0.0, -p.g),
        density_reinit=p.density_reinit,
        u_ref=u,
    )
