"""Oscillating cantilever beam: elastic plate clamped at its root, released with a bending-mode velocity (000_ Sec. 4.3).

H_over_dp defaults to 20; 000_ Table 1 runs 30 and its Figs. 11 and 13 run 10 (``--set H_over_dp=...``).
"""

import numpy as np

from mpisph.case import POISSON, SOLID_PARAMS, Body, Case, ElasticSolid, Param, classic_viscosity_params, scheme_keywords
from mpisph.geometry import box, support_layers

KL = 1.875  # first root of cos(kL) cosh(kL) = -1

PARAMS = {
    "L": Param(0.2, "m", "free length of the beam", positive=True),
    "H": Param(0.02, "m", "thickness of the beam", positive=True),
    "H_over_dp": Param(20, "-", "particles across the thickness (dp = H / H_over_dp)", positive=True),
    "rho0": Param(1000.0, "kg/m^3", "density", positive=True),
    "E": Param(2.0e6, "Pa", "Young's modulus", positive=True),
    "nu": Param(0.3975, "-", "Poisson's ratio", positive=True, bounds=POISSON),
    "v_f": Param(0.05, "-", "initial tip speed over the sound speed (000_ Eq. 45)", positive=True),
    "shear_force": Param("corrected", "-", "the shear part of the momentum sum: B-corrected (conserves kinetic "
                         "+ strain energy, physics/solid.py) or as_printed (000_ Eq. 22)",
                         choices=("corrected", "as_printed")),
    "scheme": Param("riemann_elastic", "-", "riemann_elastic: 000_ Sec. 3.1.2; classic_elastic: the classic SPH of "
                    "Gray, Monaghan & Swift 2001 (artificial viscosity, predictor-corrector), whose artificial "
                    "stress is 000_'s SPH-AS", choices=("riemann_elastic", "classic_elastic")),
    **classic_viscosity_params(1.0, 1.0, "classic_elastic"),
    **SOLID_PARAMS,
    "t_end": Param(1.0, "s", "simulated end time", positive=True),
    "output_interval": Param(0.02, "s", "simulated time between frames", positive=True),
    "diagnostics_every": Param(5, "steps", "advection steps between rows of diagnostics.csv", positive=True),
}


def mode_shape(x, L):
    """f(x) of 000_ Eq. 46 for the first bending mode."""
    k = KL / L
    return ((np.sin(KL) + np.sinh(KL)) * (np.cos(k * x) - np.cosh(k * x))
            - (np.cos(KL) + np.cosh(KL)) * (np.sin(k * x) - np.sinh(k * x)))


def setup(p):
    dp = p.H / p.H_over_dp
    # The root is held as in the paper's set-up (Fig. 10, after Gray et al. 2001):
    # the beam continues into a clamp that also covers it above and below, so the
    # particles at the root see full, fixed support; one kernel support of layers is
    # enough, as clamped particles farther away never reach the free beam.
    grip = support_layers(p.h_factor) * dp
    half = p.H / 2
    x = np.concatenate([
        box((-grip, -half), (p.L, half), dp, "the beam"),
        box((-grip, half), (0.0, half + grip), dp, "the clamp"),
        box((-grip, -half - grip), (0.0, -half), dp, "the clamp"),
    ])
    material = ElasticSolid(rho0=p.rho0, E=p.E, nu=p.nu)
    free = x[:, 0] > 0.0
    velocity = np.zeros_like(x)
    velocity[free, 1] = p.v_f * material.c0 * mode_shape(x[free, 0], p.L) / mode_shape(p.L, p.L)
    tip = int(np.argmin(np.hypot(x[:, 0] - p.L, x[:, 1])))
    return Case(
        dim=2,
        domain=((-grip - p.L, -p.L), (2 * p.L, p.L)),
        dp=dp,
        material=material,
        **scheme_keywords(p, {}, {"shear_force": p.shear_force}),
        bodies=[Body("beam", x, velocity=velocity, clamped=~free)],
        stabilisers=p.stabiliser,
        probes={"tip": tip},
    )
