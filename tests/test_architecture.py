"""The engine knows no physics: importing the step loop loads no module of mpisph.physics, and
the parts a case names are found by name, not by the type of its material."""

import subprocess
import sys

from mpisph.integrators import INTEGRATORS
from mpisph.schemes import SCHEMES
from mpisph.stabilisers import STABILISERS, stabiliser_names


def test_solver_imports_no_physics():
    code = ("import sys, mpisph.solver; "
            "print(sorted(m for m in sys.modules if m.startswith('mpisph.physics')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_registries_are_keyed_by_their_parts_names():
    for registry in (SCHEMES, STABILISERS, INTEGRATORS):
        assert registry and all(cls.name == name for name, cls in registry.items())


def test_stabiliser_lists():
    assert stabiliser_names("none") == ()
    assert stabiliser_names("utvf") == ("utvf",)
    assert stabiliser_names("artificial_stress + utvf") == ("artificial_stress", "utvf")


def test_solver_loads_no_analysis():
    """The measures of frames (mpisph.measure) are analysis: the step loop does not load them."""
    code = "import sys, mpisph.solver; print('mpisph.measure' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"
