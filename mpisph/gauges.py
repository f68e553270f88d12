"""Gauges declared by position in a case: fields sampled at points, along lines and over planes, and
the top of the material over stations along a line; each a CSV time series ``gauge_<name>.csv`` in
the output directory, one row per row of diagnostics.csv.

A ``Gauge`` samples fields by Shepard-normalised SPH interpolation over the moving particles,

    f(x) = sum_j f_j W(x - x_j) V_j / sum_j W(x - x_j) V_j,   V_j = m_j / rho_j,

and records the kernel sum S(x) = sum_j W V_j beside them: about 1 inside the material, 0 outside
it, 1/2 near a free surface, so a line of points also shows where the material is. The sums run
over each rank's owned particles and are added over ranks, so a point is sampled whole wherever
the slabs cut (their last bits depend on the partition, as any global sum does). Where S = 0 the
fields are written as nan. Vectors are written per component (``v`` -> ``vx``, ``vy``[, ``vz``]),
tensors too (``stress`` -> ``stress_xx``, ``stress_yy``, ``stress_zz``, ``stress_xy``, ...); the
points' positions are in ``gauge_<name>_points.csv``.
A row visits every owned particle once per point, without a cell list: keep gauges to hundreds of
points, or record them less often (``diagnostics_every``).

A ``SurfaceGauge`` records, over each station (a point of the horizontal coordinates), the top of
the material: the highest moving particle within half a particle spacing of the station's vertical
line, plus dp / 2 (nan where there is none); a maximum over ranks, exact on any rank count.
"""

import os
from dataclasses import dataclass, field

import numpy as np
from mpi4py import MPI
from numba import njit

from .errors import InputError
from .io.diagnostics import Diagnostics
from .kernels import w
from .particles import MOVING


@dataclass
class Gauge:
    """Fields sampled at ``points`` (n, dim): the name of a field each that the frames hold (``v``, ``p``,
    ``rho``..., and the scheme's output fields such as ``stress`` and ``von_mises``)."""

    name: str
    points: np.ndarray
    fields: tuple = ("v", "p")

    @classmethod
    def line(cls, name, start, end, count, fields=("v", "p")):
        """``count`` points evenly spaced from ``start`` to ``end`` (both included)."""
        s = np.linspace(0.0, 1.0, count)[:, None]
        return cls(name, (1.0 - s) * np.asarray(start, float) + s * np.asarray(end, float), tuple(fields))

    @classmethod
    def plane(cls, name, corner, u, v, counts, fields=("v", "p")):
        """A grid of counts[0] x counts[1] points over the parallelogram corner + a u + b v, a and b in [0, 1]."""
        a, b = np.meshgrid(np.linspace(0.0, 1.0, counts[0]), np.linspace(0.0, 1.0, counts[1]), indexing="ij")
        corner, u, v = (np.asarray(c, float) for c in (corner, u, v))
        return cls(name, corner + a.ravel()[:, None] * u + b.ravel()[:, None] * v, tuple(fields))


@dataclass
class SurfaceGauge:
    """The top of the material over ``stations`` (n, dim - 1): x in 2D, (x, y) in 3D."""

    name: str
    stations: np.ndarray = field(default_factory=lambda: np.zeros((0, 1)))


@njit(cache=True)
def interpolation_sums(n, kind, x, mass, rho, values, points, k, support, out):
    """out[p] += (sum_j W V_j, sum_j W V_j values_j[:]) over the moving particles j in [0, n) within
    ``support`` of points[p]."""
    dim = x.shape[1]
    s2 = support * support
    for j in range(n):
        if kind[j] != MOVING:
            continue
        vol = mass[j] / rho[j]
        for p in range(points.shape[0]):
            r2 = 0.0
            for a in range(dim):
                d = points[p, a] - x[j, a]
                r2 += d * d
            if r2 >= s2:
                continue
            wv = w(np.sqrt(r2), k) * vol
            out[p, 0] += wv
            for c in range(values.shape[1]):
                out[p, 1 + c] += wv * values[j, c]


@njit(cache=True)
def surface_heights(n, kind, x, stations, half_width, out):
    """out[s] = max(out[s], top coordinate) over the moving particles in [0, n) whose horizontal
    coordinates lie within ``half_width`` of stations[s] along every horizontal axis."""
    dim = x.shape[1]
    for j in range(n):
        if kind[j] != MOVING:
            continue
        for s in range(stations.shape[0]):
            inside = True
            for a in range(dim - 1):
                if abs(x[j, a] - stations[s, a]) > half_width:
                    inside = False
                    break
            if inside and x[j, dim - 1] > out[s]:
                out[s] = x[j, dim - 1]


VTK_SYMMETRIC = ("xx", "yy", "zz", "xy", "yz", "xz")  # a packed symmetric 3 x 3 tensor (tensors.py)


def _columns(field, dim):
    """The column names of a particle field ``field`` (particles.Field) in ``dim`` dimensions: its
    name for a scalar, ``vx``, ``vy``[, ``vz``] for a vector, ``stress_xx``, ... for a symmetric
    tensor packed (xx, yy, xy in 2D; VTK's six in 3D) and for a dim x dim tensor (``_xx``, ``_xy``, ...),
    else the name with the component's index."""
    name, shape = field.name, field.shape
    if shape == ():
        return [name]
    if shape == ("dim",):
        return [name + c for c in "xyz"[:dim]]
    if shape == (6,) or (shape == ("sym",) and dim == 3):
        return [f"{name}_{c}" for c in VTK_SYMMETRIC]
    if shape == ("sym",):
        return [f"{name}_{c}" for c in ("xx", "yy", "xy")]
    if shape == ("dim", "dim"):
        return [f"{name}_{a}{b}" for a in "xyz"[:dim] for b in "xyz"[:dim]]
    return [f"{name}{c}" for c in range(int(np.prod(field.shape_in(dim))))]


def _placed(g, dim):
    """(where, what, coordinates each) of a gauge in ``dim`` dimensions: its points as given, or a
    surface gauge's stations."""
    return (g.points, "points", dim) if isinstance(g, Gauge) else (g.stations, "stations", dim - 1)


def check_gauges(case):
    """Raise InputError for a gauge whose points, or a surface gauge whose stations, do not have
    the case's number of coordinates (dim; dim - 1 for the stations), or a name given twice."""
    names = [g.name for g in case.gauges]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise InputError(f"gauge names {', '.join(map(repr, twice))} are given twice: each names a file")
    for g in case.gauges:
        where, what, width = _placed(g, case.dim)
        shape = np.shape(where)
        if len(shape) != 2 or shape[1] != width or shape[0] == 0:
            raise InputError(f"gauge {g.name!r}: its {what} take {width} coordinate{'s' * (width > 1)} each in this "
                             f"{case.dim}D case, an array (n, {width}); it has shape {shape}")


def gauge_warnings(case):
    """A warning for each gauge with points, or stations, outside the case's domain, which record
    nothing (nan) there."""
    lo, hi = (np.asarray(c, float) for c in case.domain)
    out = []
    for g in case.gauges:
        where, _, width = _placed(g, case.dim)
        if np.shape(where)[1:] != (width,):
            continue  # check_gauges refuses it
        where = np.asarray(where, float)
        outside = np.any((where < lo[:width]) | (where > hi[:width]), axis=1)
        if outside.any():
            out.append(f"gauge {g.name!r}: {int(outside.sum())} of its {len(where)} points lie outside the domain "
                       f"{lo.tolist()} to {hi.tolist()} (the first at {where[outside][0].tolist()}), where they "
                       "record nan")
    return out


class GaugeRecorder:
    """Writes the case's gauges, one CSV each (``Diagnostics`` files: rank 0 writes, a restart
    continues them), and beside each the positions of its points or stations
    (``gauge_<name>_points.csv``: a row per point, p0, p1, ... in the order of the columns)."""

    def __init__(self, case, particles, comm, derived=()):
        """The columns of every gauge; InputError for a field that neither the particles nor the
        scheme's output fields ``derived`` (Scheme.derived) have (before anything is written: ``open``
        writes the files)."""
        self.comm = comm
        self.gauges = list(case.gauges)
        self.files = []
        self.columns = []
        self.dim = dim = case.dim
        fields = {f.name: f for f in (*particles.fields, *derived)}
        self.derived = {f.name for f in derived} & {f for g in self.gauges if isinstance(g, Gauge) for f in g.fields}
        for g in self.gauges:
            if isinstance(g, Gauge):
                missing = [f for f in g.fields if f not in fields]
                if missing:
                    raise InputError(f"gauge {g.name!r}: no particle field {', '.join(map(repr, missing))}; "
                                     f"the fields are {', '.join(sorted(fields))}")
                parts = [c for f in g.fields for c in _columns(fields[f], dim)]
                self.columns.append(["t"] + [f"p{i}_{c}" for i in range(len(g.points)) for c in ["kernel_sum"] + parts])
            else:
                self.columns.append(["t"] + [f"s{i}_top" for i in range(len(g.stations))])

    def open(self, out_dir, append, restart_time):
        """Open the gauges' files in ``out_dir`` (continued from ``restart_time`` when ``append``)
        and write their points' positions."""
        for g, columns in zip(self.gauges, self.columns):
            self.files.append(Diagnostics(out_dir, self.comm, columns, append, restart_time=restart_time,
                                          filename=f"gauge_{g.name}.csv"))
            if self.comm.rank == 0:
                self._write_points(out_dir, g)

    def _write_points(self, out_dir, g):
        where, what, width = _placed(g, self.dim)
        with open(os.path.join(out_dir, f"gauge_{g.name}_points.csv"), "w") as f:
            f.write(",".join(["point", *"xyz"[:width]]) + "\n")
            for i, row in enumerate(np.asarray(where, float)):
                f.write(",".join([f"{what[0]}{i}", *(repr(float(c)) for c in row)]) + "\n")

    def sample(self, sim):
        """{gauge name: {column: value}} of every gauge for the current state (collective)."""
        pa, n = sim.particles, sim.particles.n_owned
        arrays = pa.arrays
        if self.derived:
            arrays = {**arrays, **sim.parts.scheme.derived_fields(pa, n)}
        out = {}
        for g, f in zip(self.gauges, self.files):
            values = self._sample(sim, g, pa, n, arrays) if isinstance(g, Gauge) else self._tops(sim, g, pa, n)
            out[g.name] = dict(zip(f.columns[1:], values))
        return out

    def write(self, t, samples):
        """A row of every gauge's file at time ``t`` from ``sample``'s values."""
        for g, f in zip(self.gauges, self.files):
            f.record({"t": t, **samples[g.name]})

    def _sample(self, sim, g, pa, n, arrays):
        points = np.ascontiguousarray(np.asarray(g.points, float).reshape(-1, pa.dim))
        values = np.column_stack([arrays[f][:n].reshape(n, -1) for f in g.fields])
        local = np.zeros((len(points), 1 + values.shape[1]))
        kernel = sim.parts.kernel
        interpolation_sums(n, pa.kind, pa.x, pa.mass, pa.rho, np.ascontiguousarray(values), points, kernel.params,
                           kernel.support, local)
        total = np.empty_like(local)
        self.comm.Allreduce(local, total, op=MPI.SUM)
        with np.errstate(invalid="ignore", divide="ignore"):
            fields = np.where(total[:, :1] > 0, total[:, 1:] / total[:, :1], np.nan)
        return np.column_stack([total[:, 0], fields]).ravel().tolist()

    def _tops(self, sim, g, pa, n):
        stations = np.ascontiguousarray(np.asarray(g.stations, float).reshape(-1, pa.dim - 1))
        local = np.full(len(stations), -np.inf)
        surface_heights(n, pa.kind, pa.x, stations, 0.5 * sim.case.dp, local)
        top = np.empty_like(local)
        self.comm.Allreduce(local, top, op=MPI.MAX)
        return np.where(np.isfinite(top), top + 0.5 * sim.case.dp, np.nan).tolist()

    def close(self):
        for f in self.files:
            f.close()
