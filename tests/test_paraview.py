"""A frame written by a 2-rank run opens in VTK's own VTKHDF reader (what ParaView uses)."""

import os

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOHDF import vtkHDFReader

from mpisph.io.frames import list_frames, read_frame
from mpirun import mpisph


def test_solver_frame_through_vtk_reader(tmp_path):
    r = mpisph(["dam_break_2d", "--set", "dp=0.1", "--t-end", "0.05", "--output-interval", "0.05",
                "--out", tmp_path, "--quiet"], ranks=2)
    assert r.returncode == 0, r.stderr
    path = list_frames(tmp_path)[-1]
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


def test_series_file_lists_the_frames_with_their_times(tmp_path):
    """frames.vtkhdf.series (ParaView's JSON file series) names every frame with its simulated time,
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
