"""The hydrostatic tank with gauges and the force on its walls (tests/test_gauges.py): a vertical
line of points through the water and above it, the water's top over stations across the tank, a
grid of points over a rectangle in the water, and the force and moment of the water on the tank."""

import numpy as np

from mpisph.case import load_case_module
from mpisph.gauges import Gauge, SurfaceGauge

_tank = load_case_module("hydrostatic_tank")

PARAMS = _tank.PARAMS


def setup(p):
    case = _tank.setup(p)
    case.gauges = [Gauge.line("column", (0.5 * p.width, 0.1 * p.depth), (0.5 * p.width, 1.5 * p.depth), 15,
                              fields=("p", "v")),
                   SurfaceGauge("surface", np.array([[0.25 * p.width], [0.5 * p.width], [0.75 * p.width]])),
                   Gauge.plane("grid", (0.25 * p.width, 0.1 * p.depth), (0.5 * p.width, 0.0), (0.0, 0.6 * p.depth),
                               (3, 4), fields=("p",))]
    case.wall_forces = {"tank": (0.0, 0.0)}  # the moment about the tank's bottom-left corner
    return case
