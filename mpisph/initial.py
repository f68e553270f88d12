"""Initial particles, from a case or from a frame to restart.

From a case, no rank builds the global arrays: the cuts come first, from a
histogram of the bodies' particles in which each rank counts one stretch of the
slab axis, then each rank generates the particles of its own slab from the
case's sources (sources.py). The cuts are those the solver's first balance
computes (the same histogram of moving particles), so nothing migrates. Global
ids are a source's offset plus the particle's index in it.

From a frame, each rank reads an equal run of its rows; the first migration of
the run sends each particle to the rank that owns its position.
"""

import numpy as np
from mpi4py import MPI

from .errors import InputError
from .io.frames import frame_rows, read_rows
from .parallel.decomposition import SlabDecomposition
from .particles import CLAMPED, MOVING, WALL, WALL_SLIP, Particles
from .sources import as_points
from .tensors import packed


def _initial(value, index, x, shape):
    """A body's or wall's initial field at the particles ``index`` (positions ``x``): zero for
    None, a function of positions, one value for all, or an array over the rows."""
    if value is None:
        return np.zeros((len(x),) + shape)
    if callable(value):
        return np.asarray(value(x), float).reshape((len(x),) + shape)
    value = np.asarray(value)
    if value.shape == shape:
        return np.broadcast_to(value, (len(x),) + shape)
    return value[index]


def _body_kind(body, index, x):
    """MOVING, or CLAMPED where the body's ``clamped`` says so, for its particles ``index``."""
    kind = np.full(len(x), MOVING, np.int8)
    kind[_initial(body.clamped, index, x, ()).astype(bool)] = CLAMPED
    return kind


def _raise_on_every_rank(comm, problem):
    """Raise InputError on every rank with the first rank's problem, if any rank has one."""
    problems = [p for p in comm.allgather(problem) if p]
    if problems:
        raise InputError(problems[0])


def _cuts(comm, case, support):
    """A decomposition whose cuts balance the moving particles (as the solver's first balance):
    rank r counts the bodies' particles in the r-th equal stretch of the slab axis."""
    axis, (lo, hi) = case.slab_axis, case.domain
    decomp = SlabDecomposition(comm, axis, lo[axis], hi[axis], support)
    edges = np.linspace(lo[axis], hi[axis], comm.size + 1)
    edges[0], edges[-1] = -np.inf, np.inf
    s, work = [], []
    for body in case.bodies:
        index, x, _ = as_points(body.x).window(axis, edges[comm.rank], edges[comm.rank + 1])
        s.append(x[:, axis])
        work.append((_body_kind(body, index, x) == MOVING).astype(np.float64))  # as particle_work
    decomp.balance(np.concatenate(s), np.concatenate(work))
    return decomp


def particles_from_case(comm, case, parts):
    """This rank's slab of the particles of ``case``, with the fields of ``parts`` (parts.py)."""
    dim, dp, axis = case.dim, case.dp, case.slab_axis
    lo, hi = _cuts(comm, case, parts.kernel.support).slab()
    columns = {name: [] for name in ("gid", "kind", "x", "v", "p", "normal", "stress", "wall_distance")}
    counts, offset, problem = [], 0, None
    items = [(b, False) for b in case.bodies] + [(w, True) for w in case.walls]
    for (item, is_wall), points in zip(items, case.sources):
        index, x, normal = points.window(axis, lo, hi)
        n = len(index)
        counts.append(n)
        columns["gid"].append(offset + index)
        columns["x"].append(x)
        offset += points.size
        if is_wall:
            columns["kind"].append(np.full(n, WALL_SLIP if item.slip else WALL, np.int8))
            columns["v"].append(_initial(item.velocity, index, x, (dim,)))
            columns["p"].append(np.zeros(n))
            columns["stress"].append(np.zeros((n, 6)))
            columns["normal"].append(normal)
            distance = np.full(n, np.nan) if item.distance is None else _initial(item.distance, index, x, ())
            bad = ~(distance >= 0.0) if item.distance is not None else np.zeros(n, bool)
            if bad.any() and problem is None:
                k = int(np.argmax(bad))
                problem = (f"wall {item.name!r}: its distance gives {distance[k]:.6g} m at "
                           f"{np.round(x[k], 6).tolist()}; Wall.distance is each particle's depth behind the wall "
                           "surface, 0 or more")
            columns["wall_distance"].append(distance)
            continue
        columns["kind"].append(_body_kind(item, index, x))
        columns["v"].append(_initial(item.velocity, index, x, (dim,)))
        stress = None if item.stress is None else _initial(item.stress, index, x, (3, 3))
        columns["stress"].append(np.zeros((n, 6)) if stress is None else packed(stress))
        if item.pressure is not None:
            columns["p"].append(_initial(item.pressure, index, x, ()))
        elif stress is not None:
            columns["p"].append(-np.trace(stress, axis1=1, axis2=2) / 3.0)
        else:
            columns["p"].append(np.zeros(n))
        columns["normal"].append(np.zeros((n, dim)))
        columns["wall_distance"].append(np.zeros(n))
        domain_lo, domain_hi = case.domain
        outside = np.any((x < domain_lo) | (x >= domain_hi), axis=1)
        if outside.any() and problem is None:
            k = int(np.argmax(outside))
            problem = (f"body {item.name!r} lies outside the domain (particle at {np.round(x[k], 6).tolist()}, "
                       f"domain {domain_lo.tolist()} to {domain_hi.tolist()})")
    _raise_on_every_rank(comm, problem)
    totals = comm.allreduce(np.array(counts, np.int64), op=MPI.SUM)
    for (item, is_wall), total in zip(items, totals):
        if total == 0:
            what = "wall" if is_wall else "body"
            raise InputError(f"{what} {item.name!r} has no particles at dp={dp:g} m")
    arrays = {name: np.concatenate(parts_) for name, parts_ in columns.items()}
    material = (arrays["kind"] == MOVING) | (arrays["kind"] == CLAMPED)
    arrays["rho"] = np.where(material, parts.scheme.initial_density(arrays["p"]), case.material.rho0)
    arrays["mass"] = arrays["rho"] * dp**dim
    pa = Particles.empty(dim, parts.fields, len(arrays["gid"]))
    for name, a in arrays.items():
        if name in pa.arrays:
            pa.arrays[name][:] = a
    return pa


def particles_from_frame(comm, path, parts):
    """This rank's share of the particles (walls included) of the frame ``path``: an equal run of
    its rows, which the first migration sends to their owners, so no rank reads the whole frame.
    Symmetric tensors that a frame of format 1 holds as (3, 3) are packed (tensors.py). Returns
    the particles, the frame's time and its step."""
    n = frame_rows(path)
    start, stop = n * comm.rank // comm.size, n * (comm.rank + 1) // comm.size
    rows = read_rows(path, start, stop)
    symmetric = {f.name for f in parts.fields if f.shape in (("sym",), (6,))}
    pa = Particles.empty(rows["dim"], parts.fields, stop - start)
    for name, a in rows.items():
        if name in pa.arrays:
            pa.arrays[name][:] = packed(a) if name in symmetric and a.ndim == 3 else a
    return pa, rows["t"], rows["step"]
