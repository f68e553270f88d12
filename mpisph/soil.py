"""A Drucker-Prager soil block resting on a floor against a back wall, at rest under gravity.

Shared by the granular cases (column collapse, cohesive cut): the material
parameters every such case exposes, and the Case of a block [0, L] x [0, H]
with geostatic initial stress, inside a tank of no-slip dummy walls whose
floor is ``floor`` long.
"""

import numpy as np

from .case import SOLID_PARAMS, Body, Case, DruckerPrager, Param, Wall
from .geometry import box, box_walls
from .physics.drucker_prager import geostatic_stress


def soil_params(rho0, E, nu, cohesion, phi, psi=0.0):
    """Typed parameters of the soil with the given defaults, plus gravity and the solid scheme's."""
    return {
        "rho0": Param(rho0, "kg/m^3", "bulk density", positive=True),
        "E": Param(E, "Pa", "Young's modulus", positive=True),
        "nu": Param(nu, "-", "Poisson's ratio", positive=True),
        "cohesion": Param(cohesion, "Pa", "cohesion c"),
        "phi": Param(phi, "deg", "friction angle"),
        "psi": Param(psi, "deg", "dilatancy angle"),
        "g": Param(9.8, "m/s^2", "gravity", positive=True),
        **SOLID_PARAMS,
    }


def block_on_floor(p, L, H, floor, name):
    """The Case of the soil block ``name`` (L x H) on a floor ``floor`` long, parameters ``p``."""
    soil = DruckerPrager(rho0=p.rho0, E=p.E, nu=p.nu, cohesion=p.cohesion, phi=p.phi, psi=p.psi)
    block = box((0.0, 0.0), (L, H), p.dp, f"the {name}")
    layers = int(np.ceil(2 * p.h_factor))
    wall_x, wall_n = box_walls((0.0, 0.0), (floor, 2.0 * H), p.dp, layers, open_sides=("+y",))
    margin = layers * p.dp
    return Case(
        dim=2,
        domain=((-margin, -margin), (floor + margin, 2.0 * H)),
        dp=p.dp,
        material=soil,
        bodies=[Body(name, block, stress=geostatic_stress(block, H, soil, p.g))],
        walls=[Wall("floor and back wall", wall_x, wall_n)],
        gravity=(0.0, -p.g),
        stabiliser=p.stabiliser,
        u_ref=float(np.sqrt(2.0 * p.g * H)),
    )
