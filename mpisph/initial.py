"""Initial particles, from a case or from a frame to restart.

Every rank builds (or reads) the global arrays and keeps every size-th
particle; the first migration of the run sends each to the rank that owns
its position. Global ids follow the order of the case's bodies, then walls.
"""

import numpy as np

from .particles import CLAMPED, MOVING, WALL, WALL_SLIP, Particles
from .tensors import packed


def _share(comm, arrays, fields, dim):
    """This rank's strided share of the global ``arrays`` as Particles."""
    n_global = len(arrays["gid"])
    mine = np.arange(comm.rank, n_global, comm.size)
    pa = Particles.empty(dim, fields, len(mine))
    for name, a in arrays.items():
        if name in pa.arrays:
            pa.arrays[name][:] = a[mine]
    return pa


def particles_from_case(comm, case, parts):
    """This rank's share of the particles of ``case``, with the fields of ``parts`` (parts.py)."""
    dim, dp = case.dim, case.dp
    m = case.material
    xs, kinds, vs, ps, normals, stresses, distances = [], [], [], [], [], [], []
    for b in case.bodies:
        n = len(b.x)
        xs.append(b.x)
        kind = np.full(n, MOVING, np.int8)
        if b.clamped is not None:
            kind[b.clamped] = CLAMPED
        kinds.append(kind)
        vs.append(np.zeros((n, dim)) if b.velocity is None else b.velocity)
        stresses.append(np.zeros((n, 6)) if b.stress is None else packed(b.stress))
        if b.pressure is not None:
            ps.append(b.pressure)
        elif b.stress is not None:
            ps.append(-np.trace(b.stress, axis1=1, axis2=2) / 3.0)
        else:
            ps.append(np.zeros(n))
        normals.append(np.zeros((n, dim)))
        distances.append(np.zeros(n))
    for wl in case.walls:
        n = len(wl.x)
        xs.append(wl.x)
        kinds.append(np.full(n, WALL_SLIP if wl.slip else WALL, np.int8))
        vs.append(np.zeros((n, dim)) if wl.velocity is None else np.broadcast_to(wl.velocity, (n, dim)))
        ps.append(np.zeros(n))
        stresses.append(np.zeros((n, 6)))
        normals.append(wl.normal)
        distances.append(np.full(n, np.nan) if wl.distance is None else wl.distance)
    kind = np.concatenate(kinds)
    p = np.concatenate(ps)
    material = (kind == MOVING) | (kind == CLAMPED)
    rho = np.where(material, parts.scheme.initial_density(p), m.rho0)
    arrays = {
        "gid": np.arange(len(kind), dtype=np.int64),
        "kind": kind,
        "x": np.concatenate(xs),
        "v": np.concatenate(vs),
        "p": p,
        "rho": rho,
        "mass": rho * dp**dim,
        "normal": np.concatenate(normals),
        "stress": np.concatenate(stresses),
        "wall_distance": np.concatenate(distances),
    }
    return _share(comm, arrays, parts.fields, dim)


def particles_from_frame(comm, frame, parts):
    """Particles (walls included) from ``read_frame(path, walls=True)``; symmetric tensors that a
    frame of format 1 holds as (3, 3) are packed (tensors.py)."""
    symmetric = {f.name for f in parts.fields if f.shape in (("sym",), (6,))}
    arrays = {k: (packed(v) if k in symmetric and v.ndim == 3 else v)
              for k, v in frame.items() if isinstance(v, np.ndarray)}
    return _share(comm, arrays, parts.fields, frame["dim"])
