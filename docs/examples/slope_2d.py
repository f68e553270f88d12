"""A cohesive-frictional slope: the worked example of docs/YOUR_CASE.md, a case of your own.

A 2D slope H high at the angle beta between a crest and a toe region, on a foundation layer D
deep, in a tank of no-slip dummy walls open at the top; Drucker-Prager soil (the Riemann scheme of
000_ with UTVF) at rest under its own sloping surface at t = 0. It records the displacement of the
crest's and the toe's particles, the force and moment of the soil on the back wall (with its corner
block under the floor), the velocity
and plastic strain along a line under the slope's face (by half the smaller of H and D, so that it
stays in the soil), and the ground's profile.

    .venv/bin/python -m mpisph docs/examples/slope_2d.py --set beta=60 cohesion=2e3 --t-end 3
"""

import math

import numpy as np

from mpisph.case import Body, Case, Param, Wall
from mpisph.gauges import Gauge, SurfaceGauge
from mpisph.geometry import along, block, depth_outside, support_layers, walls_around
from mpisph.physics.drucker_prager import geostatic_stress
from mpisph.soil import drucker_prager, scheme_choice, scheme_params, soil_params

PARAMS = {
    "H": Param(2.0, "m", "height of the slope above the foundation", positive=True),
    "D": Param(1.0, "m", "depth of the foundation layer", positive=True),
    "crest": Param(2.0, "m", "width of the crest", positive=True),
    "beta": Param(45.0, "deg", "angle of the slope's face", bounds=(5.0, 90.0)),
    "dp": Param(0.1, "m", "particle spacing", positive=True),
    **soil_params(rho0=1800.0, E=10e6, nu=0.3, cohesion=4e3, phi=20.0),
    **scheme_params(),
    "t_end": Param(2.0, "s", "simulated end time", positive=True),
    "output_interval": Param(0.1, "s", "simulated time between frames", positive=True),
}


def setup(p):
    soil = drucker_prager(p)
    run = p.H / math.tan(math.radians(p.beta))  # the face's horizontal extent
    length = p.crest + run + 2.0 * p.H  # crest, face and a toe region
    top = p.D + p.H
    below = 0.5 * min(p.H, p.D)  # the face gauge's depth under the face

    def ground(x):
        """The ground surface's height above each position: the crest, the face, the toe region."""
        return np.clip(top - (x[:, 0] - p.crest) * math.tan(math.radians(p.beta)), p.D, top)

    def below_ground(x):
        return x[:, 1] < ground(x)

    layers = support_layers(p.h_factor)
    margin = layers * p.dp
    return Case(
        dim=2,
        domain=((-margin, -margin), (length + margin, 2.0 * top)),
        dp=p.dp,
        material=soil,
        **scheme_choice(p),
        bodies=[Body("soil", block((0.0, 0.0), (length, top), p.dp, "the slope", keep=below_ground),
                     stress=lambda x: geostatic_stress(x, ground, soil, p.g, None, p.initial_stress))],
        walls=[Wall("back", block((-margin, -margin), (0.0, 2.0 * top), p.dp, "the back wall", normal=along(0)),
                    distance=lambda x: -x[:, 0]),
               Wall("tank", walls_around((0.0, 0.0), (length, 2.0 * top), p.dp, layers, open_sides=("+y", "-x")),
                    distance=depth_outside((0.0, 0.0), (length, 2.0 * top)))],
        gravity=(0.0, -p.g),
        stabilisers=p.stabiliser,
        density_reinit=p.density_reinit,
        u_ref=math.sqrt(2.0 * p.g * top),
        probes={"crest": (p.crest, top), "toe": (p.crest + run, p.D)},
        wall_forces={"back": (0.0, 0.0)},  # and its moment about the back wall's foot
        gauges=[Gauge.line("face", (p.crest, top - below), (p.crest + run, p.D - below), 11,
                           fields=("v", "plastic_strain")),
                SurfaceGauge("profile", np.linspace(0.5 * p.dp, length - 0.5 * p.dp, 40)[:, None])],
    )
