"""Global sums over the moving particles: what diagnostics.csv records.

Every run records time, step, dt, particle count, mass, kinetic energy,
momentum, angular momentum and potential energy in gravity; the scheme adds
its own sums (the strain energy of elastic solids) and counters (the mu(I) implicit
kick's iterations), every probe of the case
(a particle given by its global id) its displacement from the initial
position, a case with a ``Front`` the largest distance of a moving
particle from its origin (a maximum, exact on any number of ranks), and a case
with ``wall_forces`` the force and moment on each of those walls
(wall_forces.py), and one with ``barrier_loads`` the approach speed and depth and
the dynamic pressure coefficient of each barrier (barrier_load.py). The last
columns describe the load balance: the fewest and most moving particles and
neighbour pairs on a rank in the current configuration, the imbalance of the
pairs (max / mean - 1, what the rebalance threshold is compared with) and the
rebalances since the start.
"""

import numpy as np
from mpi4py import MPI
from numba import njit

from .barrier_load import LOAD_KINDS, barrier_load_columns, barrier_load_values
from .particles import MOVING
from .wall_forces import wall_force_columns, wall_force_values

BLOCK = 1024  # particles per partial sum: blocked summation keeps the round-off near that of numpy's


@njit(cache=True)
def moving_sums(n, kind, mass, x, v, gravity, out):
    """Sums over the moving particles in [0, n) into ``out``: count, mass, kinetic energy,
    momentum (dim), angular momentum (z, or x y z in 3D) and the potential energy -m g.x,
    summed in blocks of BLOCK particles, with no per-particle temporary arrays."""
    dim = x.shape[1]
    k = 3 + dim
    part = np.zeros(len(out))
    for b0 in range(0, n, BLOCK):
        part[:] = 0.0
        for i in range(b0, min(b0 + BLOCK, n)):
            if kind[i] != MOVING:
                continue
            m = mass[i]
            part[0] += 1.0
            part[1] += m
            vv = gx = 0.0
            for a in range(dim):
                vv += v[i, a] * v[i, a]
                gx += gravity[a] * x[i, a]
                part[3 + a] += m * v[i, a]
            part[2] += 0.5 * m * vv
            if dim == 2:
                part[k] += m * (x[i, 0] * v[i, 1] - x[i, 1] * v[i, 0])
            else:
                part[k] += m * (x[i, 1] * v[i, 2] - x[i, 2] * v[i, 1])
                part[k + 1] += m * (x[i, 2] * v[i, 0] - x[i, 0] * v[i, 2])
                part[k + 2] += m * (x[i, 0] * v[i, 1] - x[i, 1] * v[i, 0])
            part[len(out) - 1] -= m * gx
        out += part


@njit(cache=True)
def front_distance(n, kind, x, origin, axes):
    """Largest distance of a moving particle in [0, n) from ``origin``, measured along ``axes``
    (0 when there is none)."""
    far = 0.0
    for i in range(n):
        if kind[i] != MOVING:
            continue
        s = 0.0
        for a in axes:
            s += (x[i, a] - origin[a]) ** 2
        far = max(far, s)
    return np.sqrt(far)


def observable_names(dim, scheme=None, probes=(), front=None, wall_forces=(), barrier_loads=()):
    """Columns of diagnostics.csv (``wall_forces``: wall_forces.wall_force_columns; ``barrier_loads``:
    barrier_load.barrier_load_columns)."""
    ang = ["angular_momentum_z"] if dim == 2 else [f"angular_momentum_{c}" for c in "xyz"]
    names = ["t", "step", "dt", "n", "mass", "kinetic_energy"] + [f"momentum_{c}" for c in "xyz"[:dim]] + ang
    names += ["potential_energy"]
    names += list(scheme.observable_names if scheme is not None else ())
    names += list(scheme.counter_names if scheme is not None else ())
    for probe in probes:
        names += [f"{probe}_u{c}" for c in "xyz"[:dim]]
    if front is not None:
        names.append("front")
    return names + list(wall_forces) + list(barrier_loads) + LOAD_COLUMNS


LOAD_COLUMNS = ["rank_particles_min", "rank_particles_max", "rank_pairs_min", "rank_pairs_max", "imbalance",
                "rebalances"]

_FIXED = {  # the meaning of a column of every run (a 2D run's sums and forces are per metre of depth)
    "t": "simulated time [s]", "step": "time steps since t = 0 [-]",
    "dt": "the row's last time step, cut at a frame to end on its time [s]", "n": "moving particles [-]",
    "mass": "mass of the moving particles [kg]", "kinetic_energy": "their kinetic energy [J]",
    "momentum": "their momentum [kg m/s]", "angular_momentum": "their angular momentum about the origin "
    "[kg m^2/s]", "potential_energy": "their potential energy in gravity, zero at the origin [J]",
    "strain_energy": "the elastic strain energy [J]",
    "viscous_iterations": "conjugate-gradient iterations of the implicit viscous kick a step since the row before [-]",
    "front": "the front: the farthest moving particle from the case's Front origin along its axes [m]",
    "rank_particles_min": "fewest moving particles on a rank [-]", "rank_particles_max": "most on a rank [-]",
    "rank_pairs_min": "fewest neighbour pairs on a rank [-]", "rank_pairs_max": "most on a rank [-]",
    "imbalance": "most pairs on a rank over their mean, less 1, which rebalance_threshold bounds [-]",
    "rebalances": "new cuts of the slabs since this process started [-]",
}


def column_docs(case, scheme):
    """{column: meaning with its unit} of every column of the case's diagnostics.csv, in order (a 2D
    run's sums and forces per metre of depth)."""
    walls = {f"{kind}_{name}": (kind, name) for name in case.wall_forces for kind in ("force", "moment")}
    loads = {f"{kind}_{load.wall}": doc for load in case.barrier_loads for kind, doc in LOAD_KINDS.items()}
    docs = {}
    for name in observable_names(case.dim, scheme, case.probes, case.front, wall_force_columns(case),
                                 barrier_load_columns(case)):
        stem = name.rsplit("_", 1)[0]
        if name in _FIXED or stem in ("momentum", "angular_momentum"):
            doc = _FIXED[name if name in _FIXED else stem]
        elif stem in walls:
            kind, wall = walls[stem]
            doc = (f"force of the particles on wall {wall}, as it acts on the wall [N]" if kind == "force" else
                   f"its moment about the point the case declares in wall_forces [N m]")
        elif name in loads:
            doc = loads[name]
        else:  # a probe's displacement, NAME_ux ...
            doc = f"displacement of probe {name[:-3]} from its start [m]"
        docs[name] = doc
    return docs


def _load_balance(sim):
    """The values of LOAD_COLUMNS (module docstring)."""
    pa, start = sim.particles, sim.ctx.start
    local = np.array([np.count_nonzero(pa.owned("kind") == MOVING), start[pa.n_owned] - start[0]], dtype=float)
    every = np.empty((sim.comm.size, 2))
    sim.comm.Allgather(local, every)
    particles, pairs = every[:, 0], every[:, 1]
    imbalance = pairs.max() / pairs.mean() - 1.0 if pairs.mean() > 0 else 0.0
    return [particles.min(), particles.max(), pairs.min(), pairs.max(), imbalance, sim.rebalances]


def _probe_positions(pa, n, gids, dim):
    """Positions of the owned particles with the given global ids (zeros where not owned)."""
    out = np.zeros(len(gids) * dim)
    owned = pa.gid[:n]
    for k, g in enumerate(gids):
        hit = np.flatnonzero(owned == g)
        if len(hit):
            out[k * dim:(k + 1) * dim] = pa.x[hit[0]]
    return out


def global_observables(sim, gauges):
    """The values of every column of ``observable_names`` for the current state; ``gauges``: this
    row's gauge samples (gauges.GaugeRecorder.sample), which the barrier loads read."""
    pa = sim.particles
    n = pa.n_owned
    dim = pa.dim
    motion = np.zeros(3 + dim + (1 if dim == 2 else 3) + 1)
    moving_sums(n, pa.kind, pa.mass, pa.x, pa.v, sim.case.gravity, motion)
    extra = sim.parts.scheme.observables(pa, n)
    probes = sim.case.probes
    local = np.concatenate((motion, list(extra.values()), _probe_positions(pa, n, list(probes.values()), dim)))
    total = np.empty_like(local)
    sim.comm.Allreduce(local, total, op=MPI.SUM)
    k = len(total) - len(probes) * dim
    displacement = total[k:] - np.concatenate([sim.case.probe_origins[name] for name in probes] or [[]])
    counters = sim.parts.scheme.counters()
    values = [sim.t, sim.step, sim.dt] + total[:k].tolist() + list(counters.values()) + displacement.tolist()
    front = sim.case.front
    if front is not None:
        far = front_distance(n, pa.kind, pa.x, np.asarray(front.origin, float), np.asarray(front.axes, np.int64))
        values.append(sim.comm.allreduce(far, op=MPI.MAX))
    forces = dict(zip(wall_force_columns(sim.case), wall_force_values(sim) if sim.case.wall_forces else []))
    values += list(forces.values()) + barrier_load_values(sim.case, forces, gauges)
    values += _load_balance(sim)
    out = dict(zip(observable_names(dim, sim.parts.scheme, probes, front, wall_force_columns(sim.case),
                                    barrier_load_columns(sim.case)), values))
    for name in ("n", *LOAD_COLUMNS[:4]):  # counts
        out[name] = int(out[name])
    return out
