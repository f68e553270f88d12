"""Lube's sand columns with the mu(I) scheme at CI size (cases lube_collapse_2d and _3d): the
implicit viscous kick follows the explicit step of Eq. 39 through the start of a collapse (either
viscous form), the front is recorded, the 3D column is a cylinder, and bad settings stop with one
line (tests/test_rank_agreement.py runs the planar collapse on 1, 2 and 3 ranks).

The runouts against Lube's laws are scripts/validate.py's (docs/VALIDATION.md): an open gap of
issue 14."""

import math
import re

import numpy as np
import pytest

from mpisph import measure
from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import list_frames, read_frame
from mpisph.references import MU_I_MATERIALS
from mpirun import mpisph
from repo_script import load_script

SAND = MU_I_MATERIALS["sand_0.4mm"]  # the collapses' sand (granular_column.py)
MU_S, MU_2 = (np.tan(np.radians(SAND[k])) for k in ("mu_s_deg", "mu_2_deg"))
COARSE = ["--set", "dp=0.006", "--t-end", "0.1", "--output-interval", "0.1", "--set", "diagnostics_every=10"]


@pytest.fixture(scope="module")
def planar(tmp_path_factory):
    """The coarse planar column (a = 0.9) to t = 0.1 s with each viscous form and step:
    {(form, step): out dir}; ``planar["implicit"]``: the cases' default, Eq. 27 implicitly."""
    out = {}
    for form in ("cleary", "corrected_stress"):
        for step in ("explicit", "implicit"):
            d = tmp_path_factory.mktemp(f"{form}_{step}")
            r = mpisph(["lube_collapse_2d", *COARSE, "--set", f"viscous_form={form}", "--set", f"viscous_step={step}",
                        "--out", d, "--quiet"], ranks=1, timeout=600)
            assert r.returncode == 0, r.stderr
            out[form, step] = d
    out["implicit"] = out["cleary", "implicit"]
    return out


@pytest.mark.parametrize("form", ["cleary", "corrected_stress"])
def test_implicit_kick_follows_the_explicit_step(planar, form):
    """Over the first 0.1 s (the column's foot runs out by about 1.5 dp) the kinetic energy and the
    front of the implicit run, at steps 20 times longer, stay within 6 % and dp/4 of the explicit
    run's, with either viscous form (largest gaps 4.2 % and 2.9 %, both 0.03 dp at steps 55 and 59
    times longer, for Eq. 27's pair term and the corrected stress). Backward Euler is first order in
    the viscous part: with Eq. 27's pair term the largest gap in kinetic energy, 4.5 % at t = 0.02
    s, fell to 2.3, 1.2 and 0.6 % with the time step cut to 1/2, 1/4 and 1/8
    (integrators/time_step.CFL_SINGLE set to 0.2, 0.1, 0.05)."""
    ex, im = (read_diagnostics(planar[form, s] / "diagnostics.csv") for s in ("explicit", "implicit"))
    assert np.median(ex["dt"][1:]) * 20 < np.median(im["dt"][1:])
    t = np.linspace(0.02, 0.1, 9)
    ke_ex, ke_im = np.interp(t, ex["t"], ex["kinetic_energy"]), np.interp(t, im["t"], im["kinetic_energy"])
    np.testing.assert_allclose(ke_im, ke_ex, rtol=0.06)
    front_ex, front_im = np.interp(t, ex["t"], ex["front"]), np.interp(t, im["t"], im["front"])
    assert np.abs(front_im - front_ex).max() < 0.25 * 0.006
    assert front_ex[-1] - ex["front"][0] > 1.5 * 0.006


def test_without_bulk_viscosity_a_column_below_yield_fails_at_once(tmp_path):
    """The a = 0.5 column (L_0 / dp = 20) with the regularisation time m_0 = 120 s, a hundred
    times 004_'s: with the full corrected stress, whose bulk part (about tau_y m_0 below yield)
    resists the expansion that relieves the face's pressure, it starts 0.077 s after release; with
    the deviatoric stress as soon as with m_0 = 1.2 s (0.054 and 0.052 s; physics/mu_i.py). Eq. 27's
    pair term, whose bulk viscosity is (1 + 2 / D) eta, has not started by 0.1 s; the deviatoric pair
    term starts at 0.050 s (0.045 s at m_0 = 1.2 s)."""
    onset = {}
    for form, stress, m_0 in (("corrected_stress", "full", 120), ("corrected_stress", "deviatoric", 120),
                              ("corrected_stress", "deviatoric", 1.2), ("cleary", "full", 120),
                              ("cleary", "deviatoric", 120), ("cleary", "deviatoric", 1.2)):
        d = tmp_path / f"{form}_{stress}_{m_0}"
        r = mpisph(["lube_collapse_2d", "--set", "a=0.5", "dp=0.00486", f"m_0={m_0}", f"viscous_form={form}",
                    f"viscous_stress={stress}", "viscous_step=implicit", "diagnostics_every=5", "--t-end", "0.1",
                    "--output-interval", "0.1", "--out", d, "--quiet"], ranks=1, timeout=600)
        assert r.returncode == 0, r.stderr
        diag = read_diagnostics(d / "diagnostics.csv")
        onset[form, stress, m_0] = measure.collapse_onset(diag["t"], diag["front"], 0.0972)
    for form in ("corrected_stress", "cleary"):
        assert onset[form, "deviatoric", 120] < 1.15 * onset[form, "deviatoric", 1.2]
    assert onset["corrected_stress", "full", 120] > 1.3 * onset["corrected_stress", "deviatoric", 120]
    assert not onset["cleary", "full", 120] <= 0.1  # nan: the front has not moved 0.05 L_0


def test_front_is_the_farthest_grain(planar):
    last = read_frame(list_frames(planar["implicit"])[-1])
    diag = read_diagnostics(planar["implicit"] / "diagnostics.csv")
    assert diag["front"][0] == pytest.approx(0.0972 - 0.5 * 0.006 - 0.0972 % 0.006, abs=1e-12)
    assert diag["t"][-1] == pytest.approx(last["t"])
    assert diag["front"][-1] == last["x"][:, 0].max()
    assert measure.runout(last, 0.006) - 0.006 <= measure.front_position(last, 0.006) <= last["x"][:, 0].max()


def test_the_floor_holds_the_column_back(planar):
    """The grains' force on the floor (diagnostics.csv, wall_forces.py) of the coarse column: none
    along x while it rests at t = 0, when the floor carries at most its weight; then along +x, the
    floor holding the spreading grains back, at most mu_2 times the force it carries (no grain's
    friction exceeds mu_2), with either viscous form and step."""
    for run in (key for key in planar if key != "implicit"):
        d = read_diagnostics(planar[run] / "diagnostics.csv")
        weight = d["mass"][0] * 9.81
        along, down = d["force_floor_x"], -d["force_floor_y"]
        assert abs(along[0]) < 1e-9 * weight and 0.0 < down[0] <= weight
        assert np.all(along[1:] > 0.0) and np.all(along <= MU_2 * down)


def deposit_block(dp):
    """A deposit of 10 x 3 grains, dp apart across and 0.9 dp along x (so that no grain sits on the
    edge of a dp-wide bin), its last column at x = 0.086 m for dp = 1 cm."""
    i, k = np.meshgrid(np.arange(10), np.arange(3), indexing="ij")
    return np.stack([0.5 * dp + 0.9 * dp * i, (k + 0.5) * dp], -1).reshape(-1, 2)


def turned(x, copies=64):
    """The 2D grains ``x`` (distance from the axis, height) turned about the vertical axis, ``copies`` times."""
    angle = np.linspace(0.0, 2.0 * np.pi, copies, endpoint=False)
    return np.concatenate([np.stack([x[:, 0] * np.cos(a), x[:, 0] * np.sin(a), x[:, 1]], -1) for a in angle])


def test_rest_is_the_edge_speed_over_the_peak_front_speed():
    """The deposit_block (dp = 1 cm) whose last column moves 2 mm in 0.1 s, with a front that
    peaked at 0.4 m/s: 0.02 / 0.4 = 0.05, planar and, the same block turned about the axis, radial
    (its edge taken per azimuthal sector)."""
    dp = 0.01
    x = deposit_block(dp)
    moved = x.copy()
    moved[moved[:, 0] > 0.08, 0] += 0.002
    t, front = np.array([0.0, 0.1, 0.2, 0.3]), np.array([0.0, 0.01, 0.05, 0.06])
    before, last = {"x": x, "t": 0.2}, {"x": moved, "t": 0.3}
    assert measure.edge_rest_ratio(before, last, t, front, dp) == pytest.approx(0.05, rel=1e-12)
    ratio = measure.edge_rest_ratio({"x": turned(x), "t": 0.2}, {"x": turned(moved), "t": 0.3}, t, front, dp,
                                    radial=True)
    assert ratio == pytest.approx(0.05, rel=1e-9)


def test_onset_is_when_the_front_has_moved_a_twentieth_of_the_column():
    """A front that creeps by 0.01 L_0 and then runs: its onset is the first time it is more than
    0.05 L_0 from its start; a front that never gets there has none."""
    t = np.array([0.0, 0.1, 0.2, 0.3, 0.4])
    front = 0.1 * np.array([1.0, 1.01, 1.01, 1.06, 1.5])
    assert measure.collapse_onset(t, front, 0.1) == 0.3
    assert math.isnan(measure.collapse_onset(t, front, 0.1, fraction=0.6))


def test_grains_beyond_a_gap_are_not_the_deposit():
    """The same 10 x 3 block with two grains 2.5 and 3 dp beyond its last column: the runout ends at
    the block and only those two are beyond it; turned about the axis, two per turned copy."""
    dp = 0.01
    x = np.concatenate([deposit_block(dp), [[0.086 + 0.025, 0.005], [0.086 + 0.03, 0.005]]])
    beyond = measure.beyond_the_edge({"x": x}, dp)
    assert np.flatnonzero(beyond).tolist() == [30, 31] and measure.runout({"x": x}, dp) == pytest.approx(0.095)
    assert np.sum(measure.beyond_the_edge({"x": turned(x)}, dp, radial=True)) == 2 * 64


def test_mass_extent_is_where_a_fraction_of_the_mass_lies():
    """The same block and two thrown grains, all of one mass (32 grains): 85 % of the mass (27.2
    grains) lies within the block's last column, at x = 0.086 m; 95 % (30.4 grains) reaches the
    first thrown grain, 2.5 dp beyond it. Grains of twice the mass in the block's first column
    (35 grains' mass, 85 % of it 29.75) bring the 85 % back to its second-to-last column. Turned
    about the axis, the same distances from it."""
    dp = 0.01
    x = np.concatenate([deposit_block(dp), [[0.086 + 0.025, 0.005], [0.086 + 0.03, 0.005]]])
    mass = np.ones(len(x))
    assert measure.mass_extent({"x": x, "mass": mass}, 0.85) == pytest.approx(0.086)
    assert measure.mass_extent({"x": x, "mass": mass}, 0.95) == pytest.approx(0.111)
    heavier = np.where(x[:, 0] < dp, 2.0, 1.0)
    assert measure.mass_extent({"x": x, "mass": heavier}, 0.85) == pytest.approx(0.086 - 0.009)
    spun = {"x": turned(x), "mass": np.tile(mass, 64)}
    assert measure.mass_extent(spun, 0.85, radial=True) == pytest.approx(0.086)
    assert measure.mass_extent(spun, 0.95, radial=True) == pytest.approx(0.111)


def test_the_floor_holds_a_sliding_sheet_between_mu_s_and_mu_2(tmp_path):
    """A sheet of the sand 4 layers deep (case sliding_sheet) released at 1 m/s over the collapses'
    floor loses half its speed at a mean friction U / (2 g t) between the law's mu_s and mu_2
    (004_ Eq. 7): the floor's grip on a layer a few particles deep is a friction of the law. A
    free-slip floor would give 0; a single layer is held harder than mu_2 (docs/COLLAPSES.md)."""
    r = mpisph(["sliding_sheet", "--set", "H=0.01944", "dp=0.00486", "columns=8", "diagnostics_every=5",
                "--t-end", "0.1", "--output-interval", "0.1", "--out", tmp_path, "--quiet"], ranks=1, timeout=600)
    assert r.returncode == 0, r.stderr
    d = read_diagnostics(tmp_path / "diagnostics.csv")
    speed = d["momentum_x"] / d["mass"]
    assert speed[0] == pytest.approx(1.0)
    half = d["t"][np.argmax(speed < 0.5)]
    friction = 0.5 / (9.81 * half)
    assert MU_S <= friction <= MU_2


def test_axisymmetric_column_is_a_cylinder_and_spreads_evenly(tmp_path):
    """A cylinder of the case's volume, centred on the axis as it spreads; its farthest grain moves out
    in each of 8 azimuthal sectors, along the lattice's diagonals by at least 3/4 as far as along its
    axes (the square lattice is the only anisotropy the run has)."""
    r = mpisph(["lube_collapse_3d", "--set", "dp=0.02", "--t-end", "0.1", "--output-interval", "0.1", "--out",
                tmp_path, "--quiet"], ranks=1, timeout=600)
    assert r.returncode == 0, r.stderr
    first, last = (read_frame(f) for f in list_frames(tmp_path))
    x = first["x"]
    assert np.hypot(x[:, 0], x[:, 1]).max() < 0.0972
    volume = np.pi * 0.0972**2 * (0.55 * 0.0972 // 0.02 * 0.02)
    assert len(x) * 0.02**3 == pytest.approx(volume, rel=0.15)
    np.testing.assert_allclose(last["x"][:, :2].mean(axis=0), 0.0, atol=1e-3 * 0.02)  # stays centred on the axis

    def farthest_per_sector(frame):
        x = frame["x"]
        sector = np.floor(np.arctan2(x[:, 1], x[:, 0]) / (np.pi / 4) + 0.5).astype(int) % 8
        return np.array([np.hypot(x[sector == s, 0], x[sector == s, 1]).max() for s in range(8)])

    growth = farthest_per_sector(last) - farthest_per_sector(first)
    assert growth.min() > 0 and growth.min() >= 0.75 * growth.max()
    diag = read_diagnostics(tmp_path / "diagnostics.csv")
    assert diag["front"][-1] > diag["front"][0]


@pytest.mark.parametrize("settings, words", [
    (["a=0"], "parameter a must be positive"),
    (["K_t=-1e-5"], "K_t"),
    (["viscous_step=explicit", "viscous_tolerance=1e-5"],
     "viscous_tolerance sets where the implicit kick stops, so it needs viscous_step=implicit"),
    (["viscous_tolerance=1.5"], "viscous_tolerance must lie between 0 and 1"),
])
def test_bad_settings_are_one_line_errors(tmp_path, settings, words):
    args = [a for s in settings for a in ("--set", s)]
    r = mpisph(["lube_collapse_2d", *args, "--out", tmp_path, "--quiet"], ranks=1)
    assert r.returncode == 2
    assert r.stderr.strip().startswith("mpisph: error:") and words in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


def test_implicit_kick_that_does_not_converge_stops_the_run_with_one_line(tmp_path, monkeypatch, capsys):
    """With the iteration cap cut to 1 the first kick fails: the run stops as a blow-up (exit 3)
    after writing its last frame, with one line that says why."""
    from mpisph.__main__ import main
    from mpisph.physics import implicit_viscosity

    monkeypatch.setattr(implicit_viscosity, "MAX_ITERATIONS", 1)
    code = main(["lube_collapse_2d", "--set", "dp=0.00972", "--t-end", "0.01", "--out", str(tmp_path), "--quiet"])
    err = capsys.readouterr().err.strip()
    assert code == 3
    assert err.startswith("mpisph: blow-up at step 0") and "did not converge in 1 conjugate-gradient" in err
    assert len(err.splitlines()) == 1
    assert len(list_frames(tmp_path)) == 2  # the initial frame and the one at the failure


@pytest.mark.parametrize("step", ["implicit", "explicit"])
def test_the_closing_lines_say_how_many_iterations_the_implicit_kick_took(tmp_path, capsys, step):
    """A run with the implicit kick ends with a line of its conjugate-gradient iterations, one kick a
    step (the throughput line's count), and diagnostics.csv has their mean since the row before in
    the column viscous_iterations, which weighted by the steps between rows gives the closing line's
    mean; the explicit step has neither."""
    from mpisph.__main__ import main

    code = main(["lube_collapse_2d", "--set", "dp=0.00972", f"viscous_step={step}", "diagnostics_every=3",
                 "--t-end", "0.01", "--out", str(tmp_path)])
    out = capsys.readouterr().out
    assert code == 0
    steps = int(re.search(r"^throughput: .*, (\d+) steps,", out, re.M).group(1))
    m = re.search(r"^mu\(I\): the implicit viscous kick took ([\d.]+) conjugate-gradient iterations a step on "
                  r"average, (\d+) at most \((\d+) steps\)$", out, re.M)
    diag = read_diagnostics(tmp_path / "diagnostics.csv")
    if step == "explicit":
        assert m is None and "conjugate-gradient" not in out
        assert "viscous_iterations" not in diag
        return
    assert m, out
    assert int(m.group(3)) == steps > 0
    mean, most = float(m.group(1)), int(m.group(2))
    assert 1 <= mean <= most < 2000
    rows, kicks = diag["viscous_iterations"], np.diff(diag["step"])
    assert rows[0] == 0.0 and len(rows) > 3  # the first row is the start, before any kick
    assert np.all((rows[1:] >= 1) & (rows[1:] <= most))
    assert kicks.sum() == steps
    assert np.sum(rows[1:] * kicks) / steps == pytest.approx(mean, abs=0.05)


@pytest.mark.parametrize("case, dp, warned", [
    ("lube_collapse_3d", 0.0972 / 10, ["H_0"]),  # a = 0.55: H_0 / dp = 5.5, the fill has 5 layers
    ("lube_collapse_3d", 0.0972 / 20, []),  # 11 layers
    ("lube_collapse_3d", 0.003341, []),  # 16.001 layers: the fill short by 0.1 % of dp
    ("lube_collapse_2d", 0.0972 / 30, []),  # a = 0.9: 27 layers, 30 columns
    ("lube_collapse_2d", 0.005, ["H_0", "L_0"]),
])
def test_a_column_that_is_not_whole_layers_is_warned_and_starts_hydrostatic(case, dp, warned):
    """The lattice fills floor(H_0 / dp) layers: a column whose height (or planar length) is not a
    whole number of dp has another aspect ratio, which the run's warnings say; the initial pressure
    is hydrostatic below the top of the fill, so the top layer starts at half a layer's weight."""
    from mpisph.case import build_case, load_case_module, resolve_params

    module = load_case_module(case)
    built = build_case(module, resolve_params(module, {"dp": repr(dp)}))
    assert [w.split(" =")[0] for w in built.warnings] == warned
    column = built.bodies[0]
    x, _ = column.x.everything()
    top = x[:, -1] == x[:, -1].max()
    rho0, g = built.material.rho0, 9.81
    np.testing.assert_allclose(column.pressure(x)[top], rho0 * g * 0.5 * dp, rtol=1e-12)


def test_the_deposit_script_reads_a_column_that_has_barely_moved(planar):
    """scripts/collapse_deposit.py on the coarse planar column at 0.1 s (its foot out by about 1.5 dp):
    14 layers of 6 mm fill H_0 = 0.0875 m; the column's top has sunk by less than a tenth (by half a
    layer: the open gap of issue 14 in which the top sinks where Lube's stays); the surface at 0.5 L_0,
    inside the failing wedge, has sunk by about a layer and nothing stands at 1.25 L_0; the runout
    ratio is validate.py's; 90 % of the mass lies beyond 0.9 L_0, where it stood in the column (the
    failing wedge has moved out), and within the runout, 99 % short of the farthest grain; the
    side-by-side profile (--profile 0.25) has the same surface at its stations, which end at the
    farthest grain."""
    script = load_script("collapse_deposit")
    d = script.deposit(planar["implicit"])
    assert not d["radial"] and d["layers"] == 14 and d["resolution"] == pytest.approx(0.0972 / 0.006)
    assert 0.9 < d["centre"] <= 1.0
    fill = 14 * 0.006 / 0.0972
    assert fill - 0.12 < d["surface"][0] <= fill and d["surface"][3] == 0.0
    last = read_frame(list_frames(planar["implicit"])[-1])
    assert d["ratio"] == pytest.approx((measure.runout(last, 0.006) - 0.0972) / 0.0972, abs=1e-12)
    assert 0.0 < d["ratio"] < 0.2
    assert d["beyond"] == 0 and d["ratio"] - 0.006 / 0.0972 <= d["farthest"] <= d["ratio"] + 0.5 * 0.006 / 0.0972
    assert -0.1 < d["extents"][0] < d["ratio"] and d["extents"] == sorted(d["extents"])
    assert d["extents"][-1] < d["farthest"]
    table = script.profile_table([d, d], 0.25)
    rows = {float(line.split()[0]): [float(v) for v in line.split()[1:]] for line in table[1:]}
    assert rows[0.5] == [round(d["surface"][0], 3)] * 2 and rows[1.0] == [round(d["surface"][2], 3)] * 2
    assert list(rows) == [0.25, 0.5, 0.75, 1.0] and d["farthest"] < 0.25  # stations up to the farthest grain


def test_the_deposit_script_refuses_a_path_without_frames(tmp_path):
    with pytest.raises(SystemExit, match="no frames"):
        load_script("collapse_deposit").deposit(tmp_path)


def test_the_deposit_script_averages_the_runs_of_each_spacing():
    """collapse_deposit.ensemble_table: a line for each shape, a and spacing, in that order, with the
    mean, least and greatest runout ratio and 95 and 99 % extents of its runs, and how many of them
    have an edge that moves faster than 1e-3 of the peak front speed."""
    ensemble_table = load_script("collapse_deposit").ensemble_table

    def run(resolution, ratio, rest, radial=False):
        return {"radial": radial, "a": 0.5, "resolution": resolution, "ratio": ratio, "rest": rest,
                "extents": [ratio - 0.3, ratio - 0.2, ratio - 0.1]}

    lines = ensemble_table([run(40.0, 0.5, 1e-4), run(20.0, 0.4, 2e-3), run(40.0, 0.6, 2e-3), run(40.0, 0.7, 1e-5),
                            run(20.0, 0.3, 1e-4, radial=True)])
    assert lines[1:] == ["planar 0.5 20 1: 0.400 (0.400-0.400); 0.200 (0.200-0.200); 0.300 (0.300-0.300); 1 of 1",
                         "planar 0.5 40 3: 0.600 (0.500-0.700); 0.400 (0.300-0.500); 0.500 (0.400-0.600); 1 of 3",
                         "axisymmetric 0.5 20 1: 0.300 (0.300-0.300); 0.100 (0.100-0.100); 0.200 (0.200-0.200); 0 of 1"]


def test_the_deposit_script_fits_the_planar_means_of_each_spacing():
    """collapse_deposit.ensemble_table ends with Lube et al.'s two fits of the planar means at each
    spacing that has columns a <= 1 and two a >= 4: 1.2 and 2/3 for runouts on their laws (and
    extents at fixed fractions of them); not at a spacing without them, nor for the cylinders."""
    ensemble_table = load_script("collapse_deposit").ensemble_table

    def run(a, resolution, radial=False):
        ratio = 1.2 * a if a <= 1.0 else 1.9 * a ** (2 / 3)
        return {"radial": radial, "a": a, "resolution": resolution, "ratio": ratio, "rest": 0.0,
                "extents": [0.5 * ratio, 0.6 * ratio, 0.8 * ratio]}

    runs = [run(a, 80.0) for a in (6.0, 0.5, 2.0, 1.0, 4.0)] + [run(a, 40.0) for a in (0.5, 1.0, 4.0)]
    lines = ensemble_table(runs + [run(a, 80.0, radial=True) for a in (0.5, 4.0, 6.0)])
    assert lines[-1] == ("planar fits at L_0 / dp = 80 (a = 0.5, 1, 2, 4, 6): low-a slope and high-a exponent of "
                         "the runout ratio; of 95 % and of 99 % of the mass: 1.200 0.667; 0.720 0.667; 0.960 0.667")
    assert sum(line.startswith("planar fits") for line in lines) == 1


def test_the_well_posedness_script_reads_the_planar_column(planar):
    """scripts/well_posedness.py on the coarse planar column: the sand's window (0.432 < I < 1.82),
    nothing dissipated at rest at t = 0, and at 0.1 s, as the column fails, more than nine tenths of
    the dissipation at I outside the window, three quarters of it below the window's lower end; over
    two frames the run's share is the last frame's. Eq. 27's pair term carries enough bulk friction for
    the compressible equations at every grain (docs/COLLAPSES.md): none of it short of that bound."""
    window, rows, overall = load_script("well_posedness").run_table(planar["implicit"])
    assert window == pytest.approx((0.4315, 1.815), rel=1e-3)
    assert rows[0][1] == 0.0 and math.isnan(rows[0][2]) and math.isnan(rows[0][3])
    assert rows[-1][1] > 0.0 and rows[-1][2] > 0.9 and rows[-1][4][2] < window[0]
    assert overall[0] == pytest.approx(rows[-1][2], rel=1e-12)
    assert rows[-1][3] == 0.0 and overall[1] == 0.0


def test_the_deposit_script_reads_a_slab_as_planar(tmp_path):
    """scripts/collapse_deposit.py on lube_collapse_3d with shape=slab (the planar column in 3D, its
    length r_0): a planar deposit, its runout measured along x as validate.py's slab row takes it."""
    r = mpisph(["lube_collapse_3d", "--set", "shape=slab", "a=0.5", "dp=0.0108", "width=6", "--t-end", "0.05",
                "--output-interval", "0.05", "--out", tmp_path, "--quiet"], ranks=1, timeout=600)
    assert r.returncode == 0, r.stderr
    d = load_script("collapse_deposit").deposit(tmp_path)
    assert not d["radial"] and d["length"] == pytest.approx(0.0972)
    last = read_frame(list_frames(tmp_path)[-1])
    assert d["ratio"] == pytest.approx((measure.runout(last, 0.0108) - 0.0972) / 0.0972, abs=1e-12)
    assert d["farthest"] == pytest.approx(measure.farthest_edge(last, 0.0108, False) / 0.0972 - 1.0, abs=1e-12)
