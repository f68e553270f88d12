"""Time to write one frame and its bandwidth, against plain numpy writing the same bytes.

    .venv/bin/python benchmarks/frames.py [--dp 0.02]   (1M soil particles + 0.27M wall particles)

The first frame of the 3D cube failure (every field the solver writes, wall
particles included) is written as the solver writes it, on 1 and 2 ranks
(collective parallel HDF5); the same number of bytes is then written by
numpy's tofile from one process to the same directory. Both are timed up
to an fsync, so the figures are the disk's, not the page cache's; each is the
best of three writes.
"""

import argparse
import os
import tempfile
import time

import numpy as np

from mpisph.io.frames import frame_path
from mpisph.launch import ROOT, mpirun_python

HERE = os.path.dirname(os.path.abspath(__file__))
REPEATS = 3  # best of, for each writer: the disk's speed varies from write to write


def worker(dp, out):
    """Runs under mpirun: build the cube failure at spacing ``dp`` and write its first frame
    collectively, as the solver does; print seconds, bytes and particles on rank 0."""
    from mpi4py import MPI

    from mpisph import case as cases
    from mpisph.initial import particles_from_case
    from mpisph.parts import make_parts
    from mpisph.solver import Simulation
    comm = MPI.COMM_WORLD
    module = cases.load_case_module("cube_failure_3d")
    values = cases.resolve_params(module, {"dp": str(dp)})
    values["case"] = "cube_failure_3d"
    case = cases.build_case(module, values)
    parts = make_parts(case, values)
    pa = particles_from_case(comm, case, parts)
    sim = Simulation(comm, case, values, pa, parts, out_dir=out, diagnostics=None, progress=None)
    sim.frame_index = comm.size  # one file per rank count
    n_total = comm.allreduce(pa.n_owned)
    comm.Barrier()
    t0 = time.perf_counter()
    sim.write_frame()
    path = frame_path(out, sim.frame_index)
    if comm.rank == 0:
        fd = os.open(path, os.O_RDONLY)
        os.fsync(fd)
        os.close(fd)
    comm.Barrier()
    seconds = time.perf_counter() - t0
    if comm.rank == 0:
        print(seconds, os.path.getsize(path), n_total)


def numpy_write(nbytes, out):
    """Seconds for numpy to write ``nbytes`` to one file in ``out`` and fsync it."""
    data = np.random.default_rng(0).random(nbytes // 8)
    path = os.path.join(out, "plain.bin")
    t0 = time.perf_counter()
    with open(path, "wb") as f:
        data.tofile(f)
        f.flush()
        os.fsync(f.fileno())
    return time.perf_counter() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dp", type=float, default=0.02, help="spacing of the cube failure case [m]")
    ap.add_argument("--worker", nargs=2, metavar=("DP", "DIR"), help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.worker:
        return worker(float(a.worker[0]), a.worker[1])
    with tempfile.TemporaryDirectory(dir=ROOT) as out:
        results = {}
        for ranks in (1, 2):
            for _ in range(REPEATS):
                r = mpirun_python([os.path.join(HERE, "frames.py"), "--worker", str(a.dp), out], ranks=ranks,
                                  timeout=600, accept=(0,))
                seconds, nbytes, n = r.stdout.split()
                if ranks not in results or float(seconds) < results[ranks][0]:
                    results[ranks] = float(seconds), int(nbytes), int(n)
        nbytes = results[1][1]
        plain = min(numpy_write(nbytes, out) for _ in range(REPEATS))
    plain_bw = nbytes / plain / 1e6
    print(f"numpy tofile of {nbytes / 1e6:.0f} MB: {plain:.2f} s, {plain_bw:.0f} MB/s  "
          f"[.venv/bin/python benchmarks/frames.py --dp {a.dp}]")
    for ranks, (seconds, size, n) in results.items():
        bw = size / seconds / 1e6
        print(f"frame of {n} particles of cube_failure_3d dp={a.dp} ({size / 1e6:.0f} MB) on {ranks} rank(s): "
              f"{seconds:.2f} s, {bw:.0f} MB/s, {100 * bw / plain_bw:.0f}% of numpy's bandwidth")


if __name__ == "__main__":
    main()
