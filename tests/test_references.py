"""The reference solutions reproduce the figures the engine issue quotes."""

import importlib.util

import numpy as np
import pytest

from mpisph import references
from mpisph.case import CASES_DIR


def test_elliptical_drop_semi_axes():
    (a, inv_a), (_, inv_a_early) = references.elliptical_drop_axes([0.0076, 0.004])
    assert a == pytest.approx(0.514266, abs=1e-6)
    assert inv_a == pytest.approx(1.944517, abs=1e-6)
    assert inv_a_early == pytest.approx(1.464774, abs=1e-6)


def test_taylor_green_decay():
    rate = references.taylor_green_energy_rate(100.0)
    assert rate == pytest.approx(-1.5791, abs=1e-4)
    assert np.exp(rate) == pytest.approx(0.20615, abs=1e-5)


def test_rotating_square_centre_pressure_from_eq44():
    spec = importlib.util.spec_from_file_location("rsp", CASES_DIR / "rotating_square_patch.py")
    case = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(case)
    p = case.initial_pressure(np.zeros(1), np.zeros(1), 1.0, 1.0, 1.0, 100)[0]
    assert p == pytest.approx(references.ROTATING_SQUARE_CENTRE_PRESSURE, abs=1e-6)


def test_beam_period():
    from mpisph.references import beam_period
    assert beam_period() == pytest.approx(0.2541, abs=5e-5)


def test_earth_pressure_on_a_wall():
    """phi = 30 degrees: K_a = 1/3, K_p = 3, Jaky's K_0 = 1/2; without cohesion the force is K gamma H^2 / 2;
    with it the active pressure vanishes above the tension crack at 2 c / (gamma sqrt(K_a))."""
    states = references.earth_pressure(30.0, 0.0)
    assert states["active"][0] == pytest.approx(1 / 3) and states["passive"][0] == pytest.approx(3.0)
    assert states["at rest"] == (pytest.approx(0.5), 0.0)
    assert references.lateral_earth_force(states["at rest"], 20.0, 0.0, 2.0, 1.5) == pytest.approx(0.5 * 20 * 4 / 2 * 1.5)
    active, passive = (references.earth_pressure(30.0, 10.0)[s] for s in ("active", "passive"))
    crack = 2 * 10.0 / (20.0 * np.sqrt(1 / 3))
    assert active[1] == pytest.approx(-20 / np.sqrt(3))
    assert references.lateral_earth_force(active, 20.0, 0.0, 0.9 * crack, 1.0) == 0.0
    H = 3.0
    assert references.lateral_earth_force(active, 20.0, 0.0, H, 1.0) == pytest.approx(0.5 / 3 * 20.0 * (H - crack) ** 2)
    assert references.lateral_earth_force(passive, 20.0, 1.0, H, 2.0) == pytest.approx(
        2.0 * (0.5 * 3 * 20 * (H**2 - 1) + 2 * 10 * np.sqrt(3) * (H - 1)))
