"""Initial particles, from a case or from a frame to restart.

Every rank builds (or reads) the global arrays and keeps every size-th
particle; the first migration of the run sends each to the rank that owns
its position. Global ids follow the order of the case's bodies, then walls.
"""

import numpy as np

from . import surface
from .kernels import KERNELS, normalisation
from .materials import DruckerPrager, ElasticSolid, Fluid
from .particles import CLAMPED, CORE_FIELDS, MOVING, WALL, WALL_SLIP, Particles
from .physics.drucker_prager import DruckerPragerModel
from .physics.elastic import ElasticModel
from .physics.fluid import FluidScheme, lattice_kernel_sum
from .physics.solid import SolidScheme
from .stabilisers.transport_velocity import STABILISERS
from .tensors import packed


def make_scheme(case, params):
    """The scheme of the case's material."""
    m = case.material
    if isinstance(m, DruckerPrager):
        return SolidScheme(DruckerPragerModel(m, case.dim, case.gravity), case.gravity, case.u_ref)
    if isinstance(m, ElasticSolid):
        return SolidScheme(ElasticModel(m), case.gravity, case.u_ref)
    assert isinstance(m, Fluid)
    h = params["h_factor"] * case.dp
    kernel = KERNELS[params["kernel"]]
    lattice_sum = lattice_kernel_sum(case.dim, case.dp, h, normalisation(kernel, h, case.dim), kernel)
    return FluidScheme(m, case.gravity, case.density_reinit, case.u_ref, lattice_sum)


def particle_fields(scheme, stabiliser):
    """Core fields, the scheme's, and the surface fields if the scheme or the stabiliser needs them."""
    fields = CORE_FIELDS + scheme.fields
    if getattr(scheme, "needs_surface", False) or STABILISERS[stabiliser].needs_surface:
        fields += surface.FIELDS
    return fields


def _share(comm, arrays, fields, dim):
    """This rank's strided share of the global ``arrays`` as Particles."""
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
    xs, kinds, vs, ps, normals, stresses = [], [], [], [], [], []
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
    for wl in case.walls:
        n = len(wl.x)
        xs.append(wl.x)
        kinds.append(np.full(n, WALL_SLIP if wl.slip else WALL, np.int8))
        vs.append(np.zeros((n, dim)) if wl.velocity is None else np.broadcast_to(wl.velocity, (n, dim)))
        ps.append(np.zeros(n))
        stresses.append(np.zeros((n, 6)))
        normals.append(wl.normal)
    kind = np.concatenate(kinds)
    p = np.concatenate(ps)
    material = (kind == MOVING) | (kind == CLAMPED)
    rho = np.where(material, scheme.initial_density(p), m.rho0)
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
    }
    return _share(comm, arrays, particle_fields(scheme, case.stabiliser), dim)


def particles_from_frame(comm, frame, scheme, stabiliser):
    """Particles (walls included) from ``read_frame(path, walls=True)``; symmetric tensors that a
    frame of format 1 holds as (3, 3) are packed (tensors.py)."""
    arrays = {k: (packed(v) if v.ndim == 3 and v.shape[1] == v.shape[2] else v)
              for k, v in frame.items() if isinstance(v, np.ndarray)}
    return _share(comm, arrays, particle_fields(scheme, stabiliser), frame["dim"])
