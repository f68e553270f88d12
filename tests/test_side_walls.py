"""The side walls' Coulomb friction on a plane-strain granular flow (physics/side_walls.py): the
acceleration of one particle by hand, a sheet on a free-slip floor (the case sliding_sheet) that
loses to the walls exactly the momentum their friction takes, of the grains' pressure or, with
law_pressure = carried_mean, of the law's."""

import math
from types import SimpleNamespace
import numpy as np
import pytest

from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import list_frames, read_frame
from mpisph.particles import MOVING, WALL
from mpisph.physics.side_walls import SideWallFriction, add_side_wall_friction
from mpirun import mpisph, stderr_lines

SHEET = ["sliding_sheet", "--t-end", "0.02", "--set", "floor=free_slip", "columns=8"]  # --set words follow
RATE = 2.0 * 0.4 / 0.1  # 2 mu_w / W


def friction(v, p=500.0, rho=1500.0, kind=MOVING, v_reg=0.01, dt=1e-4):
    acc = np.zeros((1, 2))
    add_side_wall_friction(1, np.array([kind]), np.array([v], dtype=float), np.array([p]), np.array([rho]),
                           RATE, v_reg, dt, acc)
    return acc[0]


def test_above_the_regularising_speed_it_is_coulombs_law_against_the_motion():
    np.testing.assert_allclose(friction([0.3, -0.4]), -RATE * 500.0 / 1500.0 * np.array([0.6, -0.8]), rtol=1e-14)


def test_below_the_regularising_speed_it_falls_linearly_to_zero():
    slow = np.array([0.003, 0.004])  # |v| = v_reg / 2
    np.testing.assert_allclose(friction(slow), -RATE * 500.0 / 1500.0 * slow / 0.01, rtol=1e-14)
    np.testing.assert_array_equal(friction([0.0, 0.0]), [0.0, 0.0])


def test_a_step_never_reverses_the_motion():
    """Where the friction would take more than the speed in one step (F dt > |v|, v_reg), it is a
    drag of rate 1 / dt: a kick of dt brings the particle to rest, not past it."""
    v, dt = np.array([0.003, -0.004]), 0.05  # F dt = 2.67 m/s^2 x 0.05 s = 0.13 m/s > |v| = 0.005 m/s
    np.testing.assert_allclose(v + dt * friction(v, dt=dt), [0.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(friction(v, dt=dt), -v / dt, rtol=1e-14)


def test_the_term_takes_the_laws_pressure_and_the_advection_step():
    """SideWallFriction.add on particles with and without the field law_pressure, and with an
    advection step long enough that the friction would take more than the speed in one step."""
    slow = np.array([[0.003, -0.004]])

    def add(arrays, advection_step):
        particles = SimpleNamespace(n_owned=1, arrays=arrays, **arrays)
        acc = np.zeros((1, 2))
        SideWallFriction(0.1, 0.4, 0.01).add(SimpleNamespace(particles=particles, advection_step=advection_step), acc)
        return acc[0]

    arrays = dict(kind=np.array([MOVING]), v=slow, p=np.array([500.0]), rho=np.array([1500.0]))
    np.testing.assert_allclose(add(arrays, 1e-4), friction(slow[0]), rtol=1e-14)
    np.testing.assert_allclose(add(dict(arrays, law_pressure=np.array([250.0])), 1e-4), friction(slow[0], p=250.0),
                               rtol=1e-14)
    np.testing.assert_allclose(add(arrays, 0.05), -slow[0] / 0.05, rtol=1e-14)


def test_no_friction_in_tension_nor_on_walls():
    np.testing.assert_array_equal(friction([1.0, 0.0], p=-10.0), [0.0, 0.0])
    np.testing.assert_array_equal(friction([1.0, 0.0], kind=WALL), [0.0, 0.0])


@pytest.fixture(scope="module")
def sheets(tmp_path_factory):
    """The sheet without side walls, and between walls its own depth apart (friction angle 20 deg)
    with the law taking the grains' pressure (law_pressure = state) or the kernel mean of the
    carried one (carried_mean)."""
    out = {}
    for width, law in ((0.0, "state"), (0.00972, "state"), (0.00972, "carried_mean")):
        out[width, law] = tmp_path_factory.mktemp(f"sheet_{width}_{law}")
        walls = [f"channel_width={width}", "wall_friction_deg=20"] if width else []  # no friction without walls
        r = mpisph([*SHEET, *walls, f"law_pressure={law}",
                    "--output-interval", "0.001", "--out", out[width, law], "--quiet"], ranks=1)
        assert r.returncode == 0, r.stderr
    return out


def test_without_side_walls_nothing_takes_the_sheets_momentum(sheets):
    momentum = read_diagnostics(sheets[0.0, "state"] / "diagnostics.csv")["momentum_x"]
    np.testing.assert_allclose(momentum, momentum[0], rtol=1e-12)


@pytest.mark.parametrize("law, pressure", [("state", "p"), ("carried_mean", "law_pressure")])
def test_the_walls_take_the_momentum_of_their_friction(sheets, law, pressure):
    """Every grain moves along +x faster than the regularising speed, so the walls take
    2 mu_w / W sum_i V_i p_i per unit time, p the law's pressure: its integral over the frames is the
    momentum lost (the grains' p, 6 % above the carried pressure here, would miss it)."""
    frames = [read_frame(f) for f in list_frames(sheets[0.00972, law])]
    assert all(f["v"][f["kind"] == MOVING, 0].min() > 0.9 for f in frames)
    rate = 2.0 * math.tan(math.radians(20.0)) / 0.00972
    force = [-rate * np.sum((f["mass"] * f[pressure] / f["rho"])[f["kind"] == MOVING]) for f in frames]
    impulse = np.trapezoid(force, [f["t"] for f in frames])
    momentum = read_diagnostics(sheets[0.00972, law] / "diagnostics.csv")["momentum_x"]
    assert momentum[-1] - momentum[0] == pytest.approx(impulse, rel=0.01)
    assert impulse < -0.07 * momentum[0]  # the friction is not negligible: 7 % of the momentum in 0.02 s


@pytest.mark.parametrize("setting, words", [("channel_width=-0.1", "side walls need channel_width > 0"),
                                            ("wall_friction_deg=90", "wall_friction_deg must lie in [0, 90)"),
                                            ("law_pressure=carried", "does not keep"),
                                            ("channel_width=0 wall_friction_deg=20", "give channel_width too")])
def test_bad_side_walls_are_one_line_errors(tmp_path, setting, words):
    sets = {"channel_width": "0.1", **dict(word.split("=") for word in setting.split())}  # a name once
    r = mpisph([*SHEET, *(f"{k}={v}" for k, v in sets.items()), "--out", tmp_path, "--quiet"], ranks=1)
    assert r.returncode == 2
    lines = stderr_lines(r.stderr)
    assert len(lines) == 1 and words in lines[0]
