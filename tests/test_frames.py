"""Serial tests of frame files (one MPI rank) and of the diagnostics CSV."""

import shutil
from pathlib import Path

import h5py
import numpy as np
import pytest
from mpi4py import MPI

from mpisph.errors import InputError
from mpisph.io.diagnostics import Diagnostics, read_diagnostics
from mpisph.io.frames import (check_frame, drop_frames_after, frame_path, list_frames,
                              read_frame, write_frame)
from mpisph.io.series import SERIES_NAME, add_to_series

COMM = MPI.COMM_WORLD
DATA = Path(__file__).parent / "data"
PARAMS = {"case": "dam_break", "h": 0.01, "n": 40, "periodic": [True, False]}


def make_fields(dim, n=50, n_walls=10, seed=0):
    """Shuffled particles with scalar, vector, tensor and integer fields."""
    rng = np.random.default_rng(seed)
    total = n + n_walls
    kind = np.r_[np.zeros(n, np.int8), np.ones(n_walls, np.int8)]
    perm = rng.permutation(total)
    return {
        "x": rng.random((total, dim)),
        "v": rng.standard_normal((total, dim)),
        "rho": 1000 + rng.random(total),
        "p": rng.standard_normal(total),
        "sigma": rng.standard_normal((total, 3, 3)),
        "gid": (np.arange(total, dtype=np.int64) * 7)[perm],
        "kind": kind[perm],
        "flag": (rng.random(total) < 0.5).astype(np.int8),
        "ncount": rng.integers(0, 100, total),
        "active": rng.random(total) < 0.5,
    }


def write(path, fields, dim, time=0.5, step=10):
    write_frame(str(path), COMM, fields, time=time, step=step, dim=dim,
                params=PARAMS, configurations=4)


def expected(fields, walls):
    order = np.argsort(fields["gid"])
    if not walls:
        order = order[fields["kind"][order] == 0]
    return {k: a[order] for k, a in fields.items()}


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("walls", [False, True])
def test_round_trip(tmp_path, dim, walls):
    fields = make_fields(dim)
    path = frame_path(tmp_path, 3)
    write(path, fields, dim)
    got = read_frame(path, walls=walls)
    assert got["t"] == 0.5 and got["step"] == 10 and got["configurations"] == 4 and got["dim"] == dim
    assert got["params"] == PARAMS
    for key, want in expected(fields, walls).items():
        assert got[key].dtype == want.dtype, key
        assert got[key].shape == want.shape, key
        assert got[key].tobytes() == want.tobytes(), key
    assert set(got) == set(fields) | {"t", "step", "configurations", "dim", "params"}


def test_empty_frame(tmp_path):
    fields = make_fields(2, n=0, n_walls=0)
    path = frame_path(tmp_path, 0)
    write(path, fields, 2)
    got = read_frame(path, walls=True)
    for key, want in fields.items():
        assert got[key].shape == want.shape and got[key].dtype == want.dtype


def test_vtkhdf_layout(tmp_path):
    """VTKHDF 1.0 UnstructuredGrid of vertex cells: the layout VTK 9.1 and later read."""
    path = frame_path(tmp_path, 0)
    assert path.endswith("frame_00000.hdf")
    write(path, make_fields(2, n=5, n_walls=0), 2)
    with h5py.File(path, "r") as f:
        vtk = f["VTKHDF"]
        assert vtk.attrs["Type"] == b"UnstructuredGrid"
        assert vtk.attrs["Type"].dtype == np.dtype("S16")
        assert list(vtk.attrs["Version"]) == [1, 0]
        for count in ("NumberOfPoints", "NumberOfCells", "NumberOfConnectivityIds"):
            assert list(vtk[count]) == [5]
        assert vtk["Points"].shape == (5, 3) and not vtk["Points"][:, 2].any()
        assert list(vtk["Offsets"]) == list(range(6))
        assert list(vtk["Connectivity"]) == list(range(5))
        assert vtk["Types"].dtype == np.uint8 and list(vtk["Types"]) == [1] * 5
        assert vtk["PointData/v"].shape == (5, 3)
        assert vtk["PointData/sigma"].shape == (5, 9)
        assert "Vertices" not in vtk
        assert f["mpisph"].attrs["complete"] == 1
        assert f["mpisph"].attrs["format_version"] == 4


@pytest.mark.parametrize("dim", [2, 3])
def test_tensors_are_stored_as_vtk_tensors(tmp_path, dim):
    """A packed symmetric dim x dim tensor is stored as VTK's 6 components (xx, yy, zz, xy, yz, xz)
    and a dim x dim tensor as a row-major 3 x 3 one, the z entries 0 in 2D, so that ParaView reads
    both as tensors; each reads back to its bits."""
    rng = np.random.default_rng(1)
    fields = make_fields(dim, n=7, n_walls=0)
    fields["strain"] = rng.standard_normal((7, dim * (dim + 1) // 2))
    fields["grad"] = rng.standard_normal((7, dim, dim))
    path = frame_path(tmp_path, 0)
    write_frame(str(path), COMM, fields, time=0.5, step=10, dim=dim, params=PARAMS, symmetric=["strain"])
    with h5py.File(path, "r") as f:
        strain, grad = f["VTKHDF/PointData/strain"][()], f["VTKHDF/PointData/grad"][()]
    assert strain.shape == (7, 6) and grad.shape == (7, 9)
    if dim == 2:
        np.testing.assert_array_equal(strain[:, [0, 1, 3]], fields["strain"])
        assert not strain[:, [2, 4, 5]].any()
        np.testing.assert_array_equal(grad.reshape(7, 3, 3)[:, :2, :2], fields["grad"])
        assert not grad.reshape(7, 3, 3)[:, 2].any() and not grad.reshape(7, 3, 3)[:, :, 2].any()
    got = read_frame(path, walls=True)
    for key, want in expected(fields, True).items():
        assert got[key].shape == want.shape and got[key].tobytes() == want.tobytes(), key
    from vtkmodules.vtkIOHDF import vtkHDFReader
    reader = vtkHDFReader()
    reader.SetFileName(str(path))
    reader.Update()
    data = reader.GetOutput().GetPointData()
    assert data.GetArray("strain").GetNumberOfComponents() == 6
    assert data.GetArray("grad").GetNumberOfComponents() == 9


def test_earlier_format_is_read(tmp_path):
    """A frame of format version 2 (VTKHDF 2.0 PolyData, ``.vtkhdf``; tests/data, written by the
    writer before version 3 with make_fields(3, n=6, n_walls=2)) reads as it was written, and
    list_frames and drop_frames_after see it beside frames of this version."""
    earlier = tmp_path / "frame_00007.vtkhdf"
    shutil.copy(DATA / "frame_00007.vtkhdf", earlier)
    fields = make_fields(3, n=6, n_walls=2)
    got = read_frame(str(earlier), walls=True)
    assert got["t"] == 0.25 and got["step"] == 7 and got["params"] == PARAMS
    for key, want in expected(fields, True).items():
        assert got[key].dtype == want.dtype and got[key].tobytes() == want.tobytes(), key
    write(frame_path(tmp_path, 8), fields, 3, time=0.5, step=8)
    assert list_frames(tmp_path) == [str(earlier), frame_path(tmp_path, 8)]
    drop_frames_after(tmp_path, 0.3)
    assert list_frames(tmp_path) == [str(earlier)]


def test_vtk_reader(tmp_path):
    import vtk  # a declared test dependency: no skip
    from vtkmodules.util.numpy_support import vtk_to_numpy
    try:
        reader = vtk.vtkHDFReader()
    except AttributeError:
        from vtkmodules.vtkIOHDF import vtkHDFReader
        reader = vtkHDFReader()
    fields = make_fields(3)
    path = frame_path(tmp_path, 1)
    write(path, fields, 3)
    reader.SetFileName(path)
    reader.Update()
    out = reader.GetOutput()
    n = len(fields["gid"])
    assert out.GetNumberOfPoints() == n
    assert out.GetNumberOfCells() == n
    assert {out.GetCellType(i) for i in range(n)} == {vtk.VTK_VERTEX}
    pd = out.GetPointData()
    assert np.array_equal(vtk_to_numpy(pd.GetArray("rho")), fields["rho"])
    assert pd.GetArray("v").GetNumberOfComponents() == 3
    assert np.array_equal(vtk_to_numpy(out.GetPoints().GetData()), fields["x"])


def test_list_frames(tmp_path):
    assert list_frames(tmp_path) == []
    assert list_frames(tmp_path / "missing") == []
    fields = make_fields(2, n=4, n_walls=1)
    # File index order differs from time order on purpose.
    for index, (time, step) in enumerate([(0.2, 20), (0.1, 10), (0.2, 15)]):
        write(frame_path(tmp_path, index), fields, 2, time, step)
    (tmp_path / "frame_00009.hdf.part").write_bytes(b"partial")
    assert list_frames(tmp_path) == [frame_path(tmp_path, i) for i in (1, 2, 0)]


def test_drop_frames_after(tmp_path):
    """Frames stored after the time go, with their series entries; earlier frames, the frame at
    the time itself and files that are not complete frames stay; -inf takes every frame."""
    import json

    fields = make_fields(2, n=4, n_walls=1)
    for index, time in enumerate([0.0, 0.1, 0.2, 0.3]):
        write(frame_path(tmp_path, index), fields, 2, time, index)
        add_to_series(tmp_path, frame_path(tmp_path, index), time)
    (tmp_path / "frame_00009.hdf").write_bytes(b"not a frame")

    def series():
        return [e["name"] for e in json.loads((tmp_path / SERIES_NAME).read_text())["files"]]

    drop_frames_after(tmp_path, 0.1)
    assert list_frames(tmp_path) == [frame_path(tmp_path, i) for i in (0, 1)]
    assert series() == ["frame_00000.hdf", "frame_00001.hdf"]
    drop_frames_after(tmp_path, -np.inf)
    assert list_frames(tmp_path) == [] and series() == []
    assert (tmp_path / "frame_00009.hdf").exists()


def check_fails(path, message):
    with pytest.raises(InputError) as err:
        check_frame(str(path))
    text = str(err.value)
    assert str(path) in text and message in text and "\n" not in text


def test_check_missing_and_garbage(tmp_path):
    check_fails(tmp_path / "nope.hdf", "no such file")
    garbage = tmp_path / "garbage.hdf"
    garbage.write_bytes(b"this is not hdf5 at all\n" * 100)
    check_fails(garbage, "not an HDF5 file")


def test_check_truncated(tmp_path):
    path = frame_path(tmp_path, 0)
    write(path, make_fields(3, n=2000), 3)
    data = open(path, "rb").read()
    cut = tmp_path / "cut.hdf"
    cut.write_bytes(data[:len(data) // 2])
    check_fails(cut, "truncated")
    with pytest.raises(InputError):
        read_frame(str(cut))


def test_check_incomplete_and_foreign(tmp_path):
    path = frame_path(tmp_path, 0)
    write(path, make_fields(2), 2)
    incomplete = tmp_path / "incomplete.hdf"
    shutil.copy(path, incomplete)
    with h5py.File(incomplete, "a") as f:
        del f["mpisph"].attrs["complete"]
    check_fails(incomplete, "no completion mark")
    foreign = tmp_path / "foreign.h5"
    with h5py.File(foreign, "w") as f:
        f["data"] = np.arange(3)
    check_fails(foreign, "not an mpisph frame")


def test_check_inconsistent_lengths(tmp_path):
    path = frame_path(tmp_path, 0)
    write(path, make_fields(2), 2)
    with h5py.File(path, "a") as f:
        del f["VTKHDF/PointData/rho"]
        f["VTKHDF/PointData/rho"] = np.zeros(3)
    check_fails(path, "PointData/rho has 3")


def test_diagnostics_serial(tmp_path):
    cols = ["t", "step", "energy"]
    with Diagnostics(tmp_path, COMM, cols) as diag:
        for step in range(5):
            diag.record({"t": step / 3, "step": step, "energy": np.pi * step})
    d = read_diagnostics(tmp_path / "diagnostics.csv")
    assert np.array_equal(d["t"], np.arange(5) / 3)
    assert np.array_equal(d["energy"], np.pi * np.arange(5))
    # Restart from t = 1/3: later rows are dropped, then the run continues.
    with Diagnostics(tmp_path, COMM, cols, append=True,
                     restart_time=1 / 3) as diag:
        diag.record({"t": 0.5, "step": 2, "energy": 1.0})
    d = read_diagnostics(tmp_path / "diagnostics.csv")
    assert list(d["step"]) == [0, 1, 2] and d["t"][-1] == 0.5
    with pytest.raises(InputError, match="columns differ.*it has step,energy,"):
        Diagnostics(tmp_path, COMM, ["t", "other"], append=True)


def test_diagnostics_widened_on_restart(tmp_path):
    """A file of an earlier version, without a column this run writes, continues with nan there."""
    with Diagnostics(tmp_path, COMM, ["t", "energy"]) as diag:
        for step in range(3):
            diag.record({"t": step / 3, "energy": np.pi * step})
    with Diagnostics(tmp_path, COMM, ["t", "iterations", "energy"], append=True, restart_time=1 / 3) as diag:
        diag.record({"t": 0.5, "iterations": 4, "energy": 1.0})
    d = read_diagnostics(tmp_path / "diagnostics.csv")
    assert list(d) == ["t", "iterations", "energy"]
    assert np.array_equal(d["t"], [0.0, 1 / 3, 0.5]) and np.array_equal(d["energy"], [0.0, np.pi, 1.0])
    assert np.isnan(d["iterations"][:2]).all() and d["iterations"][2] == 4
