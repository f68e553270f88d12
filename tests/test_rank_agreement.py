"""The same case on 1, 2 and 3 ranks gives the same particles, and a restart on
any rank count continues the run as if it had never stopped."""

import json
from pathlib import Path

import numpy as np
import pytest

from mpisph import surface
from mpisph.__main__ import cmd_info
from mpisph.case import build_case, load_case_module
from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import frame_path, list_frames, read_frame
from mpisph.launch import mpirun_python
from mpisph.particles import CLAMPED, MOVING, WALL, WALL_SLIP
from mpisph.parts import make_parts
from mpirun import mpisph

pytestmark = pytest.mark.ranks  # tests/conftest.py

# each runs >= 200 steps; the domain sizes set the tolerance 1e-10 * size
CASES = {
    # particle shifting: the maximum speed over ranks, the Taylor correction read from ghosts
    "elliptical_drop": (["--set", "dp=0.05", "stabiliser=shifting", "--t-end", "0.0076", "--output-interval",
                         "0.0038"], 5.0),
    # a fluid with a free surface under negative pressure with artificial stress (R from the
    # pressure of the ghosts)
    "rotating_square_patch": (["--set", "dp=0.05", "stabiliser=artificial_stress", "--t-end", "1.0",
                               "--output-interval", "0.5"], 2.0),
    "dam_break_2d": (["--set", "dp=0.05", "--t-end", "0.15", "--output-interval", "0.075"], 4.3),
    "taylor_green": (["--set", "nx=30", "--t-end", "0.5", "--output-interval", "0.25"], 1.0),
    "column_collapse_2d": (["--set", "dp=0.01", "--t-end", "0.04", "--output-interval", "0.02"], 0.6),
    # the soil's density by kernel summation every configuration (free_surface: the blend near the surface)
    "column_collapse_2d reinit": (["--set", "dp=0.01", "density_reinit=free_surface", "--t-end", "0.04",
                                   "--output-interval", "0.02"], 0.6),
    # 000_'s stress diffusion (Feng et al.'s geostatic form; the default, linear, reads each
    # component's gradient from ghosts)
    "column_collapse_2d geostatic_diffusion": (["--set", "dp=0.01", "stress_diffusion=geostatic", "--t-end", "0.04",
                                                "--output-interval", "0.02"], 0.6),
    # no stress diffusion: the stress update without the diffusion's pair sums
    "column_collapse_2d no_diffusion": (["--set", "dp=0.01", "stress_diffusion=none", "--t-end", "0.04",
                                         "--output-interval", "0.02"], 0.6),
    # TVF: the shift on inner particles only (a key's first word is the case)
    "column_collapse_2d tvf": (["--set", "dp=0.01", "stabiliser=tvf", "--t-end", "0.04", "--output-interval",
                                "0.02"], 0.6),
    # an elastic solid with particle shifting: its shear stress carried to the shifted places
    "oscillating_beam": (["--set", "H_over_dp=5", "stabiliser=shifting", "--t-end", "0.012", "--output-interval",
                          "0.006"], 0.6),
    # 001_'s limited TVF on a solid: the limiter on the inner particles' shift
    "oscillating_beam tvf_limited": (["--set", "H_over_dp=5", "stabiliser=tvf_limited", "--t-end", "0.012",
                                      "--output-interval", "0.006"], 0.6),
    # Gray et al.'s classic SPH for an elastic solid with their artificial stress (000_'s SPH-AS)
    "oscillating_beam classic": (["--set", "H_over_dp=5", "scheme=classic_elastic", "stabiliser=artificial_stress",
                                  "--t-end", "0.012", "--output-interval", "0.006"], 0.6),
    "dam_break_3d": (["--set", "dp=0.1", "--t-end", "0.25", "--output-interval", "0.125"], 4.3),
    # the adaptive B-spline: knots per particle from the pressure zones, a pair kernel of two knots
    "vertical_cut": (["--set", "dp=0.1", "stabiliser=adaptive_kernel", "--t-end", "0.6", "--output-interval", "0.3"],
                     10.0),
    # two remedies at once: the adaptive kernel's knots under UTVF's shift (its sums with the two knots)
    # and under artificial stress's repulsion (its f_ij from the knots), and that repulsion beside UTVF
    # on 000_'s kernel
    "vertical_cut adaptive_kernel+utvf": (["--set", "dp=0.1", "stabiliser=adaptive_kernel+utvf", "--t-end", "0.6",
                                           "--output-interval", "0.3"], 10.0),
    "vertical_cut adaptive_kernel+artificial_stress": (["--set", "dp=0.1", "stabiliser=adaptive_kernel+artificial_stress",
                                                        "--t-end", "0.6", "--output-interval", "0.3"], 10.0),
    "vertical_cut artificial_stress+utvf": (["--set", "dp=0.1", "stabiliser=artificial_stress+utvf",
                                             "kernel=wendland_c2", "h_factor=1.3", "--t-end", "0.6",
                                             "--output-interval", "0.3"], 10.0),
    # the classic scheme of 002_ (artificial viscosity, Morris walls, the predictor-corrector) with
    # artificial stress: its principal tensions from the stress the integrator advances
    "soil_cylinder_impact": (["--set", "dp=0.001", "stabiliser=artificial_stress", "--t-end", "0.004",
                              "--output-interval", "0.002"], 0.2),
    "cube_failure_3d": (["--set", "dp=0.2", "--t-end", "0.8", "--output-interval", "0.4"], 5.6),
    # 3D UTVF with the free-surface particles beside an edge kept in place: the neighbours' div r from ghosts
    "cube_failure_3d edges_kept": (["--set", "dp=0.2", "utvf_edge_neighbours=kept", "--t-end", "0.8",
                                    "--output-interval", "0.4"], 5.6),
    # and the near-surface particles projected on the outermost particles' normals, read from ghosts
    "cube_failure_3d outermost_normals": (["--set", "dp=0.2", "utvf_edge_neighbours=kept",
                                           "utvf_near_surface_normal=outermost", "--t-end", "0.8",
                                           "--output-interval", "0.4"], 5.6),
    # and the splashed particles shifted as the authors' code does (their classes from the ghosts' div r)
    "cube_failure_3d splashed_shifted": (["--set", "dp=0.2", "utvf_splashed=shifted", "--t-end", "0.8",
                                          "--output-interval", "0.4"], 5.6),
    # periodic along the slabs' axis
    "inclined_plane": (["--set", "H=0.02", "--set", "dp=0.002", "--set", "columns=16", "--set", "m_0=0.2",
                        "--t-end", "0.01", "--output-interval", "0.005"], 0.04),
    # the isotropic pressure, the law's carried pressure and kernel-mean strain rate (eps sent to the ghosts)
    # and the corrected stress's implicit kick, periodic
    "inclined_plane isotropic": (["--set", "H=0.02", "dp=0.002", "columns=16", "m_0=0.2", "pressure_form=isotropic",
                                  "law_pressure=carried", "law_strain_rate=kernel_mean",
                                  "viscous_form=corrected_stress", "viscous_step=implicit",
                                  "--t-end", "0.02", "--output-interval", "0.01"], 0.04),
    # the law's kernel means of the deviatoric strain rate and of the carried pressure (s p sent to the ghosts)
    "inclined_plane law_means": (["--set", "H=0.02", "dp=0.002", "columns=16", "m_0=0.2", "pressure_form=isotropic",
                                  "law_pressure=carried_mean", "law_strain_rate=deviatoric_kernel_mean",
                                  "viscous_form=corrected_stress", "viscous_step=implicit",
                                  "--t-end", "0.02", "--output-interval", "0.01"], 0.04),
    # the implicit viscous kick: conjugate gradients with partition-independent sums
    "lube_collapse_2d": (["--set", "dp=0.005", "--t-end", "0.06", "--output-interval", "0.03"], 0.5),
    # the implicit kick of the corrected viscous stress: its stress sent to ghosts every iteration
    "lube_collapse_2d corrected": (["--set", "dp=0.005", "viscous_form=corrected_stress", "--t-end", "0.06",
                                    "--output-interval", "0.03"], 0.5),
    # the same with the deviatoric viscous stress, the regularisation time of a column that comes to rest
    "lube_collapse_2d deviatoric": (["--set", "dp=0.005", "viscous_form=corrected_stress", "viscous_stress=deviatoric",
                                     "m_0=40", "--t-end", "0.06", "--output-interval", "0.03"], 0.5),
    # the deviatoric pair term: its part along the relative velocity, in the implicit kick too
    "lube_collapse_2d deviatoric_pairs": (["--set", "dp=0.005", "viscous_stress=deviatoric", "m_0=40", "--t-end",
                                           "0.06", "--output-interval", "0.03"], 0.5),
    # the mu(I) density by kernel summation near a free surface
    "lube_collapse_2d reinit": (["--set", "dp=0.005", "density_reinit=free_surface", "--t-end", "0.06",
                                 "--output-interval", "0.03"], 0.5),
    # the side walls' friction (a case's own force term) on the law's pressure
    "lube_collapse_2d side_walls": (["--set", "dp=0.005", "channel_width=0.05", "wall_friction_deg=20",
                                     "law_pressure=carried_mean", "--t-end", "0.06", "--output-interval", "0.03"],
                                    0.5),
}
FIELDS = ("x", "v", "rho", "p", "drho_dt", "stress", "shear_stress", "plastic_strain", "eta", "rho_s", "knot",
          "displacement_gradient")


def final_state(out):
    frames = list_frames(out)
    return read_frame(frames[-1])


def assert_same_particles(a, b, size):
    assert a["step"] >= 200
    assert a["step"] == b["step"] and a["t"] == b["t"]
    np.testing.assert_array_equal(a["gid"], b["gid"])
    for name in (f for f in FIELDS if f in a):
        scale = size if name == "x" else max(1.0, float(np.abs(a[name]).max()))
        assert np.abs(a[name] - b[name]).max() <= 1e-10 * scale, name


# the mu(I) incline: its first time step after a restart takes the viscosity stored in the frame;
# the mu(I) column: its implicit kick's first guess extrapolates from the two accelerations in the frame;
# the outermost normals: recomputed, not read from the frame (a restart takes the frame's parameters)
RESTARTED = ("dam_break_2d", "taylor_green", "column_collapse_2d", "inclined_plane", "lube_collapse_2d",
             "cube_failure_3d outermost_normals")


def keys_of(case):
    """The keys of CASES that run ``case`` (a key's first word), in their order."""
    return [key for key in CASES if key.split()[0] == case]


SEVERAL_KEYS = sorted({key.split()[0] for key in CASES if len(keys_of(key.split()[0])) > 1})


def launch(tmp_path_factory, case):
    """Every key of ``case`` on 1, 2 and 3 ranks and, for the keys of RESTARTED, restarted from the
    2-rank run's middle frame on 1 and 3 ranks, all in one launch, whose start-up of Python, MPI and
    numba's cache (about 4 s on 2 cores) then serves them all; last, where the case has several keys,
    the first once more on one rank up to its first output time (the middle frame), to show that a
    run keeps nothing of the runs before it in the same process.
    Returns {key: {1, 2, 3, ("restart", 1), ("restart", 3), "again": out_dir}}."""
    base = tmp_path_factory.mktemp(case)
    keys = keys_of(case)
    out, spec = {}, []
    for key in keys:
        args, _ = CASES[key]
        at = out[key] = {}
        for ranks in (1, 2, 3):
            at[ranks] = base / key.replace(" ", "_") / f"ranks{ranks}"
            spec.append([ranks, [case, *args, "--out", str(at[ranks]), "--quiet"]])
        if key in RESTARTED:
            for ranks in (1, 3):
                at["restart", ranks] = base / key.replace(" ", "_") / f"restart{ranks}"
                spec.append([ranks, [case, "--restart", frame_path(at[2], 1), "--out", str(at["restart", ranks]),
                                     "--quiet"]])
    if len(keys) > 1:
        again = out[keys[0]]["again"] = out[keys[0]][1].with_name("again")
        args = CASES[keys[0]][0]
        t_end = args.index("--t-end") + 1
        to_middle = [*args[:t_end], args[args.index("--output-interval") + 1], *args[t_end + 1:]]
        spec.append([1, [case, *to_middle, "--out", str(again), "--quiet"]])
    (base / "spec.json").write_text(json.dumps(spec))
    r = mpirun_python([Path(__file__).parent / "runs_in_one_launch.py", base / "spec.json"], ranks=3,
                      timeout=300 * len(out))
    assert r.returncode == 0, r.stderr
    return out


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """``runs(key)``: the output directories of ``key``, from ``launch`` of its case, launched when
    one of the case's keys is first asked for."""
    done = {}

    def of(key):
        case = key.split()[0]
        if case not in done:
            done[case] = launch(tmp_path_factory, case)
        return done[case][key]
    return of


@pytest.mark.parametrize("case", list(CASES))
@pytest.mark.parametrize("ranks", [2, 3])
def test_same_particles_on_any_rank_count(runs, case, ranks):
    one = final_state(runs(case)[1])
    many = final_state(runs(case)[ranks])
    assert_same_particles(one, many, CASES[case][1])


@pytest.mark.parametrize("case", list(CASES))
def test_bitwise_identical(runs, case):
    """Stronger than the 1e-10 requirement: canonical neighbour order gives equal bits, in every
    stored array of every particle, walls included, so no frame holds memory that a kernel left
    unset (wall rows of a scratch array once reached the law_pressure of frames)."""
    one = read_frame(list_frames(runs(case)[1])[-1], walls=True)
    for ranks in (2, 3):
        other = read_frame(list_frames(runs(case)[ranks])[-1], walls=True)
        assert sorted(stored_arrays(other)) == sorted(stored_arrays(one)), f"{case} {ranks} ranks"
        for name, a in stored_arrays(one).items():
            np.testing.assert_array_equal(a, other[name], err_msg=f"{case} {name} {ranks} ranks")


@pytest.mark.parametrize("case", SEVERAL_KEYS)
def test_a_run_keeps_nothing_of_the_runs_before_it(runs, case):
    """A case's first key run again on one rank at the end of its launch, after the case's other
    keys (other parameters, other stabilisers) ran in the same process, gives the same bits as its
    first run's middle frame: what the launch shares between runs is only the start-up."""
    key = keys_of(case)[0]
    first = read_frame(list_frames(runs(key)[1])[1], walls=True)
    again = read_frame(list_frames(runs(key)["again"])[-1], walls=True)
    assert sorted(stored_arrays(again)) == sorted(stored_arrays(first))
    for name, a in stored_arrays(first).items():
        np.testing.assert_array_equal(a, again[name], err_msg=f"{key} {name}")


def stored_arrays(frame):
    """{name: array} of a frame's particle arrays (read_frame adds t, step, configurations, dim and params)."""
    return {k: a for k, a in frame.items() if k not in ("t", "step", "configurations", "dim", "params")}


@pytest.mark.parametrize("case", list(CASES))
def test_frames_hold_the_declared_fields(runs, case):
    """The run's last frame holds its declared fields (Parts.frame_fields, the particles' and the
    scheme's derived ones), each with its declared shape and type, and nothing else: what the scheme's
    derived_fields gives agrees with its declaration, and no declared field is left out of frames."""
    frame = final_state(runs(case)[1])
    params = frame["params"]
    declared = make_parts(build_case(load_case_module(params["case"]), params), params).frame_fields
    stored = stored_arrays(frame)
    assert sorted(stored) == sorted(f.name for f in declared)
    for f in declared:
        assert stored[f.name].shape[1:] == f.shape_in(frame["dim"]), f.name
        assert stored[f.name].dtype == np.dtype(f.dtype), f.name


@pytest.mark.parametrize("case", list(CASES))
def test_frames_hold_plausible_values(runs, case):
    """Every array of every particle of the run's last frame, walls included, is finite, and what a
    frame derives from the state agrees with that state: the bitwise test cannot see a value that
    is wrong the same way on every rank count. Speed |v|, the vertical stress (y in 2D, z in 3D) and
    the von Mises stress sqrt(3/2 s:s) of the packed stress; for mu(I) the inertial number the law
    takes (from the volume fraction, 004_ Eq. 8, or with law_pressure=carried_mean from the strain
    rate and the law's pressure, Eq. 6) and a friction between mu_s and mu_2 (Eq. 7); positive masses and
    moving densities, a plastic strain that only accumulates, unit normals on the walls, and the
    documented codes of kind and surface."""
    f = read_frame(list_frames(runs(case)[1])[-1], walls=True)
    moving, dim = f["kind"] == MOVING, f["dim"]
    for name, a in stored_arrays(f).items():
        assert np.isfinite(a).all(), name
    assert set(np.unique(f["kind"])) <= {MOVING, WALL, WALL_SLIP, CLAMPED}
    assert (f["mass"] > 0).all() and (f["rho"][moving] > 0).all()
    walls = np.isin(f["kind"], (WALL, WALL_SLIP))  # walls carry a normal; clamped rows do not
    if "normal" in f and walls.any():
        np.testing.assert_allclose(np.linalg.norm(f["normal"][walls], axis=1), 1.0, rtol=1e-12)
    if "surface" in f:
        assert set(np.unique(f["surface"][moving])) <= {surface.INNER, surface.NEAR_SURFACE, surface.SURFACE,
                                                         surface.SPLASHED}
    if "plastic_strain" in f:
        assert (f["plastic_strain"] >= 0).all()
    if "speed" in f:
        np.testing.assert_allclose(f["speed"], np.linalg.norm(f["v"], axis=1), rtol=1e-14, atol=1e-300)
    if "von_mises" in f:
        s = f["stress"][moving]
        deviator = s.copy()
        deviator[:, :3] -= s[:, :3].mean(axis=1, keepdims=True)
        s_s = (deviator[:, :3] ** 2).sum(axis=1) + 2.0 * (deviator[:, 3:] ** 2).sum(axis=1)
        np.testing.assert_allclose(f["von_mises"][moving], np.sqrt(1.5 * s_s), rtol=1e-10,
                                   atol=1e-12 * np.abs(s).max())
        np.testing.assert_array_equal(f["vertical_stress"], f["stress"][:, dim - 1])
    if "friction" in f:
        p = f["params"]
        rho, rho_s = f["rho"][moving], f["rho_s"][moving]
        if "law_pressure" in f:  # law_pressure=carried_mean: Eq. 6 from the law's pressure, d of Eq. 43
            d = p["d"] * (rho_s / p["rho_s0"]) ** (-1.0 / dim)
            law_p = f["law_pressure"][moving]
            I = np.where(law_p > 0, f["gamma_dot"][moving] * d * np.sqrt(rho_s / np.where(law_p > 0, law_p, 1.0)), 0.0)
        else:
            I = np.maximum(0.0, (p["phi_max"] - rho / rho_s) / (p["phi_max"] - p["phi_min"]))
        np.testing.assert_allclose(f["inertial_number"][moving], I, rtol=1e-12, atol=1e-15)
        mu_s, mu_2 = np.tan(np.radians([p["mu_s_deg"], p["mu_2_deg"]]))
        mu = f["friction"][moving]
        assert (mu >= mu_s * (1 - 1e-12)).all() and (mu <= mu_2).all()


@pytest.mark.parametrize("case", ["dam_break_2d", "column_collapse_2d", "cube_failure_3d", "inclined_plane"])
def test_info_lists_the_arrays_of_a_frame(runs, case, capsys):
    """`python -m mpisph info CASE` lists every array of a frame of the case (these runs set only
    sizes and times), each with its type, its shape per particle and a meaning that ends in a unit or
    says what its codes are."""
    cmd_info(case, {})
    out = capsys.readouterr().out
    listed = out.split("frames hold for each particle", 1)[1].split("\n\n", 1)[0].splitlines()[1:]
    rows = {line.split()[0]: line.split()[1:] for line in listed if line.strip()}
    for name, a in stored_arrays(final_state(runs(case)[1])).items():
        dtype, shape, *doc = rows.pop(name)
        assert dtype == a.dtype.name, name
        assert shape == ("x".join(map(str, a.shape[1:])) or "scalar"), name
        assert doc and (doc[-1].endswith("]") or name in ("gid", "kind", "surface")), name
    assert not rows, f"info lists arrays the frame lacks: {sorted(rows)}"


@pytest.mark.parametrize("case", ["dam_break_2d", "column_collapse_2d", "cube_failure_3d", "inclined_plane"])
def test_info_lists_the_columns_of_the_diagnostics(runs, case, capsys):
    """`python -m mpisph info CASE` names every column of the run's diagnostics.csv, in its order,
    each with a meaning that ends in its unit."""
    cmd_info(case, {})
    out = capsys.readouterr().out
    listed = out.split("diagnostics.csv's columns", 1)[1].splitlines()[1:]
    rows = [line.split(None, 1) for line in listed if line.startswith("  ")]
    with open(runs(case)[1] / "diagnostics.csv") as f:
        header = f.readline().strip().split(",")
    assert [name for name, _ in rows] == header
    assert all(doc.endswith("]") for _, doc in rows), rows


@pytest.mark.parametrize("case", RESTARTED)
@pytest.mark.parametrize("ranks", [1, 3])
def test_restart_continues_the_run(runs, case, ranks):
    assert_same_particles(final_state(runs(case)[2]), final_state(runs(case)["restart", ranks]), CASES[case][1])


def test_the_cuts_follow_the_surge(tmp_path):
    """The dam break on 2 ranks to 0.6 s: as the water runs along the slab axis the pairs move from
    one rank to the other; the cuts are moved whenever the imbalance passes the threshold (0.1), at
    least three times, and it stays under it; with the threshold out of reach the same run's
    imbalance grows past 0.3."""
    imbalance = {}
    for threshold in ("0.1", "1e9"):
        out = tmp_path / threshold
        r = mpisph(["dam_break_2d", "--set", "dp=0.05", f"rebalance_threshold={threshold}", "--t-end", "0.6",
                    "--output-interval", "0.6", "--out", out, "--quiet"], ranks=2)
        assert r.returncode == 0, r.stderr
        d = read_diagnostics(out / "diagnostics.csv")
        imbalance[threshold] = (d["imbalance"], d["rebalances"][-1])
    assert imbalance["0.1"][1] >= 3 and imbalance["0.1"][0].max() < 0.1
    assert imbalance["1e9"][1] == 0 and imbalance["1e9"][0].max() > 0.3


@pytest.mark.parametrize("case", ["dam_break_2d", "dam_break_3d", "inclined_plane"])
def test_load_balance_columns(runs, case):
    """diagnostics.csv's load-balance columns: one rank holds everything; on three, every rank holds
    at least a quarter of the particles (the slabs balance the pairs, 30-40 % of the particles on each
    when this test was written), and the imbalance is max / mean - 1 of the pairs, the mean a third of
    the one-rank run's, which the rebalancing keeps near or under its threshold (0.1)."""
    one = read_diagnostics(runs(case)[1] / "diagnostics.csv")
    n, pairs = one["n"], one["rank_pairs_max"]
    np.testing.assert_array_equal(one["rank_particles_min"], n)
    np.testing.assert_array_equal(one["rank_particles_max"], n)
    np.testing.assert_array_equal(one["rank_pairs_min"], pairs)
    np.testing.assert_array_equal(one["imbalance"], 0.0)
    np.testing.assert_array_equal(one["rebalances"], 0.0)
    three = read_diagnostics(runs(case)[3] / "diagnostics.csv")
    assert np.all(three["rank_particles_min"] >= n / 4)
    mean = pairs / 3  # the same configurations, so the same total of pairs as on one rank
    np.testing.assert_allclose(three["imbalance"], three["rank_pairs_max"] / mean - 1.0, rtol=1e-12)
    assert np.median(three["imbalance"]) < 0.15
    assert np.all(np.diff(three["rebalances"]) >= 0)
