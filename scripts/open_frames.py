"""Open frames (or a series file) the way a viewer does and print what it found, one JSON line each.

    pvpython scripts/open_frames.py PATH ...            ParaView's OpenDataFile (the File > Open of
                                                        its GUI: the reader chosen by the extension)
    PYTHON scripts/open_frames.py --vtk PATH ...         VTK's vtkHDFReader, under any Python with vtk

Each line: {"path", "reader", "type", "points", "cells", "arrays": {name: components}, "times",
"sums": {name: sum of the array}}, or {"path", "error"} when nothing could read it. mpisph is not
imported: the script runs under ParaView's own Python (tests/test_paraview.py runs it under Debian's
pvpython and under the oldest VTK mpisph supports; scripts/paraview_check.py under both for every case).
"""

import json
import sys


def _arrays(point_data):
    """{name: number of components} and {name: sum of its values} of a vtkPointData."""
    from vtkmodules.util.numpy_support import vtk_to_numpy

    arrays, sums = {}, {}
    for i in range(point_data.GetNumberOfArrays()):
        a = point_data.GetArray(i)
        arrays[a.GetName()] = a.GetNumberOfComponents()
        sums[a.GetName()] = float(vtk_to_numpy(a).astype(float).sum())
    return arrays, sums


def _described(path, reader, data, times):
    arrays, sums = _arrays(data.GetPointData())
    return {"path": path, "reader": reader, "type": data.GetClassName(), "points": data.GetNumberOfPoints(),
            "cells": data.GetNumberOfCells(), "arrays": arrays, "times": times, "sums": sums}


def with_vtk(path):
    """The frame ``path`` through vtkHDFReader."""
    from vtkmodules.vtkIOHDF import vtkHDFReader

    reader = vtkHDFReader()
    if not reader.CanReadFile(path):
        return {"path": path, "error": "vtkHDFReader cannot read it"}
    reader.SetFileName(path)
    reader.Update()
    data = reader.GetOutputDataObject(0)
    if data is None:
        return {"path": path, "error": "vtkHDFReader returned no data"}
    return _described(path, "vtkHDFReader", data, [])


def with_paraview(path):
    """``path`` (a frame or a series file) through ParaView's OpenDataFile, at its last time."""
    from paraview import servermanager
    from paraview.simple import OpenDataFile

    try:
        proxy = OpenDataFile(path)
    except Exception as e:  # ParaView raises a bare RuntimeError when no reader takes the file
        return {"path": path, "error": str(e).strip()}
    if proxy is None:
        return {"path": path, "error": "no reader"}
    times = [float(t) for t in getattr(proxy, "TimestepValues", None) or []]
    proxy.UpdatePipeline(times[-1] if times else 0.0)
    data = servermanager.Fetch(proxy)
    return _described(path, proxy.GetXMLName(), data, times)


def main(argv):
    use_vtk = "--vtk" in argv
    paths = [a for a in argv if a != "--vtk"]
    for path in paths:
        print(json.dumps(with_vtk(path) if use_vtk else with_paraview(path)), flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
