"""Global sums over the moving particles: what diagnostics.csv records.

Every run records time, step, dt, particle count, mass, kinetic energy,
momentum and angular momentum; the scheme adds its own sums (strain and
potential energy of solids) and every probe of the case (a particle given
by its global id) its displacement from the initial position.
"""

import numpy as np
from mpi4py import MPI

from .particles import MOVING


def observable_names(dim, scheme=None, probes=()):
    """Columns of diagnostics.csv."""
    ang = ["angular_momentum_z"] if dim == 2 else [f"angular_momentum_{c}" for c in "xyz"]
    names = ["t", "step", "dt", "n", "mass", "kinetic_energy"] + [f"momentum_{c}" for c in "xyz"[:dim]] + ang
    names += list(getattr(scheme, "observable_names", ()))
    for probe in probes:
        names += [f"{probe}_u{c}" for c in "xyz"[:dim]]
    return names


def _probe_positions(pa, n, gids, dim):
    """Positions of the owned particles with the given global ids (zeros where not owned)."""
    out = np.zeros(len(gids) * dim)
    owned = pa.gid[:n]
    for k, g in enumerate(gids):
        hit = np.flatnonzero(owned == g)
        if len(hit):
            out[k * dim:(k + 1) * dim] = pa.x[hit[0]]
    return out


def global_observables(sim):
    """The values of every column of ``observable_names`` for the current state."""
    pa = sim.particles
    n = pa.n_owned
    dim = pa.dim
    moving = pa.kind[:n] == MOVING
    m, x, v = pa.mass[:n][moving], pa.x[:n][moving], pa.v[:n][moving]
    mv = m[:, None] * v
    if dim == 2:
        ang = [np.sum(x[:, 0] * mv[:, 1] - x[:, 1] * mv[:, 0])]
    else:
        ang = np.cross(x, mv).sum(axis=0)
    extra = sim.scheme.observables(pa, n) if hasattr(sim.scheme, "observables") else {}
    probes = sim.case.probes
    local = np.concatenate(([len(m), m.sum(), 0.5 * np.sum(m * np.sum(v * v, axis=1))],
                            mv.sum(axis=0), ang, list(extra.values()),
                            _probe_positions(pa, n, list(probes.values()), dim)))
    total = np.empty_like(local)
    sim.comm.Allreduce(local, total, op=MPI.SUM)
    k = len(total) - len(probes) * dim
    displacement = total[k:] - np.concatenate([sim.case.probe_origins[name] for name in probes] or [[]])
    values = [sim.t, sim.step, sim.dt] + total[:k].tolist() + displacement.tolist()
    out = dict(zip(observable_names(dim, sim.scheme, probes), values))
    out["n"] = int(out["n"])
    return out
