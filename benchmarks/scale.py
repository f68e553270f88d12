"""Ten million particles: flume_3d built a slab per rank, a few steps and one frame, on 2 and 8 ranks.

    .venv/bin/python benchmarks/scale.py [--dp 0.0062] [--ranks 2 8] [--steps 10]

dp = 0.0062 m gives 8.06 M soil and 2.12 M wall particles. Each rank count is a fresh
``mpirun`` of this file's worker, after a one-rank warm-up at dp = 0.1 m that fills numba's cache
(as the cluster jobs do). The worker builds the case as ``python -m mpisph`` does, runs the steps
(a neighbour configuration each: the flume steps once per configuration) and writes one frame,
and prints per rank:

- set-up time, and the peak resident memory during set-up and during the steps, above the
  interpreter and libraries (measured before the case is built);
- each rank's share of the run's own memory: its owned particles times the run's bytes per owned
  particle (the sum over ranks of the step peaks over the particle count), and the largest ratio
  of a rank's peak to its share, at set-up and in the steps;
- particle-steps per second per core (cores: the ranks, or the machine's cores when there are
  fewer) and the frame's size over its write time;
- the halo (ghosts) of every rank, and from the particles' histogram along the slab axis, the
  halo-to-owned ratio that slabs balanced the same way would have at 8, 32 and 128 ranks, first
  checked against the measured halos at this rank count.
"""

import argparse
import json
import os
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
PROJECTED = (8, 32, 128)


def projected_halos(counts, moving, bin_width, support, ranks):
    """Owned and ghost particles per rank of slabs cut as the first balance cuts them (equal
    moving-particle counts, on the histogram's bins), from the histograms ``counts`` (all
    particles) and ``moving`` along the slab axis: a rank's ghosts are the particles within one
    support outside its slab."""
    from mpisph.parallel.decomposition import balanced_edges
    edges = balanced_edges(moving, ranks)
    reach = int(round(support / bin_width))
    cum = np.concatenate([[0.0], np.cumsum(counts)])
    owned, ghosts = [], []
    for a, b in zip(edges[:-1], edges[1:]):
        owned.append(cum[b] - cum[a])
        ghosts.append(cum[a] - cum[max(a - reach, 0)] + cum[min(b + reach, len(counts))] - cum[b])
    return np.array(owned), np.array(ghosts)


def worker(dp, steps, out):
    """Runs under mpirun: build, step and write as the run command does; rank 0 prints a JSON line."""
    from mpi4py import MPI

    from mpisph import case as cases
    from mpisph.initial import particles_from_case
    from mpisph.memory import check_fits, peak_bytes, resident_bytes
    from mpisph.particles import MOVING
    from mpisph.parts import make_parts
    from mpisph.solver import Simulation

    comm = MPI.COMM_WORLD
    baseline = resident_bytes()
    comm.Barrier()
    t0 = time.perf_counter()
    module = cases.load_case_module("flume_3d")
    values = cases.resolve_params(module, {"dp": str(dp)})
    values["case"] = "flume_3d"
    case = cases.build_case(module, values)
    parts = make_parts(case, values)
    case.validate(parts.kernel.support)
    check_fits(comm, case.sources)
    pa = particles_from_case(comm, case, parts)
    case.forget_particles()
    comm.Barrier()
    setup = time.perf_counter() - t0
    setup_peak = peak_bytes()
    sim = Simulation(comm, case, values, pa, parts, out_dir=out, diagnostics=None, progress=None)
    comm.Barrier()
    t1 = time.perf_counter()
    for _ in range(steps):
        sim._configure()
        dt = sim._time_steps()[0]
        sim.parts.integrator.step(sim.ctx, dt)
        sim.step += 1
        sim.t += dt
    comm.Barrier()
    stepping = time.perf_counter() - t1
    owned, ghosts = pa.n_owned, pa.n_ghost
    step_peak = peak_bytes()
    comm.Barrier()
    t2 = time.perf_counter()
    sim.write_frame()
    comm.Barrier()
    writing = time.perf_counter() - t2
    axis = sim.decomp.axis
    s = pa.x[:owned, axis]
    bins = sim.decomp.bin_of(s)
    counts = comm.allreduce(np.bincount(bins, minlength=sim.decomp.nbins).astype(float), op=MPI.SUM)
    moving = comm.allreduce(np.bincount(bins, weights=(pa.kind[:owned] == MOVING).astype(float),
                                        minlength=sim.decomp.nbins).astype(float), op=MPI.SUM)
    rows = comm.gather(dict(owned=owned, ghosts=ghosts, baseline=baseline, setup_peak=setup_peak - baseline,
                            step_peak=step_peak - baseline), root=0)
    if comm.rank == 0:
        frame = sorted(f for f in os.listdir(out) if f.endswith(".hdf"))[-1]
        print(json.dumps(dict(ranks=comm.size, dp=dp, steps=steps, setup=setup, stepping=stepping, writing=writing,
                              frame_bytes=os.path.getsize(os.path.join(out, frame)), rows=rows,
                              counts=counts.tolist(), moving=moving.tolist(), bin_width=sim.decomp.bin_width,
                              support=parts.kernel.support)), flush=True)


def report(r):
    rows = r["rows"]
    ranks, n = r["ranks"], sum(row["owned"] for row in rows)
    cores = min(ranks, os.cpu_count())
    per_particle = sum(row["step_peak"] for row in rows) / n
    print(f"flume_3d dp = {r['dp']} m, {n} particles on {ranks} ranks ({cores} cores): "
          f"set-up {r['setup']:.1f} s; {r['steps']} steps in {r['stepping']:.1f} s, "
          f"{n * r['steps'] / r['stepping'] / cores:.3g} particle-steps/s/core; frame {r['frame_bytes'] / 1e9:.2f} GB "
          f"in {r['writing']:.1f} s, {r['frame_bytes'] / r['writing'] / 1e6:.0f} MB/s")
    print(f"  the run's own memory: {per_particle:.0f} bytes per owned particle (step peaks above the interpreter, "
          f"summed over ranks, over the particles)")
    worst = {"setup_peak": 0.0, "step_peak": 0.0}
    for k, row in enumerate(rows):
        share = row["owned"] * per_particle
        ratios = {key: row[key] / share for key in worst}
        worst = {key: max(worst[key], ratios[key]) for key in worst}
        print(f"  rank {k}: {row['owned']} owned, {row['ghosts']} ghosts ({row['ghosts'] / row['owned']:.2f}); "
              f"peak {row['setup_peak'] / 1e9:.2f} GB at set-up, {row['step_peak'] / 1e9:.2f} GB in the steps; "
              f"share {share / 1e9:.2f} GB; interpreter and libraries {row['baseline'] / 1e9:.2f} GB")
    print(f"  largest peak / share: {worst['setup_peak']:.2f} at set-up, {worst['step_peak']:.2f} in the steps")
    counts, moving = np.array(r["counts"]), np.array(r["moving"])
    owned, ghosts = projected_halos(counts, moving, r["bin_width"], r["support"], ranks)
    measured = np.array([row["ghosts"] for row in rows])
    print(f"  halo from the histogram at {ranks} ranks: {ghosts.sum():.0f} ghosts (measured {measured.sum()}), "
          f"largest ghosts / owned {np.max(ghosts / owned):.2f} (measured "
          f"{max(row['ghosts'] / row['owned'] for row in rows):.2f})")
    for size in PROJECTED:
        owned, ghosts = projected_halos(counts, moving, r["bin_width"], r["support"], size)
        print(f"  projected at {size} ranks: ghosts / owned {ghosts.sum() / owned.sum():.2f} overall, "
              f"{np.max(ghosts / owned):.2f} on the worst rank")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dp", type=float, default=0.0062)
    ap.add_argument("--ranks", type=int, nargs="+", default=[2, 8])
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument("--worker", nargs=2, metavar=("STEPS", "OUT"), help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.worker:
        worker(a.dp, int(a.worker[0]), a.worker[1])
        return
    sys.path.insert(0, os.path.dirname(HERE))
    from mpisph.launch import ROOT, mpirun_mpisph, mpirun_python
    with tempfile.TemporaryDirectory() as out:
        mpirun_mpisph(["flume_3d", "--set", "dp=0.1", "--t-end", "0.01", "--out", out, "--quiet"],
                      accept=(0,))  # numba's cache
    (ROOT / "runs").mkdir(exist_ok=True)  # a fresh checkout has none
    for ranks in a.ranks:
        with tempfile.TemporaryDirectory(dir=ROOT / "runs") as out:
            args = [os.path.abspath(__file__), "--dp", str(a.dp), "--worker", str(a.steps), out]
            r = mpirun_python(args, ranks=ranks, accept=(0,))
            report(json.loads(r.stdout.strip().splitlines()[-1]))
        print(f"  [.venv/bin/python benchmarks/scale.py --dp {a.dp} --ranks {ranks} --steps {a.steps}]", flush=True)


if __name__ == "__main__":
    main()
