"""A force term declared by a case (tests/cases/pushed_square.py) reaches the particles through
the documented route (docs/ARCHITECTURE.md), on 1 and 2 ranks alike, as does the run parameter
``damping``; and the order of the sum."""

from pathlib import Path

import numpy as np
import pytest

from mpisph.forces import Forces, ForceTerm, Gravity
from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import list_frames, read_frame
from mpirun import runs_on

pytestmark = pytest.mark.ranks  # tests/conftest.py

CASE = str(Path(__file__).parent / "cases" / "pushed_square.py")


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    return runs_on(tmp_path_factory, "pushed", CASE, [])


@pytest.mark.parametrize("ranks", [1, 2])
def test_particles_feel_the_case_force(runs, ranks):
    """Internal forces cancel in pairs: the momentum is M a t and the centre of mass moves a t^2 / 2."""
    diag = read_diagnostics(runs[ranks] / "diagnostics.csv")
    t, mass = diag["t"][-1], diag["mass"][-1]
    assert t == pytest.approx(0.05)
    assert diag["momentum_x"][-1] == pytest.approx(mass * 2.0 * t, rel=1e-9)
    assert diag["momentum_y"][-1] == pytest.approx(mass * -1.0 * t, rel=1e-9)
    first, last = (read_frame(f) for f in list_frames(runs[ranks])[::len(list_frames(runs[ranks])) - 1])
    shift = last["x"].mean(axis=0) - first["x"].mean(axis=0)
    np.testing.assert_allclose(shift, 0.5 * np.array([2.0, -1.0]) * t**2, rtol=1e-6)


@pytest.fixture(scope="module")
def damped(tmp_path_factory):
    return runs_on(tmp_path_factory, "damped", CASE, ["--set", "damping=20"])


@pytest.mark.parametrize("ranks", [1, 2])
def test_the_velocity_damping_relaxes_the_momentum_to_its_terminal_value(damped, ranks):
    """With the run parameter damping = c (forces.VelocityDamping) the pushed square's momentum obeys
    dP/dt = M a - c P, internal forces cancelling: P = M a (1 - exp(-c t)) / c, here c t = 1 at the
    end. The kick takes the damping at the step's start velocity, first order in time: its relative
    error is about c dt / 2 (0.74 % at the first row, c dt = 0.013, where the recursion
    v += dt (a - c v) at the run's mean step gives 0.63 %)."""
    diag = read_diagnostics(damped[ranks] / "diagnostics.csv")
    t, mass, c = diag["t"], diag["mass"][-1], 20.0
    bound = c * diag["dt"].max() / 2 * 1.2
    for name, a in (("momentum_x", 2.0), ("momentum_y", -1.0)):
        exact = mass * a * (1.0 - np.exp(-c * t[1:])) / c
        error = diag[name][1:] / exact - 1.0
        assert np.all(error > 0.0) and np.all(error < bound), (name, error, bound)  # damped late, not more
        assert error[-1] < error[0]  # and the error falls as the momentum nears its terminal value


def test_same_bits_on_two_ranks_with_damping(damped):
    one, two = (read_frame(list_frames(damped[r])[-1]) for r in (1, 2))
    for name in ("x", "v", "rho", "p"):
        np.testing.assert_array_equal(one[name], two[name], err_msg=name)


def test_same_bits_on_two_ranks(runs):
    one, two = (read_frame(list_frames(runs[r])[-1]) for r in (1, 2))
    for name in ("x", "v", "rho", "p"):
        np.testing.assert_array_equal(one[name], two[name], err_msg=name)


class _Record(ForceTerm):
    """Appends its name to a log when summed."""

    def __init__(self, name, log, frozen=False, uniform=False):
        self.name, self.log, self.frozen, self.uniform = name, log, frozen, uniform

    def add(self, ctx, acc):
        self.log.append(self.name)


def test_frozen_terms_go_first_and_uniform_ones_need_no_field():
    log = []
    varying = Forces([Gravity((0.0, -9.81)), _Record("pressure", log), _Record("viscosity", log, frozen=True)])
    assert [t.name for t in varying.per_configuration] == ["gravity", "viscosity"]
    assert [t.name for t in varying.per_step] == ["pressure"]
    assert [f.name for f in varying.fields] == ["prior"]
    uniform = Forces([Gravity((0.0, -9.81)), _Record("stress", log), _Record("body", log, frozen=True, uniform=True)])
    assert uniform.per_configuration == () and uniform.fields == ()
    assert [t.name for t in uniform.per_step] == ["gravity", "body", "stress"]
