"""Several runs of mpisph in one launch: ``mpirun -n N python tests/runs_in_one_launch.py SPEC``.

SPEC is a JSON file: a list of ``[ranks, argv]``, run in that order. Each run takes the first
``ranks`` ranks of the launch as its communicator, while the others wait for it without spinning.
A small case's run is mostly the start-up of Python, numba's cache and MPI (about 2 s of a 2.4 s
run of the 2D column on one rank), so the runs of a case's variants on 1, 2 and 3 ranks share one
start-up. A run that does not end with status 0 ends the launch with its status (1 for an
exception), after a line that names it."""

import json
import sys
import time
import traceback

from mpi4py import MPI

from mpisph.__main__ import main


def wait_for_all(comm, poll=0.002):
    """A barrier over ``comm`` in which a waiting rank sleeps, leaving its core to the ranks that run."""
    request = comm.Ibarrier()
    while not request.Test():
        time.sleep(poll)


def run_all(spec, world):
    for ranks, argv in spec:
        if ranks > world.size:
            raise SystemExit(f"runs_in_one_launch: a run on {ranks} ranks in a launch of {world.size}")
        comm = world.Split(0 if world.rank < ranks else MPI.UNDEFINED, world.rank)
        if comm != MPI.COMM_NULL:
            try:
                status = main(argv, comm)
            except Exception:  # main raises on a 1-rank communicator: end the launch, not leave the rest waiting
                traceback.print_exc()
                status = 1
            if status:
                print(f"runs_in_one_launch: {' '.join(argv)} on {ranks} ranks ended with status {status}",
                      file=sys.stderr, flush=True)
                world.Abort(status)
            comm.Free()
        wait_for_all(world)


if __name__ == "__main__":
    with open(sys.argv[1]) as f:
        run_all(json.load(f), MPI.COMM_WORLD)
