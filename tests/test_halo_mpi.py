"""Halo exchange under MPI: every owned particle sees exactly the neighbours it
would see on one rank, periodic images across ranks included."""

import itertools

import numpy as np
import pytest
from mpi4py import MPI

from mpisph.parallel.decomposition import SlabDecomposition, migrate
from mpisph.parallel.halo import Halo
from mpisph.particles import CORE_FIELDS, Particles


def global_particles(n, dim, seed=3):
    rng = np.random.default_rng(seed)
    return rng.uniform(0.0, 1.0, (n, dim)), rng.permutation(n).astype(np.int64)


def brute_force(x, gid, periodic, radius):
    """{gid: sorted (gid_j, rounded offset) of neighbours} with periodic images."""
    n, dim = x.shape
    shifts = [np.array(s) for s in itertools.product(*[(-1.0, 0.0, 1.0) if p else (0.0,) for p in periodic])]
    out = {}
    for i in range(n):
        found = []
        for s in shifts:
            d = np.linalg.norm(x[i] - (x + s), axis=1)
            for j in np.nonzero(d < radius)[0]:
                if j != i or s.any():
                    found.append((int(gid[j]), tuple(np.round(x[i] - x[j] - s, 9))))
        out[int(gid[i])] = sorted(found)
    return out


@pytest.mark.mpi(min_size=2)
@pytest.mark.parametrize("dim, periodic", [(2, (True, True)), (2, (False, True)), (3, (True, False, True))])
def test_halo_gives_every_neighbour(dim, periodic):
    comm = MPI.COMM_WORLD
    radius = 0.09
    x_all, gid_all = global_particles(300 if dim == 2 else 500, dim)
    decomp = SlabDecomposition(comm, 0, 0.0, 1.0, radius)
    mine = np.arange(comm.rank, len(gid_all), comm.size)
    pa = Particles.empty(dim, CORE_FIELDS, len(mine))
    pa.x[:] = x_all[mine]
    pa.gid[:] = gid_all[mine]
    migrate(pa, decomp)
    decomp.balance(pa.owned("x")[:, 0], np.ones(pa.n_owned))
    migrate(pa, decomp)
    lo, hi = decomp.slab()
    assert np.all((pa.owned("x")[:, 0] >= lo) & (pa.owned("x")[:, 0] < hi))
    Halo(decomp, radius, np.zeros(dim), np.ones(dim), periodic).build(pa)

    expected = brute_force(x_all, gid_all, periodic, radius)
    x, gid = pa.x, pa.gid
    for i in range(pa.n_owned):
        d = np.linalg.norm(x[i] - x, axis=1)
        found = sorted((int(gid[j]), tuple(np.round(x[i] - x[j], 9)))
                       for j in np.nonzero(d < radius)[0] if j != i)
        assert found == expected[int(gid[i])]
    counts = comm.allgather(pa.n_owned)
    assert sum(counts) == len(gid_all)
