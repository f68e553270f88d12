"""Forces on named walls (mpisph/wall_forces.py): the force of a flowing mu(I) layer on its bed
closes the momentum balance of the layer, d(P_x)/dt = M g sin(theta) - F_x, and carries its weight,
F_y = -M g cos(theta), with the viscous step explicit and implicit (where the wall force sums the
viscous term explicitly), as the normal stress of a gauge line across it (the frames' stress) does;
the barrier load declared on the bed puts each row's force over the
momentum flux its gauges measure in the same row; a wall name the case does not have is a
one-line error, and so is a barrier load without its wall force or gauges. The still-water
tank's force and moment are in tests/test_gauges.py."""

from pathlib import Path

import numpy as np
import pytest

from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import list_frames, read_frame
from mpisph.barrier_load import depth_averaged
from mpirun import mpisph

CASE = str(Path(__file__).parent / "cases" / "incline_bed_force.py")


@pytest.mark.parametrize("step, ranks", [("explicit", 1), pytest.param("implicit", 2, marks=pytest.mark.ranks)])
def test_bed_force_closes_the_momentum_balance_of_the_layer(tmp_path, step, ranks):
    r = mpisph([CASE, "--set", "H=0.02", "dp=0.002", "columns=8", "m_0=0.2", f"viscous_step={step}",
                "diagnostics_every=20", "--t-end", "0.3", "--output-interval", "0.3", "--out", tmp_path, "--quiet"],
               ranks=ranks, timeout=600)
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
    # the barrier load declared on the bed: each row's alpha is that row's bed force over rho v^2 h w,
    # v and h from the same row of the gauges (barrier_load.py)
    line, top = (read_diagnostics(tmp_path / f"gauge_{name}.csv") for name in ("line", "top"))
    np.testing.assert_array_equal(line["t"], d["t"])
    points = range(16)
    v = depth_averaged(np.column_stack([line[f"p{i}_vx"] for i in points]),
                       np.column_stack([line[f"p{i}_kernel_sum"] for i in points]))
    np.testing.assert_array_equal(d["approach_speed_bed"], v)
    np.testing.assert_array_equal(d["approach_depth_bed"], top["s0_top"])
    moving = v > 0
    assert moving[-1] and d["approach_depth_bed"][-1] == pytest.approx(0.02, abs=0.002)
    np.testing.assert_allclose(d["alpha_bed"][moving],
                               d["force_bed_x"][moving] / (800.0 * v[moving] ** 2 * top["s0_top"][moving]),
                               rtol=1e-12)
    # the line gauge's stress (the frames' stress of physics/mu_i_stress.py): at the end its normal
    # stress across the layer grows with depth as the weight, rho g cos(theta), inside the material
    inside = [i for i in points if abs(line[f"p{i}_kernel_sum"][-1] - 1.0) < 0.02]
    y = np.loadtxt(tmp_path / "gauge_line_points.csv", delimiter=",", skiprows=1, usecols=2)[inside]
    sigma_yy = np.array([line[f"p{i}_stress_yy"][-1] for i in inside])
    rho = read_frame(list_frames(tmp_path)[-1])["rho"].mean()
    assert len(inside) >= 6
    assert np.polyfit(y, sigma_yy, 1)[0] == pytest.approx(rho * g * np.cos(theta), rel=0.02)


def test_unknown_wall_is_an_input_error():
    """(An InputError is the command line's one-line error, tests/test_cli_errors.py.)"""
    from mpisph.case import build_case, load_case_module, resolve_params
    from mpisph.errors import InputError

    module = load_case_module(CASE)
    case = build_case(module, resolve_params(module, {"H": "0.02", "dp": "0.002", "columns": "8"}))
    case.wall_forces = {"barrier": (0.0, 0.0)}
    with pytest.raises(InputError, match="^wall_forces names 'barrier': the walls are 'bed'$"):
        case.validate(0.0052)


@pytest.mark.parametrize("change, message", [
    ({"wall": "barrier"}, "barrier load on 'barrier': the case records no force on that wall"),
    ({"approach": "top"}, "barrier load on 'bed': 'top' is not a gauge that samples v"),
    ({"top": "line"}, "barrier load on 'bed': 'line' is not a surface gauge"),
    ({"width": 0.0}, "barrier load on 'bed': width and density must be positive"),
])
def test_a_barrier_load_without_its_force_or_gauges_is_an_input_error(change, message):
    import dataclasses

    from mpisph.case import build_case, load_case_module, resolve_params
    from mpisph.errors import InputError

    module = load_case_module(CASE)
    case = build_case(module, resolve_params(module, {"H": "0.02", "dp": "0.002", "columns": "8"}))
    case.barrier_loads = [dataclasses.replace(case.barrier_loads[0], **change)]
    with pytest.raises(InputError, match="^" + message):
        case.validate(0.0052)
