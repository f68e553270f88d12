"""The inclined plane with the force of the layer on its bed recorded, and a barrier load declared on
the bed: the bed's shear over the momentum flux of the layer through a vertical gauge line, which
also samples the stress (tests/test_wall_forces.py)."""

from mpisph.barrier_load import BarrierLoad
from mpisph.case import load_case_module
from mpisph.gauges import Gauge, SurfaceGauge

_incline = load_case_module("inclined_plane")

PARAMS = _incline.PARAMS


def setup(p):
    case = _incline.setup(p)
    middle = 0.5 * p.columns * p.dp
    case.wall_forces = {"bed": (0.0, 0.0)}
    case.gauges = [Gauge.line("line", (middle, 0.5 * p.dp), (middle, 1.5 * p.H), 16, fields=("v", "stress")),
                   SurfaceGauge("top", [[middle]])]
    case.barrier_loads = [BarrierLoad("bed", "line", "top", width=1.0, density=p.rho_s0)]
    return case
