"""The per-slab build under MPI (initial.particles_from_case): each rank generates only its own slab,
with the cuts the solver's first balance makes (so nothing migrates), and together the ranks hold
exactly the particles, ids and initial state of a one-rank build."""

import numpy as np
import pytest
from mpi4py import MPI

from mpisph import case as cases
from mpisph.initial import particles_from_case
from mpisph.parallel.decomposition import SlabDecomposition, particle_work
from mpisph.parts import make_parts

FIELDS = ("gid", "kind", "x", "v", "p", "rho", "mass", "normal", "stress", "wall_distance")


def build(comm, name, dp):
    module = cases.load_case_module(name)
    values = cases.resolve_params(module, {"dp": str(dp)})
    values["case"] = name
    case = cases.build_case(module, values)
    parts = make_parts(case, values)
    return case, parts, particles_from_case(comm, case, parts)


def by_gid(arrays):
    order = np.argsort(arrays["gid"])
    return {k: v[order] for k, v in arrays.items()}


@pytest.mark.mpi(min_size=2)
@pytest.mark.parametrize("name, dp", [("cube_failure_3d", 0.25), ("flume_3d", 0.1), ("lube_collapse_3d", 0.0097)])
def test_ranks_build_their_slabs_and_together_the_whole_case(name, dp):
    comm = MPI.COMM_WORLD
    case, parts, pa = build(comm, name, dp)
    n = pa.n_owned
    fields = [k for k in FIELDS if k in pa.arrays]  # the mu(I) scheme has no stress
    mine = {k: pa.arrays[k][:n] for k in fields}
    gathered = {k: np.concatenate(comm.allgather(v)) for k, v in mine.items()}
    _, _, alone = build(MPI.COMM_SELF, name, dp)
    alone = {k: alone.arrays[k][:alone.n_owned] for k in fields}
    gathered, alone = by_gid(gathered), by_gid(alone)
    assert len(np.unique(gathered["gid"])) == len(gathered["gid"])
    for k in fields:
        assert np.array_equal(gathered[k], alone[k]), k
    # the solver's first balance of these particles gives this rank the slab it built
    lo, hi = case.domain
    decomp = SlabDecomposition(comm, case.slab_axis, lo[case.slab_axis], hi[case.slab_axis], parts.kernel.support)
    decomp.balance(mine["x"][:, case.slab_axis], particle_work(pa, None))
    assert np.all(decomp.owner(mine["x"][:, case.slab_axis]) == comm.rank)
    assert comm.allreduce(n, op=MPI.MIN) > 0
