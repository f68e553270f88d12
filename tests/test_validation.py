"""Fluid cases against their references (000_ Sec. 4.1-4.2, 001_ Sec. 4.1-4.2).

Each test runs the case under mpirun and compares frames or diagnostics with
the closed-form solution or the experiment, with the tolerance the engine
issue states. Runs are bitwise identical on any rank count
(test_rank_agreement.py), so they run on one rank (tests/conftest.py says
why). docs/VALIDATION.md shows the same comparisons as plots
(scripts/validate.py).
"""

import numpy as np
import pytest

from mpisph import measure, references
from mpisph.kernels import Kernel
from mpirun import run


def test_elliptical_drop_semi_axis(tmp_path):
    """dp = 0.02: y semi-axis at t = 0.0076 s within 1.5 % of 1.944517; mass exact."""
    frames, diag = run("elliptical_drop", ["--t-end", "0.0076", "--output-interval", "0.0038"], tmp_path)
    last = frames[-1]
    assert last["t"] == pytest.approx(0.0076)
    _, b = measure.semi_axes(last, 0.02)
    assert b == pytest.approx(1.944517, rel=0.015)
    # every particle keeps its mass exactly; the total changes only by the order of summation
    np.testing.assert_array_equal(last["mass"], frames[0]["mass"])
    np.testing.assert_allclose(diag["mass"], np.sum(frames[0]["mass"]), rtol=1e-13)


def test_rotating_square_patch(tmp_path):
    """The start as 000_ Eq. 44 and the rigid rotation give it (centre pressure within 1 %, angular
    momentum -rho omega L^4 / 6); to t omega = 2 angular momentum drifts by at most 1 % and the
    kinetic energy, which the inviscid incompressible patch keeps, falls by at most 5 % (000_ Fig. 9a:
    a few per cent, the Riemann solver's dissipation) and never exceeds its start."""
    frames, diag = run("rotating_square_patch", ["--t-end", "2.0", "--output-interval", "1.0"], tmp_path)
    rho, omega, L = 1000.0, 1.0, 1.0
    p_centre = measure.nearest_value(frames[0], "p", (0.0, 0.0))
    assert p_centre / (rho * omega**2 * L**2) == pytest.approx(references.ROTATING_SQUARE_CENTRE_PRESSURE, rel=0.01)
    ang = diag["angular_momentum_z"]
    assert diag["t"][-1] == pytest.approx(2.0)
    assert abs(ang[-1] / ang[0] - 1.0) <= 0.01
    assert ang[0] == pytest.approx(-rho * omega * L**4 / 6, rel=0.01)
    kinetic = diag["kinetic_energy"]
    assert kinetic[0] == pytest.approx(rho * omega**2 * L**4 / 12, rel=0.01)  # (1/2) I omega^2, I = rho L^4 / 6
    assert np.all(kinetic <= kinetic[0] * (1 + 1e-9)) and kinetic[-1] >= 0.95 * kinetic[0]


def test_lid_driven_cavity_re100(tmp_path):
    """dp = 1/50, Re = 100: RMS error of u and v on the centre lines against Ghia <= 0.03."""
    frames, _ = run("lid_driven_cavity", ["--t-end", "10", "--output-interval", "5"], tmp_path)
    last, kernel = frames[-1], Kernel("wendland_c2", 1.3 / 50, 2)
    y, x = references.GHIA_Y[1:-1], references.GHIA_X[1:-1]
    u = measure.line_average(last, np.stack([np.full_like(y, 0.5), y], 1), 0, kernel)
    v = measure.line_average(last, np.stack([x, np.full_like(x, 0.5)], 1), 1, kernel)
    assert np.sqrt(np.mean((u - references.GHIA_U[1:-1]) ** 2)) <= 0.03
    assert np.sqrt(np.mean((v - references.GHIA_V[1:-1]) ** 2)) <= 0.03


@pytest.fixture(scope="module")
def dam_break_front(tmp_path_factory):
    """(T, front z/L) from one dam-break run to T = 3.19, dp = 0.02 L."""
    frames, _ = run("dam_break_2d", ["--t-end", "0.72", "--output-interval", "0.02"],
                    tmp_path_factory.mktemp("dam_break"))
    return measure.dam_break_fronts(frames)


def test_dam_break_front_within_10_percent_of_koshizuka_and_oka_to_T_1_6(dam_break_front):
    """The front advances monotonically and is within 10 % of Koshizuka & Oka at their T <= 1.6
    (issue 13's settlement of the reference)."""
    T, z = dam_break_front
    assert np.all(np.diff(z) > 0)
    early = references.KOSHIZUKA_T[(references.KOSHIZUKA_T > 0) & (references.KOSHIZUKA_T <= 1.6)]
    assert np.all(np.abs(np.interp(early, T, z) / references.koshizuka_oka_front(early) - 1) <= 0.10)


def test_dam_break_late_front_speed_within_10_percent_of_martin_and_moyce(dam_break_front):
    """dZ/dT over T = 1.9-3.1 within 10 % of Martin & Moyce's (n^2 = 2, a = 2.25 in)."""
    T, z = dam_break_front
    assert T[-1] >= references.MARTIN_MOYCE_SPAN[1]
    speed = measure.front_speed(T, z, *references.MARTIN_MOYCE_SPAN)
    assert speed == pytest.approx(references.martin_moyce_speed(), rel=0.10)


def test_taylor_green_decay_rate(tmp_path):
    """50 x 50, Re = 100: fitted decay rate of the kinetic energy over [0, 1] within 5 % of -1.5791."""
    _, diag = run("taylor_green", ["--set", "diagnostics_every=1", "--t-end", "1.0"], tmp_path)
    rate = measure.decay_rate(diag["t"], diag["kinetic_energy"])
    assert rate == pytest.approx(references.taylor_green_energy_rate(100.0), rel=0.05)
