"""Soil cylinder impact: a 5 cm cohesive Drucker-Prager cylinder hits a rigid floor at 5 m/s and spreads (plane strain, 002_ Sec. 5).

The floor's surface is the line y = 0, the cylinder's lowest point starts
``gap`` above it, its axis on x = 0. The column ``front`` of diagnostics.csv
is the largest |x| of a soil particle: the cylinder's half-width, so its
maximum spread (002_ Fig. 10) is twice the front. The step follows the CFL
condition; ``--set max_time_step=1e-6`` caps it at 002_ Table 2's.
"""

import math

import numpy as np

from mpisph.case import ANGLE, POISSON, SOLID_PARAMS, Body, Case, Front, Param, Wall, h_factor_param
from mpisph.geometry import bed_layers, depth, disk, support_layers
from mpisph.kernels import KERNELS
from mpisph.soil import drucker_prager, scheme_choice, scheme_params

PARAMS = {
    "D": Param(0.05, "m", "diameter of the cylinder", positive=True),
    "speed": Param(5.0, "m/s", "impact speed", positive=True),
    "gap": Param(0.0015, "m", "initial gap between the cylinder and the floor", positive=True),
    "dp": Param(0.0005, "m", "particle spacing (002_ Table 2)", positive=True),
    "rho0": Param(1850.0, "kg/m^3", "bulk density", positive=True),  # 002_ Table 1
    "E": Param(5.0e6, "Pa", "Young's modulus", positive=True),
    "nu": Param(0.2, "-", "Poisson's ratio", positive=True, bounds=POISSON),
    "cohesion": Param(3.0e4, "Pa", "cohesion c", bounds=(0.0, math.inf)),
    "phi": Param(22.0, "deg", "friction angle", bounds=ANGLE),
    "psi": Param(0.0, "deg", "dilatancy angle (002_: zero), at most phi", bounds=ANGLE),
    "g": Param(9.8, "m/s^2", "gravity", positive=True),
    **{**SOLID_PARAMS, "stabiliser": SOLID_PARAMS["stabiliser"].with_default("none")},
    **{**scheme_params(alpha=1.0, beta=1.0),  # 002_ Table 2
       "scheme": scheme_params()["scheme"].with_default("classic_granular")},
    "kernel": Param("cubic_spline", "-", "smoothing kernel (002_: the cubic B-spline)", choices=tuple(KERNELS)),
    "h_factor": h_factor_param(1.5, "002_ Table 2: h = 1.5 dp"),
    "t_end": Param(0.01, "s", "simulated end time (the spread levels off by 5 ms)", positive=True),
    "output_interval": Param(0.0005, "s", "simulated time between frames", positive=True),
}


def setup(p):
    radius = 0.5 * p.D
    soil = drucker_prager(p)
    x = disk((0.0, p.gap + radius), radius, p.dp, "the cylinder")
    half_floor = 2.0 * p.D  # the spread levels off at about twice the diameter (002_ Fig. 10)
    floor = bed_layers((-half_floor,), (half_floor,), p.dp, support_layers(p.h_factor))
    margin = 4.0 * p.dp
    return Case(
        dim=2,
        domain=((-half_floor - margin, -margin - support_layers(p.h_factor) * p.dp),
                (half_floor + margin, p.gap + 2.0 * p.D)),
        dp=p.dp,
        material=soil,
        **scheme_choice(p),
        bodies=[Body("cylinder", x, velocity=np.tile((0.0, -p.speed), (len(x), 1)))],
        walls=[Wall("floor", floor, distance=depth)],
        gravity=(0.0, -p.g),
        stabilisers=p.stabiliser,
        front=Front((0.0, 0.0), (0,)),
        u_ref=p.speed,
    )
