"""Forces and moments that the particles exert on named walls (``Case.wall_forces``), recorded in
diagnostics.csv as ``force_<wall>_x`` ... and ``moment_<wall>_z`` (2D) or ``_x``, ``_y``, ``_z``
(3D, about the wall's declared point).

The force on wall k is the reaction to what its particles add to the acceleration of the moving
particles: with a_i^(k) the pair force terms of the run (forces.py, those with ``pairwise``) summed
over the partners of i that belong to wall k only,

    F_k = - sum_i m_i a_i^(k),      M_k = - sum_i (x_i - P_k) x m_i a_i^(k),

summed over the owned moving particles and added over ranks. The moment takes the force of a pair
at x_i: exact for central pair forces (along r_ij: the fluid's pressure and Riemann terms, the
mu(I) pressure and Eq. 27's viscous term), since a force moved along its line of action keeps its
moment; for non-central terms (the solids' stress, the corrected viscous stress) the arm is
uncertain by up to a kernel support. A term that leaves a part to an implicit step (the mu(I)
viscous kick) sums it here explicitly at the current velocities (``ForceTerm.add_all``).
"""

import copy

import numpy as np
from mpi4py import MPI
from numba import njit

from .particles import MOVING


def wall_force_columns(case):
    """The diagnostics columns of the case's wall forces."""
    moments = ["z"] if case.dim == 2 else ["x", "y", "z"]
    return [f"{kind}_{name}_{c}" for name in case.wall_forces
            for kind, comps in (("force", "xyz"[:case.dim]), ("moment", moments)) for c in comps]


@njit(cache=True)
def partners_in(n, start, nbr, gid, lo, hi, start_out, nbr_out):
    """The neighbour lists (CSR) restricted to the partners whose global id is in [lo, hi)."""
    m = 0
    for i in range(n):
        start_out[i] = m
        for k in range(start[i], start[i + 1]):
            j = nbr[k]
            if lo <= gid[j] < hi:
                nbr_out[m] = j
                m += 1
    start_out[n] = m
    return m


@njit(cache=True)
def reaction_sums(n, kind, mass, x, acc, point, out):
    """out = (-sum m a, -sum (x - point) x m a) over the moving particles in [0, n)."""
    dim = x.shape[1]
    for i in range(n):
        if kind[i] != MOVING:
            continue
        f = -mass[i] * acc[i]
        r = x[i] - point
        for a in range(dim):
            out[a] += f[a]
        if dim == 2:
            out[2] += r[0] * f[1] - r[1] * f[0]
        else:
            out[3] += r[1] * f[2] - r[2] * f[1]
            out[4] += r[2] * f[0] - r[0] * f[2]
            out[5] += r[0] * f[1] - r[1] * f[0]


def wall_force_values(sim):
    """The values of ``wall_force_columns``, in their order (collective)."""
    case, ctx = sim.case, sim.ctx
    pa = ctx.particles
    n = pa.n_owned
    terms = [t for t in sim.parts.forces.terms if t.pairwise]
    width = case.dim + (1 if case.dim == 2 else 3)
    local = np.zeros(len(case.wall_forces) * width)
    for k, (name, point) in enumerate(case.wall_forces.items()):
        lo, hi = case.wall_gids[name]
        start = np.empty(n + 1, dtype=ctx.start.dtype)
        nbr = np.empty(ctx.start[n] - ctx.start[0], dtype=ctx.nbr.dtype)
        partners_in(n, ctx.start, ctx.nbr, pa.gid, lo, hi, start, nbr)
        walls_only = copy.copy(ctx)
        walls_only.start, walls_only.nbr = start, nbr
        acc = np.zeros((n, pa.dim))
        for term in terms:
            term.add_all(walls_only, acc)
        reaction_sums(n, pa.kind, pa.mass, pa.x, acc, np.asarray(point, float), local[k * width:(k + 1) * width])
    total = np.empty_like(local)
    sim.comm.Allreduce(local, total, op=MPI.SUM)
    return total.tolist()
