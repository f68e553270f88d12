"""A Drucker-Prager soil block resting on a floor, at rest under gravity.

Shared by the Drucker-Prager cases: the material and solid-scheme parameters (``soil_params``:
the column collapse, the cohesive cut, the vertical cut, the cube failure and the flume; the soil
cylinder impact types its own), the material (``drucker_prager``), the choice between the
Riemann and the classic scheme (``scheme_params``, ``scheme_choice``), and the Case of a block
with geostatic initial stress (or another start, parameter initial_stress) inside a tank of
no-slip dummy walls: in 2D the block [0, L] x [0, H] against the back wall of a floor ``floor``
long, in 3D a cube standing in the middle of a square floor with a low rim. ``confined_layer``
is a layer filling a tank of free-slip walls, the test case of docs/FLUME.md.
"""

import math

import numpy as np

from .case import (ANGLE, POISSON, SOLID_PARAMS, Body, Case, DruckerPrager, Param, Wall, classic_viscosity_params,
                   density_reinit_param, limiter_param, scheme_keywords)
from .geometry import block, depth_outside, lattice_mismatch, support_layers, walls_around
from .physics.drucker_prager import INITIAL_STRESSES, STRESS_DIFFUSIONS, geostatic_stress


def drucker_prager(p):
    """The Drucker-Prager soil of the parameters ``p`` (those of ``soil_params``, by attribute)."""
    return DruckerPrager(rho0=p.rho0, E=p.E, nu=p.nu, cohesion=p.cohesion, phi=p.phi, psi=p.psi)


def soil_params(rho0, E, nu, cohesion, phi, psi=0.0, density_reinit="none", at_rest=True):
    """Typed parameters of the soil with the given defaults, plus gravity, the density
    reinitialisation and the solid scheme's; ``at_rest``: also the profile of the initial stress
    of a block at rest (the block cases below)."""
    profile = {"initial_stress": Param(
        INITIAL_STRESSES[0], "-", "initial stress of the block: geostatic (at rest), none (gravity loads it at "
        "t = 0) or inverted (-rho0 g height above the floor, as the authors' SPHinXsys soil cases start; 000_ "
        "prints none)", choices=INITIAL_STRESSES)} if at_rest else {}
    return {
        "rho0": Param(rho0, "kg/m^3", "bulk density", positive=True),
        "E": Param(E, "Pa", "Young's modulus", positive=True),
        "nu": Param(nu, "-", "Poisson's ratio", positive=True, bounds=POISSON),
        "cohesion": Param(cohesion, "Pa", "cohesion c", bounds=(0.0, math.inf)),
        "phi": Param(phi, "deg", "friction angle", bounds=ANGLE),
        "psi": Param(psi, "deg", "dilatancy angle, at most phi", bounds=ANGLE),
        "g": Param(9.8, "m/s^2", "gravity", positive=True),
        "density_reinit": density_reinit_param(density_reinit, why="000_ evolves the density by Eq. 16 alone, "
                                               "the authors' code sums it for soils (docs/FLUME.md)"),
        **SOLID_PARAMS,
        **profile,
    }


def stress_diffusion_param():
    """The parameter choosing riemann_granular's stress diffusion (physics/drucker_prager.py)."""
    return Param(STRESS_DIFFUSIONS[0], "-", "riemann_granular's stress diffusion: linear (sigma less each "
                 "component's local linear part, as delta-SPH's density diffusion; physics/drucker_prager.py), "
                 "geostatic (Feng et al. 2021, as 000_: sigma less its geostatic part) or none",
                 choices=STRESS_DIFFUSIONS)


def scheme_params(alpha=1.0, beta=0.0):
    """Typed parameters choosing the soil's scheme: the Riemann SPH of 000_ (with the pairs its
    limiter damps) or the classic SPH of 002_ (with the artificial viscosity ``alpha``, ``beta`` of
    its Eq. 25 and its Morris walls)."""
    return {
        "scheme": Param("riemann_granular", "-", "riemann_granular: 000_ Sec. 3.1.3; classic_granular: 002_ "
                        "Secs. 2-3 (artificial viscosity, stress scaling back, predictor-corrector, Morris walls)",
                        choices=("riemann_granular", "classic_granular")),
        **classic_viscosity_params(alpha, beta, "classic_granular"),
        "chi_max": Param(1.5, "-", "chi_max of Morris's walls (002_ Eq. 34, 1.5-2; classic_granular)",
                         positive=True, applies=("scheme", ("classic_granular",))),
        "limiter": limiter_param("separating").only_with("scheme", "riemann_granular"),
        "stress_diffusion": stress_diffusion_param().only_with("scheme", "riemann_granular"),
    }


def scheme_choice(p):
    """The keyword arguments of a soil ``Case`` for the scheme the parameters ``p`` choose: the
    classic scheme with Morris's chi_max, or the Riemann scheme with its limiter and stress diffusion."""
    return scheme_keywords(p, {"chi_max": p.chi_max}, {"limiter": p.limiter, "stress_diffusion": p.stress_diffusion})


def block_on_floor(p, L, H, floor, name):
    """The 2D Case of the soil block ``name`` (L x H) on a floor ``floor`` long, parameters ``p``."""
    return _soil_in_tank(p, (0.0, 0.0), (L, H), (0.0, 0.0), (floor, 2.0 * H), name)


def cube_on_floor(p, edge, floor, name, **records):
    """The 3D Case of the soil cube ``name`` (edge ``edge``) centred on the z axis on a square floor
    of side ``floor`` at z = 0, fenced by a rim a quarter of the cube high, parameters ``p``;
    ``records``: the Case's front, probes and gauges."""
    half, rim = 0.5 * edge, 0.25 * edge
    return _soil_in_tank(p, (-half, -half, 0.0), (half, half, edge), (-0.5 * floor, -0.5 * floor, 0.0),
                         (0.5 * floor, 0.5 * floor, rim), name, **records)


def confined_layer(p, L, H, name, k_lateral):
    """The 2D Case of the soil layer ``name`` (L x H) filling a tank L wide of free-slip walls,
    at rest under geostatic stress with the lateral coefficient ``k_lateral``: laterally confined,
    the layer is in equilibrium with any lateral stress."""
    return _soil_in_tank(p, (0.0, 0.0), (L, H), (0.0, 0.0), (L, 2.0 * H), name, slip=True, k_lateral=k_lateral)


def _soil_in_tank(p, lo, hi, tank_lo, tank_hi, name, slip=False, k_lateral=None, **records):
    """Soil filling the box [lo, hi] inside an open-topped tank [tank_lo, tank_hi] of dummy walls
    (no-slip unless ``slip``) under geostatic stress (lateral coefficient ``k_lateral``, Jaky's
    1 - sin phi if None); the domain reaches one block height above the block's top. A side of the
    block that is not a whole number of spacings is warned: its fill falls short of it. ``records``
    go to the Case (front, probes, gauges)."""
    dim = len(lo)
    soil = drucker_prager(p)
    height, top = hi[-1] - lo[-1], hi[-1]
    layers = support_layers(p.h_factor)
    up = "+" + "xyz"[dim - 1]
    margin = layers * p.dp
    domain_lo = tuple(a - margin for a in tank_lo)
    domain_hi = tuple(a + margin for a in tank_hi[:-1]) + (max(tank_hi[-1], hi[-1] + height),)
    gravity = (0.0,) * (dim - 1) + (-p.g,)
    return Case(
        dim=dim,
        domain=(domain_lo, domain_hi),
        dp=p.dp,
        material=soil,
        **scheme_choice(p),
        bodies=[Body(name, block(lo, hi, p.dp, f"the {name}"),
                     stress=lambda x: geostatic_stress(x, top, soil, p.g, k_lateral, p.initial_stress, lo[-1]))],
        walls=[Wall("tank", walls_around(tank_lo, tank_hi, p.dp, layers, open_sides=(up,)), slip=slip,
                    distance=depth_outside(tank_lo, tank_hi))],
        gravity=gravity,
        stabilisers=p.stabiliser,
        density_reinit=p.density_reinit,
        u_ref=float(np.sqrt(2.0 * p.g * height)),
        warnings=[w for w in (lattice_mismatch(f"the {name}'s {'xyz'[a]} side", hi[a] - lo[a], p.dp)
                              for a in range(dim)) if w],
        **records,
    )
