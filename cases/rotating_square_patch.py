"""Rotating square water patch with free surface (000_ Sec. 4.2, Colagrossi 2005).

The defaults run a quick patch (dp = L / 50, no stabiliser, dual time stepping, to t omega = 2);
000_ Figs. 8-9 are ``--set dp=0.01 stabiliser=utvf time_stepping=single --t-end 2.04``
(docs/VALIDATION.md, sections rotating_square_patch and rotating_square_patch_remedies).
"""

import numpy as np

from mpisph.case import Body, Case, Fluid, Param, density_reinit_param, fluid_stabiliser_params, limiter_param
from mpisph.geometry import box

PARAMS = {
    "L": Param(1.0, "m", "side of the square", positive=True),
    "dp": Param(0.02, "m", "particle spacing", positive=True),
    "omega": Param(1.0, "rad/s", "angular velocity of the initial rigid rotation", positive=True),
    "rho0": Param(1000.0, "kg/m^3", "water density", positive=True),
    "c0_factor": Param(10.0, "-", "sound speed over the largest initial speed omega L / sqrt(2)",
                       positive=True),
    "series_terms": Param(40, "-", "odd terms per index in the pressure series", positive=True),
    "density_reinit": density_reinit_param("free_surface", ("none", "free_surface")),
    **fluid_stabiliser_params("none"),
    "limiter": limiter_param("separating"),
    "t_end": Param(2.0, "s", "simulated end time", positive=True),
    "output_interval": Param(0.1, "s", "simulated time between frames", positive=True),
}


def initial_pressure(x, y, L, rho, omega, terms):
    """Incompressible pressure of the rotating square at t = 0 (000_ Eq. 44)."""
    xs, ys = x + L / 2, y + L / 2
    p = np.zeros_like(x)
    odd = np.arange(1, 2 * terms, 2)
    for m in odd:
        sx = np.sin(m * np.pi * xs / L)
        for n in odd:
            k2 = (m * np.pi / L) ** 2 + (n * np.pi / L) ** 2
            p -= rho * 32 * omega**2 / (m * n * np.pi**2 * k2) * sx * np.sin(n * np.pi * ys / L)
    return p


def setup(p):
    half = p.L / 2
    x = box((-half, -half), (half, half), p.dp, "the square")
    velocity = p.omega * np.stack([x[:, 1], -x[:, 0]], axis=1)
    pressure = initial_pressure(x[:, 0], x[:, 1], p.L, p.rho0, p.omega, p.series_terms)
    extent = 2.0 * p.L
    u = p.omega * p.L / np.sqrt(2.0)
    return Case(
        dim=2,
        domain=((-extent, -extent), (extent, extent)),
        dp=p.dp,
        material=Fluid(rho0=p.rho0, c0=p.c0_factor * u),
        scheme="riemann_fluid",
        scheme_options={"limiter": p.limiter},
        bodies=[Body("patch", x, velocity, pressure)],
        density_reinit=p.density_reinit,
        stabilisers=p.stabiliser,
        u_ref=u,
    )
