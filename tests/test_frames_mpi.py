"""Collective frame and diagnostics writing on several ranks.

Run with ``mpirun -n 2 python -m pytest -m mpi --with-mpi``.
"""

import shutil
import tempfile

import numpy as np
import pytest
from mpi4py import MPI

from mpisph.io.diagnostics import Diagnostics, read_diagnostics
from mpisph.io.frames import frame_path, list_frames, read_frame, write_frame

COMM = MPI.COMM_WORLD


@pytest.fixture
def shared_dir():
    """A temporary directory made on rank 0 and known to every rank."""
    path = tempfile.mkdtemp(prefix="mpisph-test-") if COMM.rank == 0 else None
    path = COMM.bcast(path, root=0)
    yield path
    COMM.Barrier()
    if COMM.rank == 0:
        shutil.rmtree(path)


def local_fields(dim, rank):
    """Rank-dependent particle count; the last rank owns none."""
    n = 0 if rank == COMM.size - 1 else 3 + 5 * rank
    rng = np.random.default_rng(rank)
    gid = np.arange(n, dtype=np.int64) * COMM.size + rank  # interleaved ids
    return {
        "x": rng.random((n, dim)),
        "v": rng.standard_normal((n, dim)),
        "rho": rng.random(n),
        "sigma": rng.standard_normal((n, 3, 3)),
        "gid": gid[::-1].copy(),
        "kind": (gid % 4 == 0).astype(np.int8),
    }


@pytest.mark.mpi(min_size=2)
@pytest.mark.parametrize("dim", [2, 3])
def test_collective_frame(shared_dir, dim):
    fields = local_fields(dim, COMM.rank)
    path = frame_path(shared_dir, 7)
    write_frame(path, COMM, fields, time=1.25, step=42, dim=dim,
                params={"case": "mpi"})
    gathered = COMM.gather(fields, root=0)
    if COMM.rank == 0:
        every = {k: np.concatenate([g[k] for g in gathered]) for k in fields}
        order = np.argsort(every["gid"])
        got = read_frame(path, walls=True)
        assert len(got["gid"]) == sum(len(g["gid"]) for g in gathered)
        for key in fields:
            assert got[key].tobytes() == every[key][order].tobytes(), key
        moving = read_frame(path)
        assert (moving["kind"] == 0).all()
        assert moving["t"] == 1.25 and moving["step"] == 42
        assert list_frames(shared_dir) == [path]
    COMM.Barrier()


@pytest.mark.mpi(min_size=2)
def test_collective_diagnostics(shared_dir):
    cols = ["t", "n", "ekin"]
    with Diagnostics(shared_dir, COMM, cols) as diag:
        for step in range(4):
            ekin = COMM.allreduce(0.1 * (COMM.rank + 1) * step)
            diag.record({"t": step * 0.1, "n": COMM.size, "ekin": ekin})
    COMM.Barrier()
    if COMM.rank == 0:
        d = read_diagnostics(f"{shared_dir}/diagnostics.csv")
        assert len(d["t"]) == 4 and (d["n"] == COMM.size).all()
        assert np.allclose(d["ekin"][1], 0.1 * COMM.size * (COMM.size + 1) / 2)
