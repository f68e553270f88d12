"""Global sums over the moving particles: what diagnostics.csv records."""

import numpy as np
from mpi4py import MPI

from .particles import MOVING


def observable_names(dim):
    """Columns of diagnostics.csv."""
    ang = ["angular_momentum_z"] if dim == 2 else [f"angular_momentum_{c}" for c in "xyz"]
    return ["t", "step", "dt", "n", "mass", "kinetic_energy"] + [f"momentum_{c}" for c in "xyz"[:dim]] + ang


def global_observables(sim):
    """t, step, dt, particle count, mass, kinetic energy, momentum and angular momentum."""
    pa = sim.particles
    n = pa.n_owned
    moving = pa.kind[:n] == MOVING
    m, x, v = pa.mass[:n][moving], pa.x[:n][moving], pa.v[:n][moving]
    mv = m[:, None] * v
    if x.shape[1] == 2:
        ang = [np.sum(x[:, 0] * mv[:, 1] - x[:, 1] * mv[:, 0])]
    else:
        ang = np.cross(x, mv).sum(axis=0)
    local = np.concatenate(([len(m), m.sum(), 0.5 * np.sum(m * np.sum(v * v, axis=1))],
                            mv.sum(axis=0), ang))
    total = np.empty_like(local)
    sim.comm.Allreduce(local, total, op=MPI.SUM)
    values = [sim.t, sim.step, sim.dt] + total.tolist()
    out = dict(zip(observable_names(x.shape[1]), values))
    out["n"] = int(out["n"])
    return out
