"""Forces on named walls (mpisph/wall_forces.py): the force of a flowing mu(I) layer on its bed
closes the momentum balance of the layer, d(P_x)/dt = M g sin(theta) - F_x, and carries its weight,
F_y = -M g cos(theta), with the viscous step explicit and implicit (where the wall force sums the
viscous term explicitly); a wall name the case does not have is a one-line error. The still-water
tank's force and moment are in tests/test_gauges.py."""

from pathlib import Path

import numpy as np
import pytest

from mpisph.io.diagnostics import read_diagnostics
from mpirun import mpisph

CASE = str(Path(__file__).parent / "cases" / "incline_bed_force.py")


@pytest.mark.parametrize("step", ["explicit", "implicit"])
def test_bed_force_closes_the_momentum_balance_of_the_layer(tmp_path, step):
    r = mpisph([CASE, "--set", "H=0.02", "dp=0.002", "columns=8", "m_0=0.2", f"viscous_step={step}",
                "diagnostics_every=20", "--t-end", "0.3", "--output-interval", "0.3", "--out", tmp_path, "--quiet"],
               ranks=2, timeout=600)
    assert r.returncode == 0, r.stderr
    d = read_diagnostics(tmp_path / "diagnostics.csv")
    mass, g, theta = d["mass"][-1], 9.81, np.radians(25.0)
    settled = d["t"] > 0.05  # after the start's pressure waves
    drive = mass * g * np.sin(theta) - np.gradient(d["momentum_x"], d["t"])
    shear = d["force_bed_x"][settled][:-1] / drive[settled][:-1]  # the one-sided difference at the end left out
    assert np.median(shear) == pytest.approx(1.0, abs=0.002)
    assert np.all(np.abs(shear - 1.0) < 0.02)
    normal = d["force_bed_y"][settled] / (-mass * g * np.cos(theta))
    assert normal.mean() == pytest.approx(1.0, abs=0.005)
    assert np.all(np.abs(normal - 1.0) < 0.03)


def test_unknown_wall_is_an_input_error():
    """(An InputError is the command line's one-line error, tests/test_cli_errors.py.)"""
    from mpisph.case import build_case, load_case_module, resolve_params
    from mpisph.errors import InputError

    module = load_case_module(CASE)
    case = build_case(module, resolve_params(module, {"H": "0.02", "dp": "0.002", "columns": "8"}))
    case.wall_forces = {"barrier": (0.0, 0.0)}
    with pytest.raises(InputError, match="^wall_forces names 'barrier': the walls are 'bed'$"):
        case.validate(0.0052)
