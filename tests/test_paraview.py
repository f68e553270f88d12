"""A frame written by a 2-rank run opens in VTK's own VTKHDF reader (what ParaView uses)."""

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
