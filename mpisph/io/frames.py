"""Output frames: one VTKHDF UnstructuredGrid file per frame, written collectively.

A frame holds the whole global particle state.  Under ``/VTKHDF`` it follows
the VTKHDF 1.0 UnstructuredGrid layout (one partition, one vertex cell per
particle), which VTK's ``vtkHDFReader`` has read since VTK 9.1: ParaView 5.10
and later open it, Debian 12's ParaView 5.11 among them (PolyData, the layout
of format versions 1-2, needs VTK 9.3, ParaView 5.12).  ParaView 5.11 knows
the reader only by the extension ``.hdf``, which later releases still accept:

* ``Points`` (N, 3) float64, z = 0 in 2D;
* ``Connectivity`` = 0..N-1, ``Offsets`` = 0..N, ``Types`` = VTK_VERTEX (1)
  for every cell; ``NumberOfPoints``, ``NumberOfCells`` and
  ``NumberOfConnectivityIds`` hold N;
* ``PointData/<name>`` for every field but ``x``: 2-component vectors padded
  to 3, symmetric tensors as their 6 components in VTK's order (xx, yy, zz,
  xy, yz, xz; ParaView reads them as symmetric tensors; format 1 stored
  (3, 3) stresses flattened to 9, which a restart still reads); in 2D a
  packed symmetric 2 x 2 tensor (xx, yy, xy) goes among those 6 and a 2 x 2
  tensor into a 3 x 3 one (9 components), their z rows and columns 0, so
  that ParaView sees a tensor rather than a vector (formats 1-3 stored them
  as 3 and 4 components); the attributes ``mpisph_shape`` and
  ``mpisph_dtype`` record the original trailing shape and dtype, and
  ``mpisph_columns`` which stored columns hold its components;
* ``FieldData/time`` and ``FieldData/step``.

The top-level group ``/mpisph`` (ignored by VTK) carries ``format``,
``format_version``, ``time``, ``step``, ``configurations`` (the run's advection steps
since t = 0, which a restart goes on counting; frames written before it was stored
read 0), ``dim``, ``n_total``, ``params`` (JSON) and, written last, ``complete`` = 1.
The file is written as ``<path>.part`` and renamed once every rank has closed it.
Frames of format versions 1-2 (PolyData, ``frame_NNNNN.vtkhdf``) are still read:
restarts, ``read_frame`` and ``list_frames`` take them.
"""

import glob
import json
import os

import h5py
import numpy as np
from h5py import h5fd, h5p, h5s

from mpisph.errors import InputError
from mpisph.io.series import drop_from_series

FRAME_PREFIX = "frame_"
FRAME_SUFFIX = ".hdf"
EARLIER_SUFFIX = ".vtkhdf"  # format versions 1-2
FORMAT = "mpisph-frame"
FORMAT_VERSION = 4  # 2: symmetric tensors packed (tensors.py); 3: UnstructuredGrid, .hdf; 4: 2D tensors as 3D
VTKHDF_VERSION = (1, 0)
VTK_VERTEX = 1
REQUIRED = ("x", "gid", "kind")


def frame_path(out_dir, index):
    """Path of frame number ``index`` in ``out_dir`` (``frame_00012.hdf``)."""
    return os.path.join(out_dir, f"{FRAME_PREFIX}{index:05d}{FRAME_SUFFIX}")


def regular_frame_number(t, interval):
    """The number of the last output time at or before ``t``: frames are numbered by t / output_interval,
    so a run at ``t`` writes its next regular frame as this number + 1."""
    return int(np.floor(t / interval + 1e-9))


def _check_fields(comm, fields, dim):
    """Raise ValueError on every rank if any rank's ``fields`` are malformed.

    All ranks must pass the same names, dtypes and trailing shapes, and every
    array of a rank must have that rank's number of rows.
    """
    schema = [(k, np.asarray(a).dtype.str, np.shape(a)[1:])
              for k, a in fields.items()]
    rows = {np.shape(a)[0] if np.ndim(a) else -1 for a in fields.values()}
    everyone = comm.allgather((schema, len(rows) == 1))
    if any(s != schema for s, _ in everyone):
        raise ValueError("write_frame: ranks pass different field names, "
                         "dtypes or shapes")
    if not all(ok for _, ok in everyone):
        raise ValueError("write_frame: fields of one rank differ in length")
    names = [k for k, _, _ in schema]
    missing = [k for k in REQUIRED if k not in names]
    if missing:
        raise ValueError(f"write_frame: missing field(s) {missing}")
    if dict((k, s) for k, _, s in schema)["x"] != (dim,):
        raise ValueError(f"write_frame: x must have shape (n, {dim})")


# the stored columns of a 2D field's components among VTK's 3D ones
SYMMETRIC_2D_COLUMNS = (0, 1, 3)  # xx, yy, xy among xx, yy, zz, xy, yz, xz
TENSOR_2D_COLUMNS = (0, 1, 3, 4)  # xx, xy, yx, yy of a row-major 3 x 3 tensor


def _columns(shape, dim, symmetric):
    """(stored width, the stored columns holding the flat components) of a field of trailing
    ``shape``: a 2-component vector padded to 3, in 2D a packed symmetric tensor (``symmetric``)
    among VTK's 6 components and a 2 x 2 tensor as a 3 x 3 one, anything else as it is."""
    if dim == 2 and symmetric:
        return 6, SYMMETRIC_2D_COLUMNS
    if dim == 2 and shape == (2, 2):
        return 9, TENSOR_2D_COLUMNS
    if shape == (2,):
        return 3, (0, 1)
    width = int(np.prod(shape))
    return width, tuple(range(width))


def _stored(a, columns):
    """Local array as stored in PointData: bool -> int8, scalars 1-D, the rest 2-D with the
    field's flat components in the columns ``_columns`` gives and zeros elsewhere."""
    a = np.asarray(a)
    if a.dtype == np.bool_:
        a = a.astype(np.int8)
    if a.ndim == 1:
        return np.ascontiguousarray(a)
    flat = a.reshape(a.shape[0], int(np.prod(a.shape[1:])))
    width, cols = columns
    if cols == tuple(range(flat.shape[1])) and width == flat.shape[1]:
        return np.ascontiguousarray(flat)  # no copy for a contiguous field
    out = np.zeros((a.shape[0], width), dtype=a.dtype)
    out[:, cols] = flat
    return out


def _put(dset, start, data, dxpl):
    """Collectively write ``data`` to rows ``start:start+len(data)``.

    Every rank must call this, also with zero rows: a rank with nothing to
    write takes part with an empty selection (h5py's ``dset[...] = ...``
    skips the HDF5 call for an empty selection, which would deadlock).
    """
    if dset.size == 0:
        return
    data = np.ascontiguousarray(data, dtype=dset.dtype)
    fspace = dset.id.get_space()
    if len(data):
        mspace = h5s.create_simple(data.shape)
        fspace.select_hyperslab((start,) + (0,) * (data.ndim - 1), data.shape)
    else:
        data = np.zeros((1,) + dset.shape[1:], dtype=dset.dtype)
        mspace = h5s.create_simple(data.shape)
        mspace.select_none()
        fspace.select_none()
    dset.id.write(mspace, fspace, data, dxpl=dxpl)


def _write_cells(vtk, comm, n_total, off, n, dxpl):
    """One vertex cell per point: the cell counts, Connectivity, Offsets and Types."""
    root = comm.rank == 0
    for count in ("NumberOfCells", "NumberOfConnectivityIds"):
        _put(vtk.create_dataset(count, (1,), np.int64), 0, [n_total] if root else [], dxpl)
    last = comm.rank == comm.size - 1
    _put(vtk.create_dataset("Connectivity", (n_total,), np.int64), off, np.arange(off, off + n), dxpl)
    _put(vtk.create_dataset("Offsets", (n_total + 1,), np.int64), off,
         np.arange(off, off + n + last), dxpl)
    _put(vtk.create_dataset("Types", (n_total,), np.uint8), off, np.full(n, VTK_VERTEX, np.uint8), dxpl)


def write_frame(path, comm, fields, *, time, step, dim, params, symmetric=(), configurations=0):
    """Write one frame collectively over ``comm``.

    ``fields`` maps names to this rank's local arrays (owned particles only,
    possibly zero rows); it must contain ``x`` (n, dim), ``gid`` and
    ``kind``.  ``symmetric`` names the fields that hold a symmetric dim x dim
    tensor packed (tensors.py, a Field of shape ``("sym",)``).  ``time``,
    ``step``, ``configurations``, ``dim`` and ``params`` (JSON-able dict) are taken
    from rank 0.
    """
    _check_fields(comm, fields, dim)
    meta = comm.bcast((float(time), int(step), int(configurations), int(dim),
                       json.dumps(params, sort_keys=True)), root=0)
    time, step, configurations, dim, params_json = meta
    n = len(fields["x"])
    off = comm.exscan(n) or 0  # None on rank 0
    n_total = comm.allreduce(n)
    root = comm.rank == 0
    dxpl = h5p.create(h5p.DATASET_XFER)
    dxpl.set_dxpl_mpio(h5fd.MPIO_COLLECTIVE)
    part = path + ".part"

    with h5py.File(part, "w", driver="mpio", comm=comm) as f:
        info = f.create_group("mpisph")
        info.attrs["format"] = FORMAT
        info.attrs["format_version"] = FORMAT_VERSION
        info.attrs["time"] = np.float64(time)
        for key, value in (("step", step), ("configurations", configurations), ("dim", dim),
                           ("n_total", n_total)):
            info.attrs[key] = np.int64(value)
        info.attrs["params"] = params_json

        vtk = f.create_group("VTKHDF")
        vtk.attrs["Version"] = np.array(VTKHDF_VERSION, dtype=np.int64)
        vtk.attrs["Type"] = np.bytes_("UnstructuredGrid")  # fixed-length ASCII
        _put(vtk.create_dataset("NumberOfPoints", (1,), np.int64), 0,
             [n_total] if root else [], dxpl)
        points = _stored(fields["x"], _columns((dim,), dim, False))  # 2D positions padded to 3
        _put(vtk.create_dataset("Points", (n_total, 3), np.float64), off,
             points, dxpl)
        _write_cells(vtk, comm, n_total, off, n, dxpl)

        pdata = vtk.create_group("PointData", track_order=True)
        for name, a in fields.items():
            if name == "x":
                continue
            a = np.asarray(a)
            columns = _columns(a.shape[1:], dim, name in symmetric)
            local = _stored(a, columns)
            d = pdata.create_dataset(name, (n_total,) + local.shape[1:],
                                     local.dtype)
            d.attrs["mpisph_shape"] = json.dumps(list(a.shape[1:]))
            d.attrs["mpisph_dtype"] = a.dtype.str
            if a.ndim > 1:
                d.attrs["mpisph_columns"] = json.dumps(list(columns[1]))
            _put(d, off, local, dxpl)

        fdata = vtk.create_group("FieldData")
        for name, value in (("time", np.float64(time)), ("step", np.int64(step))):
            d = fdata.create_dataset(name, (1,), value.dtype)
            _put(d, 0, [value] if root else [], dxpl)

        f.flush()
        info.attrs["complete"] = np.int64(1)

    err = None
    if root:
        try:
            os.replace(part, path)
        except OSError as e:
            err = f"cannot rename {part} to {path}: {e}"
    err = comm.bcast(err, root=0)
    if err:
        raise OSError(err)


def _open(path):
    """Open a frame read-only without HDF5 file locking."""
    return h5py.File(path, "r", locking=False)


def _inspect(path):
    """Return the reason ``path`` is not a readable frame, or None."""
    if not os.path.exists(path):
        return "no such file"
    if not os.path.isfile(path):
        return "not a regular file"
    if not h5py.is_hdf5(path):
        return "not an HDF5 file"
    try:
        with _open(path) as f:
            info = f.get("mpisph")
            if info is None or info.attrs.get("format") != FORMAT:
                return "not an mpisph frame (format attribute missing)"
            if "complete" not in info.attrs:
                return "truncated or incomplete frame (no completion mark)"
            version = int(info.attrs["format_version"])
            if version > FORMAT_VERSION:
                return f"frame format version {version} is newer than " \
                       f"this mpisph ({FORMAT_VERSION})"
            n_total = int(info.attrs["n_total"])
            vtk = f["VTKHDF"]
            cells = "Connectivity" if version >= 3 else "Vertices/Connectivity"
            lengths = {"NumberOfPoints": int(vtk["NumberOfPoints"][0]),
                       "Points": len(vtk["Points"]),
                       cells: len(vtk[cells])}
            for name in REQUIRED[1:]:
                if name not in vtk["PointData"]:
                    return f"dataset PointData/{name} missing"
            lengths.update({f"PointData/{k}": len(d)
                            for k, d in vtk["PointData"].items()})
    except (OSError, KeyError, ValueError) as e:
        return f"unreadable or truncated HDF5 file ({e})"
    bad = {k: v for k, v in lengths.items() if v != n_total}
    if bad:
        return f"inconsistent dataset lengths (n_total = {n_total}, " + \
            ", ".join(f"{k} has {v}" for k, v in bad.items()) + ")"
    return None


def check_frame(path):
    """Raise InputError with one line naming ``path`` and what is wrong."""
    problem = _inspect(path)
    if problem:
        raise InputError(f"frame {path}: {problem}")


def frame_rows(path):
    """How many particles (walls included) the frame ``path`` holds."""
    check_frame(path)
    with _open(path) as f:
        return int(f["mpisph"].attrs["n_total"])


def read_rows(path, start=0, stop=None):
    """The stored rows [start, stop) of a frame, in file order: every field in its original shape
    and dtype (``x`` is (n, dim)), plus ``t``, ``step``, ``configurations``, ``dim`` and ``params``."""
    check_frame(path)
    with _open(path) as f:
        info = f["mpisph"].attrs
        dim = int(info["dim"])
        rows = slice(start, stop)
        out = {"x": f["VTKHDF/Points"][rows, :dim]}
        for name, d in f["VTKHDF/PointData"].items():
            shape = tuple(json.loads(d.attrs["mpisph_shape"]))
            a = d[rows]
            if shape:
                columns = json.loads(d.attrs.get("mpisph_columns", "null")) or slice(int(np.prod(shape)))
                a = a[:, columns].reshape((len(a),) + shape)
            out[name] = a.astype(np.dtype(d.attrs["mpisph_dtype"]), copy=False)
        out.update({"t": float(info["time"]), "step": int(info["step"]),
                    "configurations": int(info.get("configurations", 0)),
                    "dim": dim, "params": json.loads(info["params"])})
    return out


def read_frame(path, walls=False):
    """Read a frame serially; arrays of moving particles sorted by gid.

    With ``walls=True`` all particles (sorted by gid) are returned. Keys as ``read_rows``.
    """
    out = read_rows(path)
    order = np.argsort(out["gid"], kind="stable")
    if not walls:
        order = order[out["kind"][order] == 0]
    return {k: (np.ascontiguousarray(a[order]) if isinstance(a, np.ndarray) else a) for k, a in out.items()}


def _time_key(path):
    """(time, step) of a frame, or None if it is not a complete frame."""
    if _inspect(path):
        return None
    with _open(path) as f:
        info = f["mpisph"].attrs
        return float(info["time"]), int(info["step"])


def frame_time(path):
    """The simulated time of the complete frame ``path``, read from its attributes alone."""
    return _time_key(path)[0]


def _frame_files(out_dir):
    """The files of ``out_dir`` named as frames, of this format or the earlier one."""
    return [p for suffix in (FRAME_SUFFIX, EARLIER_SUFFIX)
            for p in glob.glob(os.path.join(glob.escape(out_dir), f"{FRAME_PREFIX}*{suffix}"))]


def list_frames(out_dir):
    """Complete frames in ``out_dir`` ordered by stored time, then step."""
    keyed = [(_time_key(p), p) for p in _frame_files(out_dir)]
    return [p for k, p in sorted((k, p) for k, p in keyed if k is not None)]


def incomplete_frames(out_dir):
    """{path: why} of the files of ``out_dir`` named as frames that are no complete frame (a write
    cut short, another file), which ``list_frames`` leaves out."""
    return {p: why for p in sorted(_frame_files(out_dir)) if (why := _inspect(p))}


def frame_cases(out_dir):
    """{case: how many of its complete frames} in ``out_dir``, from the frames' attributes alone."""
    cases = {}
    for p in _frame_files(out_dir):
        if not _inspect(p):
            with _open(p) as f:
                case = json.loads(f["mpisph"].attrs["params"]).get("case")
            cases[case] = cases.get(case, 0) + 1
    return cases


def frames_after(out_dir, time):
    """The complete frames of ``out_dir`` stored after ``time``."""
    return [p for p in _frame_files(out_dir) if (_time_key(p) or (-np.inf,))[0] > time]


def frames_kept_and_numbered_from(out_dir, time, index):
    """The complete frames of ``out_dir`` stored at or before ``time`` whose number is ``index`` or
    more: those that a run starting at ``time`` there, whose next frame is number ``index``, would
    write over."""
    numbers = {p: os.path.basename(p)[len(FRAME_PREFIX):-len(FRAME_SUFFIX)] for p in _frame_files(out_dir)
               if p.endswith(FRAME_SUFFIX)}
    return sorted(p for p, number in numbers.items() if number.isdigit() and int(number) >= index
                  and (_time_key(p) or (np.inf,))[0] <= time)


def drop_frames_after(out_dir, time):
    """Delete the frames of ``out_dir`` stored after ``time`` and their entries in its series file
    (io/series.py): a run that starts at ``time`` there replaces what an earlier run wrote later
    (``time`` = -inf: every frame, for a run from the start). Files that are not complete frames stay."""
    late = frames_after(out_dir, time)
    for p in late:
        os.remove(p)
    drop_from_series(out_dir, [os.path.basename(p) for p in late])
