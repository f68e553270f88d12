"""Elliptical water drop: a circular drop stretched by v = (-A x, A y) (000_ Sec. 4.1, Monaghan 1994).

The defaults run 000_ Fig. 4a (no stabiliser) with 001_'s dual time stepping; ``--set
stabiliser=utvf time_stepping=single`` runs 000_'s method with its single step.
"""

import numpy as np

from mpisph.case import Body, Case, Fluid, Param, density_reinit_param, fluid_stabiliser_params, limiter_param
from mpisph.geometry import disk

PARAMS = {
    "dp": Param(0.02, "m", "particle spacing", positive=True),
    "radius": Param(1.0, "m", "initial drop radius", positive=True),
    "A0": Param(100.0, "1/s", "initial stretching rate A(0)", positive=True),
    "rho0": Param(1000.0, "kg/m^3", "water density", positive=True),
    "c0": Param(1000.0, "m/s", "artificial sound speed (10 A0 R)", positive=True),
    "density_reinit": density_reinit_param("none", ("none", "free_surface")),
    **fluid_stabiliser_params("none"),
    "limiter": limiter_param("separating"),
    "t_end": Param(0.008, "s", "simulated end time", positive=True),
    "output_interval": Param(0.0004, "s", "simulated time between frames", positive=True),
}


def setup(p):
    x = disk((0.0, 0.0), p.radius, p.dp, "the drop")
    velocity = p.A0 * np.stack([-x[:, 0], x[:, 1]], axis=1)
    # incompressible pressure at t = 0: p_c (1 - r^2/R^2) with p_c = rho A^2 R^2 / 2
    pressure = 0.5 * p.rho0 * p.A0**2 * (p.radius**2 - np.sum(x**2, axis=1))
    box = 2.5 * p.radius
    return Case(
        dim=2,
        domain=((-box, -box), (box, box)),
        dp=p.dp,
        material=Fluid(rho0=p.rho0, c0=p.c0),
        scheme="riemann_fluid",
        scheme_options={"limiter": p.limiter},
        bodies=[Body("drop", x, velocity, pressure)],
        density_reinit=p.density_reinit,
        stabilisers=p.stabiliser,
        u_ref=p.A0 * p.radius,
    )
