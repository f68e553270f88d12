"""Lid-driven square cavity, compared with Ghia et al. 1982: Re = 100 by default, Re = 1000 as in
001_ Sec. 4.2 (`--set Re=1000 nx=100`)."""

import numpy as np

from mpisph.case import Body, Case, Fluid, Param, Wall, limiter_param
from mpisph.geometry import box, box_walls, support_layers

PARAMS = {
    "nx": Param(50, "-", "particles along each side", positive=True),
    "Re": Param(100.0, "-", "Reynolds number U L / nu", positive=True),
    "U": Param(1.0, "m/s", "lid speed", positive=True),
    "rho0": Param(1.0, "kg/m^3", "density", positive=True),
    "c0": Param(10.0, "m/s", "artificial sound speed (10 U)", positive=True),
    "stabiliser": Param("tvf_limited", "-", "particle regularisation (001_ Eq. 16)",
                        choices=("none", "tvf_limited")),
    "limiter": limiter_param("separating"),
    "t_end": Param(30.0, "s", "simulated end time", positive=True),
    "output_interval": Param(1.0, "s", "simulated time between frames", positive=True),
}


def setup(p):
    dp = 1.0 / p.nx
    fluid = box((0.0, 0.0), (1.0, 1.0), dp, "the cavity")
    layers = support_layers(p.h_factor)
    wall_x, wall_n = box_walls((0.0, 0.0), (1.0, 1.0), dp, layers)
    lid = wall_x[:, 1] > 1.0
    wall_v = np.zeros_like(wall_x)
    wall_v[lid, 0] = p.U
    margin = layers * dp
    return Case(
        dim=2,
        domain=((-margin, -margin), (1.0 + margin, 1.0 + margin)),
        dp=dp,
        material=Fluid(rho0=p.rho0, c0=p.c0, viscosity=p.rho0 * p.U / p.Re),
        scheme="riemann_fluid",
        scheme_options={"limiter": p.limiter},
        bodies=[Body("fluid", fluid)],
        walls=[Wall("cavity", wall_x, wall_n, velocity=wall_v)],
        density_reinit="inner",
        stabilisers=p.stabiliser,
        u_ref=p.U,
    )
