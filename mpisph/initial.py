"""Initial particles, from a case or from a frame to restart.

Every rank builds (or reads) the global arrays and keeps every size-th
particle; the first migration of the run sends each to the rank that owns
its position. Global ids follow the order of the case's bodies, then walls.
"""

import numpy as np

from .kernels import KERNELS, normalisation
from .particles import CORE_FIELDS, MOVING, WALL, WALL_SLIP, Particles
from .physics.fluid import FluidScheme, lattice_kernel_sum


def make_scheme(case, params):
    """The fluid scheme with its reference kernel sum for density reinitialisation."""
    h = params["h_factor"] * case.dp
    kernel = KERNELS[params["kernel"]]
    lattice_sum = lattice_kernel_sum(case.dim, case.dp, h, normalisation(kernel, h, case.dim), kernel)
    return FluidScheme(case.material, case.gravity, case.density_reinit, case.u_ref, lattice_sum)


def _share(comm, arrays, scheme, dim):
    """This rank's strided share of the global ``arrays`` as Particles."""
    fields = CORE_FIELDS + scheme.fields
    n_global = len(arrays["gid"])
    mine = np.arange(comm.rank, n_global, comm.size)
    pa = Particles.empty(dim, fields, len(mine))
    for name, a in arrays.items():
        if name in pa.arrays:
            pa.arrays[name][:] = a[mine]
    return pa


def particles_from_case(comm, case, scheme):
    dim, dp = case.dim, case.dp
    m = case.material
    xs, kinds, vs, ps, normals = [], [], [], [], []
    for b in case.bodies:
        n = len(b.x)
        xs.append(b.x)
        kinds.append(np.full(n, MOVING, np.int8))
        vs.append(np.zeros((n, dim)) if b.velocity is None else b.velocity)
        ps.append(np.zeros(n) if b.pressure is None else b.pressure)
        normals.append(np.zeros((n, dim)))
    for wl in case.walls:
        n = len(wl.x)
        xs.append(wl.x)
        kinds.append(np.full(n, WALL_SLIP if wl.slip else WALL, np.int8))
        vs.append(np.zeros((n, dim)) if wl.velocity is None else np.broadcast_to(wl.velocity, (n, dim)))
        ps.append(np.zeros(n))
        normals.append(wl.normal)
    kind = np.concatenate(kinds)
    p = np.concatenate(ps)
    rho = np.where(kind == MOVING, scheme.initial_density(p), m.rho0)
    arrays = {
        "gid": np.arange(len(kind), dtype=np.int64),
        "kind": kind,
        "x": np.concatenate(xs),
        "v": np.concatenate(vs),
        "p": p,
        "rho": rho,
        "mass": rho * dp**dim,
        "normal": np.concatenate(normals),
    }
    return _share(comm, arrays, scheme, dim)


def particles_from_frame(comm, frame, scheme):
    """Particles (walls included) from ``read_frame(path, walls=True)``."""
    arrays = {k: v for k, v in frame.items() if isinstance(v, np.ndarray)}
    return _share(comm, arrays, scheme, frame["dim"])
