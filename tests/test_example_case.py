"""docs/YOUR_CASE.md's worked example, docs/examples/slope_2d.py, runs by its path on two ranks: a
slope cut from a block by a function of position, at rest under its sloping ground, against a back
wall that carries the at-rest thrust; its probes, given by position, and its gauges are recorded."""

import math
from pathlib import Path

import pytest

from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import list_frames, read_frame
from mpirun import mpisph

pytestmark = pytest.mark.ranks  # tests/conftest.py

EXAMPLE = Path(__file__).resolve().parent.parent / "docs" / "examples" / "slope_2d.py"


def test_the_worked_example_runs_and_its_back_wall_carries_the_at_rest_thrust(tmp_path):
    r = mpisph([EXAMPLE, "--t-end", "0.02", "--output-interval", "0.01", "--out", tmp_path, "--quiet"], ranks=2)
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""  # no warning: the example's sides are whole spacings, its angles degrees
    d = read_diagnostics(tmp_path / "diagnostics.csv")
    first = read_frame(list_frames(tmp_path)[0])
    p = first["params"]
    k0 = 1.0 - math.sin(math.radians(p["phi"]))
    thrust = 0.5 * k0 * p["rho0"] * p["g"] * (p["H"] + p["D"]) ** 2  # 52.2 kN/m
    # the sum of the back wall's pair forces at t = 0: 50.9 kN/m here, the rows' stress at their
    # centres and the kernel's reach into the wall (the tolerance is that discretisation's, 2.5 %)
    assert -d["force_back_x"][0] == pytest.approx(thrust, rel=0.05)
    assert {"crest_ux", "crest_uy", "toe_ux", "toe_uy"} <= set(d)
    assert d["crest_uy"][0] == 0.0 and abs(d["crest_uy"][-1]) < 0.01 * p["dp"]  # at rest, settling
    points = (tmp_path / "gauge_face_points.csv").read_text().splitlines()
    assert points[0] == "point,x,y" and points[1] == "p0,2.0,2.5" and len(points) == 12
    assert "p0_plastic_strain" in read_diagnostics(tmp_path / "gauge_face.csv")
