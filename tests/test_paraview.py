"""Frames open in the readers users have: VTK's own vtkHDFReader, newest (this venv) and oldest
supported (VTK 9.2.6, ParaView 5.11's generation, in .venv/oldest-vtk), and Debian 12's ParaView
5.11 through pvpython's OpenDataFile, frames and series alike (scripts/open_frames.py, judged by
scripts/paraview_check.py's problems(); both readers installed by scripts/bootstrap.sh test)."""

import os
import shutil
from pathlib import Path

import numpy as np
import pytest
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOHDF import vtkHDFReader

from mpisph.io.frames import list_frames, read_frame
from mpisph.io.series import SERIES_NAME
from mpirun import mpisph
from repo_script import load_script

pytestmark = pytest.mark.ranks  # tests/conftest.py

ROOT = Path(__file__).resolve().parent.parent
CHECK = load_script("paraview_check")  # opened: scripts/open_frames.py's lines; problems: what a reader missed
OLDEST_VTK = ROOT / ".venv" / "oldest-vtk" / "bin" / "python"
RUNS = {"dam_break_2d": ["--set", "dp=0.1", "--t-end", "0.02", "--output-interval", "0.01"],
        "cube_failure_3d": ["--set", "dp=0.2", "--t-end", "0.02", "--output-interval", "0.01"]}


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """{case: output directory} of a 2D fluid and a 3D soil (tensor fields), each on 2 ranks."""
    out = {}
    for case, args in RUNS.items():
        d = tmp_path_factory.mktemp(case)
        r = mpisph([case, *args, "--out", d, "--quiet"], ranks=2)
        assert r.returncode == 0, r.stderr
        out[case] = d
    return out


def test_solver_frame_through_vtk_reader(runs):
    """The newest VTK (this venv's) reads every particle's position and fields as written."""
    path = list_frames(runs["dam_break_2d"])[-1]
    ours = read_frame(path, walls=True)
    reader = vtkHDFReader()
    reader.SetFileName(str(path))
    reader.Update()
    grid = reader.GetOutput()
    assert grid.GetNumberOfPoints() == len(ours["gid"])
    data = grid.GetPointData()
    order = np.argsort(vtk_to_numpy(data.GetArray("gid")))
    np.testing.assert_array_equal(vtk_to_numpy(data.GetArray("rho"))[order], ours["rho"])
    points = vtk_to_numpy(grid.GetPoints().GetData())[order]
    np.testing.assert_array_equal(points[:, :2], ours["x"])
    np.testing.assert_array_equal(vtk_to_numpy(data.GetArray("v"))[order][:, :2], ours["v"])


@pytest.mark.parametrize("case", sorted(RUNS))
def test_frames_open_in_the_oldest_vtk(runs, case):
    """VTK 9.2.6 reads the frames whole: every point, every array with its components and values."""
    assert OLDEST_VTK.exists(), f"{OLDEST_VTK} missing: run bash scripts/bootstrap.sh test"
    frames = list_frames(runs[case])
    for seen, path in zip(CHECK.opened([str(OLDEST_VTK)], frames, "--vtk"), frames):
        assert CHECK.problems(seen, path) == []
        assert seen["reader"] == "vtkHDFReader"


@pytest.mark.parametrize("case", sorted(RUNS))
def test_frames_and_series_open_in_paraview(runs, case):
    """Debian 12's ParaView (pvpython's OpenDataFile, which picks the reader by the file's extension
    as File > Open does) opens a frame, and the series with the frames' physical times on its time
    axis, the last frame's data at the last time."""
    pvpython = shutil.which("pvpython")
    assert pvpython, "pvpython missing: run bash scripts/bootstrap.sh test (installs Debian's paraview)"
    frames = list_frames(runs[case])
    series = runs[case] / SERIES_NAME
    one, whole = CHECK.opened([pvpython, "--force-offscreen-rendering"], [frames[0], series])
    assert CHECK.problems(one, frames[0]) == []
    assert CHECK.problems(whole, frames[-1], [read_frame(f)["t"] for f in frames]) == []
    assert one["reader"] == whole["reader"] == "HDFReader"
    assert whole["times"][-1] > 0


def test_series_file_lists_the_frames_with_their_times(tmp_path):
    """frames.hdf.series (ParaView's JSON file series) names every frame with its simulated time,
    in order; a restart that rewrites a frame replaces its entry."""
    import json

    from mpisph.io.series import SERIES_NAME

    args = ["dam_break_2d", "--set", "dp=0.1", "--t-end", "0.03", "--output-interval", "0.01", "--out", tmp_path,
            "--quiet"]
    r = mpisph(args, ranks=2)
    assert r.returncode == 0, r.stderr
    frames = list_frames(tmp_path)
    assert len(frames) == 4

    def entries():
        series = json.loads((tmp_path / SERIES_NAME).read_text())
        assert series["file-series-version"] == "1.0"
        return [(e["name"], e["time"]) for e in series["files"]]

    expected = [(os.path.basename(f), read_frame(f)["t"]) for f in frames]
    assert entries() == expected
    r = mpisph(["dam_break_2d", "--restart", frames[1], "--out", tmp_path, "--quiet"], ranks=1)
    assert r.returncode == 0, r.stderr
    assert [name for name, _ in entries()] == [name for name, _ in expected]
    assert entries() == [(os.path.basename(f), read_frame(f)["t"]) for f in list_frames(tmp_path)]


def test_a_new_run_replaces_the_frames_of_an_earlier_one(tmp_path):
    """A shorter run from the start into the directory of a longer one leaves only its own frames
    in the directory and in the series (no stale later frames in ParaView's time axis); a restart
    from an earlier frame drops the frames after it before writing its own."""
    import json

    from mpisph.io.series import SERIES_NAME

    def run(t_end, *more):
        r = mpisph(["dam_break_2d", "--set", "dp=0.1", "--t-end", t_end, "--output-interval", "0.01",
                    "--out", tmp_path, "--quiet", *more], ranks=1)
        assert r.returncode == 0, r.stderr
        names = [e["name"] for e in json.loads((tmp_path / SERIES_NAME).read_text())["files"]]
        assert names == [os.path.basename(f) for f in list_frames(tmp_path)]
        return [read_frame(f)["t"] for f in list_frames(tmp_path)]

    assert len(run("0.04")) == 5
    times = run("0.02")
    assert len(times) == 3 and max(times) <= 0.02 + 1e-12
    run("0.04")
    times = run("0.02", "--restart", list_frames(tmp_path)[1])
    assert len(times) == 3 and max(times) <= 0.02 + 1e-12
