"""Pictures of 3D runs (mpisph/render.py): the frames nearest the asked times, perspective views by
speed, and the particles of a plane cut with their field."""

import numpy as np
import pytest
from mpi4py import MPI

from mpisph import render
from mpisph.errors import InputError
from mpisph.io.frames import frame_path, write_frame

DP = 0.1


def cube_run(directory):
    """A 10^3 cube on a floor layer, frames at t = 0, 0.5, 1; plastic strain = height * t."""
    directory.mkdir()
    g = (np.arange(10) + 0.5) * DP
    x = np.stack([a.ravel() for a in np.meshgrid(g - 0.5, g - 0.5, g, indexing="ij")], axis=1)
    floor = np.stack([a.ravel() for a in np.meshgrid(g - 0.5, g - 0.5, [-0.5 * DP], indexing="ij")], axis=1)
    n, nw = len(x), len(floor)
    for index, t in enumerate((0.0, 0.5, 1.0)):
        fields = {"x": np.r_[x, floor], "gid": np.arange(n + nw, dtype=np.int64),
                  "kind": np.r_[np.zeros(n, np.int8), np.ones(nw, np.int8)],
                  "mass": np.full(n + nw, 1000.0 * DP**3), "rho": np.full(n + nw, 1000.0),
                  "v": np.r_[np.c_[np.full(n, t), np.zeros((n, 2))], np.zeros((nw, 3))],
                  "plastic_strain": np.r_[x[:, 2] * t, np.zeros(nw)]}
        write_frame(frame_path(str(directory), index), MPI.COMM_SELF, fields, time=t, step=index, dim=3,
                    params={"case": "fake_cube", "dp": DP})
    return directory


def is_png(path):
    with open(path, "rb") as f:
        return f.read(8) == b"\x89PNG\r\n\x1a\n"


def test_frames_nearest_the_asked_times(tmp_path):
    run = cube_run(tmp_path / "run")
    assert [f["t"] for f in render.frames_at(run, (0.1, 0.7, 5.0))] == [0.0, 0.5, 1.0]


def test_snapshots_and_a_plane_cut_are_drawn(tmp_path):
    run = cube_run(tmp_path / "run")
    assert is_png(render.snapshots_png(run, (0.0, 1.0), tmp_path / "speed.png", title="cube"))
    diagonal = np.array([1.0, 1.0, 0.0]) / np.sqrt(2.0)
    assert is_png(render.slice_png(run, (0.5, 1.0), tmp_path / "cut.png", (0.0, 0.0, 0.0), diagonal, (0, 0, 1.0)))


def test_a_grid_of_plane_cuts_a_row_per_run(tmp_path):
    """Two runs, a row each, coloured to a shared maximum or to each panel's own 99th percentile."""
    runs = {"first": cube_run(tmp_path / "a"), "second": cube_run(tmp_path / "b")}
    diagonal = np.array([1.0, 1.0, 0.0]) / np.sqrt(2.0)
    for each in (False, True):
        png = tmp_path / f"grid_{each}.png"
        assert is_png(render.slice_grid_png(runs, (0.5, 1.0), png, (0.0, 0.0, 0.0), diagonal, (0, 0, 1.0), each=each))


def test_the_plane_cut_keeps_the_particles_within_half_a_spacing():
    """The vertical plane x = y through the axis of a cube lattice centred on it: a column of
    particles on the diagonal (10 per layer), at their distance along the cut and their height."""
    g = (np.arange(10) + 0.5) * DP - 0.5
    x = np.stack([a.ravel() for a in np.meshgrid(g, g, [0.05], indexing="ij")], axis=1)
    diagonal = np.array([1.0, 1.0, 0.0]) / np.sqrt(2.0)
    a, b, dist = render.plane_coordinates(x, (0, 0, 0), diagonal, (0, 0, 1.0))
    near = dist < 0.5 * DP
    assert near.sum() == 10
    np.testing.assert_allclose(np.sort(a[near]), np.sqrt(2.0) * g)
    np.testing.assert_allclose(b[near], 0.05)


def test_a_missing_field_is_one_line(tmp_path):
    run = cube_run(tmp_path / "run")
    with pytest.raises(InputError, match="no field 'stress'"):
        render.slice_png(run, (1.0,), tmp_path / "cut.png", (0, 0, 0), (1, 0, 0), (0, 0, 1), field="stress")
