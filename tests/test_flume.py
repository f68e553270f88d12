"""The flume of 000_ Sec. 5.4 built from its STL files (cases/flume_3d.py, cases/flume/): the files
are the ones scripts/make_flume_stl.py writes, the soil sits on the chute's lattice, no two
particles crowd, and a small run on 8 ranks (oversubscribed) ends with the same bits as on 1."""

from pathlib import Path

import numpy as np
import pytest

from mpisph.case import build_case, load_case_module, resolve_params
from mpisph.errors import InputError
from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import list_frames, read_frame
from mpisph.meshes import read_surface
from mpisph.neighbours import neighbour_lists
from mpirun import mpisph
from repo_script import load_script

ROOT = Path(__file__).resolve().parent.parent


def make_flume_stl():
    return load_script("make_flume_stl")


def flume(**overrides):
    module = load_case_module("flume_3d")
    return build_case(module, resolve_params(module, {k: str(v) for k, v in overrides.items()}))


def test_the_shipped_stl_files_are_the_scripts(tmp_path):
    script = make_flume_stl()
    script.write(tmp_path)
    for name in script.SURFACES:
        shipped = read_surface(ROOT / "cases" / "flume" / f"{name}.stl").triangles
        np.testing.assert_allclose(shipped, read_surface(tmp_path / f"{name}.stl").triangles, atol=1e-12)


def test_the_soil_sits_on_the_chute_lattice():
    script = make_flume_stl()
    case = flume(dp=0.1)
    soil, _ = case.bodies[0].x.everything()
    along, across, up = script.slope_axes()
    u = (soil - script.chute_top()) @ np.column_stack([along, across, up])
    dp = 0.1
    layers = [round(script.SOIL_LENGTH / dp), round(script.WIDTH / dp), round(script.SOIL_DEPTH / dp)]
    assert len(soil) == np.prod(layers)
    for a in range(3):
        k = u[:, a] / dp - 0.5
        assert np.allclose(k, np.round(k), atol=1e-9) and k.min() > -1e-9
    chute = next(w for w in case.walls if w.name == "chute")
    w = (chute.points.everything()[0] - script.chute_top()) @ np.column_stack([along, across, up])
    under = (w[:, 0] > 0) & (w[:, 0] < script.CHUTE_LENGTH) & (w[:, 1] > 0) & (w[:, 1] < script.WIDTH)
    depth = -w[under, 2] / dp - 0.5  # the floor's layers continue the soil's lattice below the floor
    assert np.allclose(depth, np.round(depth), atol=1e-9) and set(np.round(depth)) == {0.0, 1.0, 2.0}
    assert [w.slip for w in case.walls] == [False, True, False, True, False]


def test_no_two_particles_of_the_flume_crowd():
    """Soil and every wall at dp = 0.1: no pair nearer than dp / 2 (the joints of the parts)."""
    case = flume(dp=0.1)
    x = np.concatenate([source.everything()[0] for source in case.sources])
    start, nbr = neighbour_lists(x, np.arange(len(x)), np.zeros(len(x), np.int8), len(x), 0.05, x.min(axis=0) - 0.1)
    assert len(nbr) == 0


def test_at_a_coarse_spacing_only_the_barrier_is_too_thin(tmp_path):
    """At dp = 0.08 m the 0.12 m barrier holds one layer and is warned of. The other walls are not:
    the run-out's end wall (x = 3 m) and the side wall at y = 1 m pass through planes of lattice
    points and keep three layers behind them (two before meshes.ON_SURFACE), and where two parts'
    lattices meet, a deeper particle with the other lattice's in front off its line is not taken
    for a surface of one layer (overlap.NEAR)."""
    r = mpisph(["flume_3d", "--set", "dp=0.08", "--t-end", "1e-6", "--quiet", "--out", tmp_path / "out"], ranks=1,
               timeout=300)
    assert r.returncode == 0, r.stderr
    warnings = [line for line in r.stderr.splitlines() if "dp thick" in line]
    assert len(warnings) == 1 and warnings[0].startswith("mpisph: warning: wall 'barrier' is 1 dp thick"), r.stderr


@pytest.mark.ranks
def test_the_flume_on_eight_ranks_ends_with_the_bits_of_one(tmp_path):
    args = ["--set", "dp=0.1", "--t-end", "0.12", "--output-interval", "0.06", "--quiet"]
    ends = {}
    for ranks in (1, 8):
        out = tmp_path / f"r{ranks}"
        r = mpisph(["flume_3d", *args, "--out", out], ranks=ranks, timeout=600)
        assert r.returncode == 0, r.stderr
        ends[ranks] = read_frame(list_frames(out)[-1])
        d = read_diagnostics(out / "diagnostics.csv")
        assert d["kinetic_energy"][-1] > 0 and "force_barrier_x" in d
        assert (out / "gauge_approach.csv").exists() and (out / "gauge_depth.csv").exists()
    one, eight = ends[1], ends[8]
    assert one["step"] >= 50 and one["step"] == eight["step"]
    for name in ("gid", "x", "v", "rho", "p", "stress", "plastic_strain"):
        np.testing.assert_array_equal(one[name], eight[name], err_msg=name)



def test_a_soil_surface_that_is_not_watertight_is_one_line_from_the_command_line(tmp_path):
    import shutil

    import meshio

    for path in (ROOT / "cases" / "flume").glob("*.stl"):
        shutil.copy(path, tmp_path)
    with np.errstate(over="ignore"):  # meshio probes an ASCII STL as binary first
        soil = meshio.read(tmp_path / "soil.stl")
    cells = soil.cells_dict["triangle"][1:]  # one facet gone
    meshio.write(tmp_path / "soil.stl", meshio.Mesh(soil.points, [("triangle", cells)]), binary=False)
    r = mpisph(["flume_3d", "--set", f"geometry={tmp_path}", "--out", tmp_path / "out"], ranks=1, timeout=300)
    assert r.returncode == 2
    assert "the surface 'soil' is not watertight" in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr


def test_the_barrier_coefficient_from_a_gauge_line():
    """Depth-averaged speed over the points inside the flow (kernel sum >= 1/2), nan where none is;
    alpha = F / (rho v^2 h w), nan where the flow has not arrived."""
    from mpisph.barrier_load import barrier_coefficient, depth_averaged

    speed = np.array([[9.0, 9.0, 9.0], [2.0, 4.0, 9.0], [1.0, 3.0, 5.0]])
    inside = np.array([[0.0, 0.0, 0.0], [1.0, 0.6, 0.2], [1.0, 1.0, 0.5]])
    v = depth_averaged(speed, inside)
    assert np.isnan(v[0]) and v[1] == 3.0 and v[2] == 3.0
    alpha = barrier_coefficient(np.array([5.0, 1800.0, 3600.0]), 2000.0, v, np.array([np.nan, 0.2, 0.4]), 0.5)
    assert np.isnan(alpha[0])
    np.testing.assert_allclose(alpha[1:], [1800.0 / (2000 * 9 * 0.2 * 0.5), 3600.0 / (2000 * 9 * 0.4 * 0.5)])


def test_the_deposit_stress_script_on_a_banked_block():
    """scripts/deposit_stress.py on a block resting against the barrier's face under a geostatic
    stress with sigma_xx = 0.6 sigma_zz: the section carries 0.6 gamma H^2 / 2 per metre of width,
    the medians are the coefficients, the top is the block's; the classical forces are the
    references' for that top."""
    script = load_script("deposit_stress")
    face, height, ys = script.barrier_box(ROOT / "cases" / "flume")
    assert (face, height, ys) == (0.6, 0.8, (0.0, 1.0))
    dp, top, gamma = 0.02, 0.9, 1850.0 * 9.8
    axes = [np.arange(lo + dp / 2, hi, dp) for lo, hi in ((0.0, face), ys, (0.0, top))]
    x = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    stress = np.zeros((len(x), 6))
    stress[:, 2] = -gamma * (top - x[:, 2])
    stress[:, 0], stress[:, 1] = 0.6 * stress[:, 2], 0.3 * stress[:, 2]
    params = {"dp": dp, "rho0": 1850.0, "g": 9.8, "nu": 0.3, "phi": 25.0, "cohesion": 5e3}
    frame = {"x": x, "stress": stress, "mass": np.full(len(x), 1850.0 * dp**3), "rho": np.full(len(x), 1850.0),
             "params": params}
    force, deposit_top, kx, ky = script.frame_row(frame, face, ys, 0.1)
    assert force == pytest.approx(0.6 * gamma * top**2 / 2, rel=1e-9)
    assert deposit_top == pytest.approx(top) and kx == pytest.approx(0.6) and ky == pytest.approx(0.3)
    forces = script.classical_forces(params, top, height, 1.0)
    assert forces["elastic at rest"] == pytest.approx(0.3 / 0.7 * gamma * (top**2 - 0.1**2) / 2)
    assert forces["active"] < forces["elastic at rest"] < forces["at rest"] < forces["passive"]


def test_a_barrier_upstream_of_its_approach_gauge_is_one_line(tmp_path):
    """flume_3d measures the approach 0.4 m upstream of the barrier, on the run-out (x > 0): a
    geometry of one's own with the barrier 0.3 m from the foot is refused naming where it stands,
    where the case failed on its own gauge's empty stations."""
    script = make_flume_stl()
    script.BARRIER_X = 0.3
    script.write(tmp_path)
    module = load_case_module("flume_3d")
    with pytest.raises(InputError, match=r"^flume_3d: the barrier's upstream face is at x = 0.3 m, where the case "
                                         r"needs it on the run-out more than the approach gauge's 0.4 m"):
        build_case(module, resolve_params(module, {"geometry": str(tmp_path), "dp": "0.1"}))


@pytest.mark.parametrize("args, words", [(["BARRIER_HEIGHT=0.5"], "reads as a dimension"),
                                         (["cases/flume", "BARRIER_HEIGHT=0.5"], "would write over the shipped")])
def test_a_flume_variant_without_a_directory_of_its_own_is_refused(args, words):
    """make_flume_stl.py DIR NAME=VALUE: a dimension given first wrote into a directory named after it,
    and a variant into cases/flume/ over the shipped surfaces; both are usage errors that write nothing."""
    import subprocess
    import sys

    before = {p.name: p.read_bytes() for p in (ROOT / "cases" / "flume").glob("*.stl")}
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "make_flume_stl.py"), *args], cwd=ROOT,
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and words in r.stderr, r.stderr
    assert not (ROOT / args[0]).exists() or args[0] == "cases/flume"
    assert {p.name: p.read_bytes() for p in (ROOT / "cases" / "flume").glob("*.stl")} == before
