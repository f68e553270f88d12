"""``python -m mpisph compare``: one run per stabiliser, a Markdown table and two pictures; clear
one-line errors for what it cannot compare (mpisph/compare.py)."""

import shutil
import subprocess
import sys

import numpy as np
import pytest

from mpisph.io.frames import list_frames, read_frame
from mpisph.launch import MPI_ENV, ROOT


def compare(*args, ranks=None, cwd=ROOT):
    import os

    env = dict(MPI_ENV, **os.environ)
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    cmd = [sys.executable, "-m", "mpisph", "compare", *map(str, args)]
    if ranks:
        cmd = ["mpirun", "-n", str(ranks), *cmd]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=600, cwd=cwd, env=env)


def table_rows(path):
    """The rows of compare.md's first table (the one of every case), without its header."""
    text = path.read_text()
    first = text[text.index("| "):].split("\n\n")[0]
    return [line for line in first.splitlines() if line.startswith("| ") and "---" not in line][1:]


@pytest.mark.ranks
def test_a_cut_with_and_without_utvf_side_by_side(tmp_path):
    r = compare("cohesive_failure_2d", "--stabiliser", "none,utvf", "--set", "dp=0.1", "t_end=0.1",
                "output_interval=0.05", "--out", tmp_path, "-n", "2")
    assert r.returncode == 0, r.stderr
    rows = table_rows(tmp_path / "compare.md")
    assert [row.split(" | ")[0] for row in rows] == ["| none", "| utvf"]
    for row in rows:
        cells = row.strip("| ").split(" | ")
        assert cells[1] == "done" and float(cells[2]) == pytest.approx(0.1)
        assert cells[4].endswith(" %") and float(cells[4].split()[0]) <= float(cells[3].split()[0])  # paired
        assert cells[7] == "1 (0.00 %)"  # fragments (outside the largest): the cut is whole at 0.1 s
        assert cells[10] == cells[11] == "–"  # a walled, gravity-driven case: no momentum columns
    for name in ("compare_particles.png", "compare_energy.png", "none/diagnostics.csv", "utvf/diagnostics.csv"):
        assert (tmp_path / name).stat().st_size > 0


def test_a_periodic_wall_free_case_reports_its_momentum_drift(tmp_path):
    """Taylor-Green: pairwise forces conserve linear momentum to round-off; angular momentum is left
    out on a periodic domain."""
    r = compare("taylor_green", "--stabiliser", "none,tvf_limited", "--set", "nx=20", "t_end=0.1",
                "output_interval=0.05", "--out", tmp_path)
    assert r.returncode == 0, r.stderr
    rows = table_rows(tmp_path / "compare.md")
    assert [row.split(" | ")[0] for row in rows] == ["| none", "| tvf_limited"]
    for row in rows:
        cells = row.strip("| ").split(" | ")
        assert cells[1] == "done" and cells[4] == "–"  # a fluid: no paired share
        assert float(cells[10]) < 1e-12 and cells[11] == "–"


def test_a_clamped_elastic_solid_keeps_its_energy_in_the_table(tmp_path):
    """The beam to a quarter period, with TVF and 001_'s limited TVF: its kinetic energy has gone
    into strain energy, which the energy columns count (dE within 10 % of the energy moved, where
    kinetic and gravitational energy alone would have lost all of it); the
    clamp exchanges momentum with the beam, so the momentum columns are left out."""
    r = compare("oscillating_beam", "--stabiliser", "tvf,tvf_limited", "--set", "H_over_dp=5", "t_end=0.064",
                "output_interval=0.032", "--out", tmp_path)
    assert r.returncode == 0, r.stderr
    rows = table_rows(tmp_path / "compare.md")
    assert [row.split(" | ")[0] for row in rows] == ["| tvf", "| tvf_limited"]
    for row in rows:
        cells = row.strip("| ").split(" | ")
        assert cells[1] == "done" and abs(float(cells[9])) < 0.1
        assert cells[10] == cells[11] == "–"


def test_paths_are_read_from_where_compare_is_started(tmp_path):
    """A case file and --out given relative to the caller's directory, outside the repository: the
    runs (started in the repository's root) read that case and write where the table looks; `none`
    alone is one run, the baseline."""
    shutil.copy(ROOT / "cases" / "taylor_green.py", tmp_path / "my_vortex.py")
    r = compare("my_vortex.py", "--stabiliser", "none", "--set", "nx=10", "t_end=0.05", "output_interval=0.05",
                "--out", "side_by_side", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    (row,) = table_rows(tmp_path / "side_by_side" / "compare.md")
    cells = row.strip("| ").split(" | ")
    assert cells[1] == "done" and float(cells[2]) == pytest.approx(0.05)
    assert (tmp_path / "side_by_side" / "none" / "diagnostics.csv").is_file()
    assert not (ROOT / "side_by_side").exists()
    r = compare("my_vortex.py", "--stabiliser", "none", "--set", "nx=10", "t_end=0.05", "output_interval=0.05",
                cwd=tmp_path)  # no --out: runs/compare_<the case file's stem> under the caller's directory
    assert r.returncode == 0, r.stderr
    assert len(table_rows(tmp_path / "runs" / "compare_my_vortex" / "compare.md")) == 1


@pytest.mark.parametrize("args, message", [
    (["dam_break_3d", "--stabiliser", "none,utvf"], "has no stabiliser parameter"),
    (["cohesive_failure_2d", "--stabiliser", "none,xsph"], "parameter stabiliser must be one of"),
    (["cohesive_failure_2d", "--stabiliser", "none", "--set", "stabiliser=tvf"],
     "stabiliser is what compare varies: give its values to --stabiliser, not --set"),
    (["cohesive_failure_2d"], "compare takes --stabiliser A,B,... or --vary NAME=A,B,..., one of the two"),
    (["cohesive_failure_2d", "--stabiliser", "none", "--vary", "phi=20,30"], "one of the two"),
    (["cohesive_failure_2d", "--vary", "phi"], "--vary takes NAME=A,B,..., not 'phi'"),
    (["cohesive_failure_2d", "--vary", "phii=20,30"], "case 'cohesive_failure_2d' has no phii parameter"),
    (["cohesive_failure_2d", "--vary", "phi=20,95"], "phi must lie in [0, 90), not 95.0"),
    (["lube_collapse_2d", "--vary", "m_0=1.2,40", "--set", "m_0=2"], "m_0 is what compare varies"),
    (["cohesive_failure_2d", "--stabiliser", "utvf,none,utvf"], "names utvf twice"),
    (["cohesive_failure_2d", "--stabiliser", "none,utvf", "--colour", "bogus"],
     "--colour bogus: the frames with stabiliser=none have no such field (they hold "),
])
def test_what_cannot_be_compared_is_one_line(tmp_path, args, message):
    r = compare(*args, "--out", tmp_path)
    assert r.returncode == 2
    assert message in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
    if "--colour" in args:  # the fields it names, speed among them once
        assert r.stderr.count("speed") == 1 and "plastic_strain" in r.stderr, r.stderr


def test_compare_varies_any_parameter(tmp_path):
    """--vary NAME=A,B: a run for each value of a parameter that is not a stabiliser (the kernel of
    the vortex here), into OUT/<value>, its table's rows and the pictures' panels named by it."""
    r = compare("taylor_green", "--vary", "kernel=wendland_c2,cubic_spline", "--set", "nx=10", "t_end=0.05",
                "output_interval=0.05", "--out", tmp_path)
    assert r.returncode == 0, r.stderr
    assert "compare: taylor_green with kernel=cubic_spline: done" in r.stdout
    text = (tmp_path / "compare.md").read_text()
    assert text.startswith("# taylor_green: kernel side by side") and "--vary kernel=wendland_c2,cubic_spline" in text
    assert [row.split(" | ")[0].strip("| ") for row in table_rows(tmp_path / "compare.md")] == ["wendland_c2",
                                                                                                 "cubic_spline"]
    for name in ("wendland_c2", "cubic_spline"):
        assert read_frame(list_frames(tmp_path / name)[-1])["params"]["kernel"] == name


def test_an_output_path_that_is_a_file_is_one_line(tmp_path):
    (tmp_path / "a_file").write_text("not a directory")
    r = compare("cohesive_failure_2d", "--stabiliser", "none", "--out", tmp_path / "a_file")
    assert r.returncode == 2
    assert "cannot write output directory" in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr


@pytest.mark.ranks
def test_a_run_that_fails_makes_compare_fail_after_the_table(tmp_path):
    """Three ranks on a domain of two slabs: each run stops with its one-line error, which compare
    prints and puts in its table, and compare exits 1; each run's whole standard error is kept."""
    r = compare("elliptical_drop", "--stabiliser", "none,utvf", "--set", "dp=1.0", "--out", tmp_path, "-n", "3")
    assert r.returncode == 1, r.stderr
    assert r.stdout.count("only 2 slabs") == 2 and "none, utvf failed" in r.stdout, r.stdout
    for name in ("none", "utvf"):
        assert "mpisph: error: 3 ranks" in (tmp_path / name / "stderr.txt").read_text()
    assert [row.split(" | ")[1] for row in table_rows(tmp_path / "compare.md")][0].startswith("failed: ")


@pytest.mark.ranks
def test_compare_is_not_started_under_mpirun(tmp_path):
    r = compare("cohesive_failure_2d", "--stabiliser", "none", "--out", tmp_path, ranks=2)
    assert r.returncode == 2 and "without mpirun" in r.stderr


def test_compare_tables_what_the_case_records(tmp_path):
    """A case with probes and wall forces (docs/examples/slope_2d.py): a second table gives each
    run's probe displacements at the end and the peak force on each named wall, when and its
    components then, from its diagnostics.csv; the weaker slope moves more."""
    from mpisph.io.diagnostics import read_diagnostics
    r = compare(ROOT / "docs" / "examples" / "slope_2d.py", "--vary", "cohesion=2e3,4e3", "--set", "beta=60", "dp=0.2",
                "t_end=0.3", "output_interval=0.3", "--out", tmp_path)
    assert r.returncode == 0, r.stderr
    text = (tmp_path / "compare.md").read_text()
    header = ("| cohesion (" + str(ROOT / "docs" / "examples" / "slope_2d.py") + ") | crest's displacement at the end [m] "
              "| toe's displacement at the end [m] | peak force on back, its size [N/m] | back: at t [s] "
              "| back: F_x then [N/m] | back: F_y then [N/m] |")
    assert header in text
    rows = text.split("What the case records (diagnostics.csv):")[1].splitlines()
    rows = [line for line in rows if line.startswith(("| 2e3 |", "| 4e3 |"))]
    crest = {line.split(" | ")[0][2:]: float(line.split(" | ")[1]) for line in rows}
    for value in ("2e3", "4e3"):
        d = read_diagnostics(tmp_path / value / "diagnostics.csv")
        assert crest[value] == pytest.approx(float(np.hypot(d["crest_ux"][-1], d["crest_uy"][-1])), rel=1e-3)
    assert crest["2e3"] > crest["4e3"]
    cells = {line.split(" | ")[0][2:]: [float(c) for c in line.strip(" |").split(" | ")[1:]] for line in rows}
    for value in ("2e3", "4e3"):
        d = read_diagnostics(tmp_path / value / "diagnostics.csv")
        size = np.hypot(d["force_back_x"], d["force_back_y"])
        k = int(np.argmax(size))
        assert cells[value][2:] == pytest.approx([size[k], d["t"][k], d["force_back_x"][k], d["force_back_y"][k]],
                                                 rel=1e-3)


def test_the_pictures_frame_the_material_not_the_walls():
    """The panels span the moving particles of every run, widened by a twentieth, in x and the
    last axis: a tank's walls twice the material's height (a probe's slope, half its panels empty)
    are left out."""
    from mpisph.compare import _material_box
    from mpisph.particles import MOVING, WALL
    runs = {}
    for name, top in (("a", 1.0), ("b", 2.0)):
        x = np.array([[0.0, 0.0], [4.0, top], [-1.0, 10.0], [9.0, -1.0]])
        runs[name] = {"x": x, "kind": np.array([MOVING, MOVING, WALL, WALL], np.int8)}
    lo, hi = _material_box(runs)
    assert lo == pytest.approx((-0.2, -0.2)) and hi == pytest.approx((4.2, 2.2))
