"""Gauges (mpisph/gauges.py) on still water: the samples along a vertical line are the Shepard
interpolation of the last frame's particles, the pressure is near hydrostatic, the kernel sum is 1
in the water and 0 above it (where the fields are nan), the water's top is its depth; 1 and 2 ranks
give the same samples (to round-off: sums over ranks) and the same tops (a maximum: exactly). The
water's force on its tank (wall_forces.py) is its weight, and its moment about the tank's corner
that of the weight at mid-width (the side walls' moments cancel)."""

import math
from pathlib import Path

import numpy as np
import pytest

from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import list_frames, read_frame
from mpisph.kernels import Kernel
from mpirun import runs_on

pytestmark = pytest.mark.ranks  # tests/conftest.py

CASE = str(Path(__file__).parent / "cases" / "gauged_tank.py")


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """{ranks: (gauge_column.csv, gauge_surface.csv, diagnostics.csv, last frame)} on 1 and 2 ranks."""
    dirs = runs_on(tmp_path_factory, "gauged", CASE, ["--set", "dp=0.025", "--t-end", "0.3", "--output-interval",
                                                      "0.3"])
    out = {n: (read_diagnostics(d / "gauge_column.csv"), read_diagnostics(d / "gauge_surface.csv"),
               read_diagnostics(d / "diagnostics.csv"), read_frame(list_frames(d)[-1]),
               read_diagnostics(d / "gauge_grid.csv")) for n, d in dirs.items()}
    out["dirs"] = dirs
    return out


def test_each_gauge_writes_its_points_positions(runs):
    """gauge_<name>_points.csv: a row per point (p0, p1, ...) or station (s0, ...) with its
    coordinates, so that the columns p<i>_... can be placed without the case file."""
    column = (runs["dirs"][1] / "gauge_column_points.csv").read_text().splitlines()
    assert column[0] == "point,x,y"
    rows = [line.split(",") for line in column[1:]]
    assert [r[0] for r in rows] == [f"p{i}" for i in range(15)]
    np.testing.assert_allclose(np.array([r[1:] for r in rows], float),
                               np.column_stack([np.full(15, 0.5), np.linspace(0.05, 0.75, 15)]), rtol=1e-15)
    surface = (runs["dirs"][1] / "gauge_surface_points.csv").read_text().splitlines()
    assert surface == ["point,x", "s0,0.25", "s1,0.5", "s2,0.75"]


def test_gauges_sample_still_water(runs):
    column, surface, diag, frame, _ = runs[1]
    np.testing.assert_array_equal(column["t"], diag["t"])  # one row per row of diagnostics.csv
    assert column["t"][-1] == frame["t"]
    depth, rho0, g = 0.5, 1000.0, 9.81
    points = np.column_stack([np.full(15, 0.5), np.linspace(0.05, 0.75, 15)])
    kernel = Kernel("wendland_c2", frame["params"]["h_factor"] * 0.025, 2)
    r = np.linalg.norm(points[:, None, :] - frame["x"][None, :, :], axis=2)
    wv = kernel.value(r) * frame["mass"] / frame["rho"]
    last = {k: v[-1] for k, v in column.items()}
    for i, z in enumerate(points[:, 1]):
        s = last[f"p{i}_kernel_sum"]
        assert s == pytest.approx(wv[i].sum(), rel=1e-12, abs=1e-15)
        if s > 0:
            assert last[f"p{i}_p"] == pytest.approx(wv[i] @ frame["p"] / s, rel=1e-12)
            assert last[f"p{i}_vx"] == pytest.approx(wv[i] @ frame["v"][:, 0] / s, rel=1e-9, abs=1e-12)
        if z < depth - 0.1:  # a kernel support below the surface
            assert s == pytest.approx(1.0, abs=0.03)
            assert last[f"p{i}_p"] == pytest.approx(rho0 * g * (depth - z), rel=0.1)
        elif z > depth + 0.1:
            assert s == 0.0 and math.isnan(last[f"p{i}_p"])
    for k in range(3):
        assert surface[f"s{k}_top"][-1] == pytest.approx(depth, abs=0.025)


def test_a_plane_gauge_samples_its_grid(runs):
    """Gauge.plane over the rectangle x in [0.25, 0.75] m, z in [0.05, 0.35] m of the water, 3 x 4
    points (the first direction outer): each point's sample is the Shepard interpolation at
    corner + a u + b v, near hydrostatic at its depth."""
    *_, frame, grid = runs[1]
    a, b = np.meshgrid(np.linspace(0.0, 1.0, 3), np.linspace(0.0, 1.0, 4), indexing="ij")
    points = np.column_stack([0.25 + 0.5 * a.ravel(), 0.05 + 0.3 * b.ravel()])
    kernel = Kernel("wendland_c2", frame["params"]["h_factor"] * 0.025, 2)
    r = np.linalg.norm(points[:, None, :] - frame["x"][None, :, :], axis=2)
    wv = kernel.value(r) * frame["mass"] / frame["rho"]
    assert [k for k in grid if k.endswith("_p")] == [f"p{i}_p" for i in range(12)]
    for i, (x, z) in enumerate(points):
        assert grid[f"p{i}_kernel_sum"][-1] == pytest.approx(wv[i].sum(), rel=1e-12)
        assert grid[f"p{i}_p"][-1] == pytest.approx(wv[i] @ frame["p"] / wv[i].sum(), rel=1e-12)
        assert grid[f"p{i}_p"][-1] == pytest.approx(1000.0 * 9.81 * (0.5 - z), rel=0.1)


def test_gauges_on_two_ranks(runs):
    (c1, s1, _, _, _), (c2, s2, _, _, _) = runs[1], runs[2]
    assert list(c1) == list(c2)
    def field(name):  # p0_vx -> v: the velocity's components share one scale
        f = name.split("_", 1)[-1]
        return "v" if f in ("vx", "vy") else f

    scale = {}
    for name in c1:
        scale[field(name)] = max(scale.get(field(name), 0.0), np.nanmax(np.abs(c1[name]), initial=0.0))
    for name in c1:  # to round-off of the field's scale: the ranks sum the samples in other orders
        np.testing.assert_allclose(c2[name], c1[name], rtol=1e-9, atol=1e-9 * scale[field(name)], equal_nan=True,
                                   err_msg=name)
    for name in s1:
        np.testing.assert_array_equal(s2[name], s1[name])


def test_force_of_still_water_on_its_tank(runs):
    (_, _, one, _, _), (_, _, two, _, _) = runs[1], runs[2]
    weight = one["mass"][-1] * 9.81
    assert np.all(np.abs(one["force_tank_x"]) < 1e-9 * weight)
    assert one["force_tank_y"][1:].mean() == pytest.approx(-weight, rel=0.01)  # the water oscillates by a few %
    np.testing.assert_allclose(one["moment_tank_z"], 0.5 * one["force_tank_y"], rtol=0.002)  # width 1 m
    for name in ("force_tank_y", "moment_tank_z"):
        np.testing.assert_allclose(two[name], one[name], rtol=1e-9, err_msg=name)
