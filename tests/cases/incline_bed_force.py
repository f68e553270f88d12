"""The inclined plane with the force of the layer on its bed recorded (tests/test_wall_forces.py)."""

from mpisph.case import load_case_module

_incline = load_case_module("inclined_plane")

PARAMS = _incline.PARAMS


def setup(p):
    case = _incline.setup(p)
    case.wall_forces = {"bed": (0.0, 0.0)}
    return case
