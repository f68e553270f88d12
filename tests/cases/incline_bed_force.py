"""The inclined plane with the force of the layer on its bed recorded (tests/test_wall_forces.py)."""

import importlib.util
from pathlib import Path

_spec = importlib.util.spec_from_file_location("inclined_plane", Path(__file__).parents[2] / "cases" /
                                               "inclined_plane.py")
_incline = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_incline)

PARAMS = _incline.PARAMS


def setup(p):
    case = _incline.setup(p)
    case.wall_forces = {"bed": (0.0, 0.0)}
    return case
