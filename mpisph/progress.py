"""Progress lines on rank 0: step, time, time step, particles, wall time, ETA, throughput."""

import sys
import time as wallclock

import numpy as np
from mpi4py import MPI

from .memory import per_rank_line, resident_bytes
from .particles import MOVING

PRINT_EVERY = 2.0  # seconds of wall time between lines that are not at a frame


class Progress:
    def __init__(self, comm, quiet, baseline_bytes):
        self.comm = comm
        self.quiet = quiet
        self.baseline = baseline_bytes  # resident before the case was built (memory.per_rank_line)
        self.start_bytes = 0
        self.n_total = 0
        self._last = -np.inf
        self._first = None  # (wall, t, step) at the first progress line

    def start(self, sim):
        self.start_bytes = resident_bytes()
        pa = sim.particles
        self.n_total = self.comm.allreduce(int(np.count_nonzero(pa.owned("kind") == MOVING)))
        self._say(f"mpisph: case {sim.params['case']}, {self.n_total} moving particles, "
                  f"{self.comm.size} rank(s), t = {sim.t:g} s to {sim.params['t_end']:g} s, "
                  f"frames in {sim.out_dir}")
        for line in sim.parts.scheme.report():
            self._say(line)
        for line in (*sim.case.warnings, *sim.parts.scheme.warnings()):
            self.warn(line)

    def warn(self, line):
        """``line`` as a warning on rank 0's standard error, quiet or not."""
        if self.comm.rank == 0:
            print(f"mpisph: warning: {line}", file=sys.stderr, flush=True)

    def __call__(self, sim, wall, t0, step0, at_frame):
        now = wallclock.perf_counter()
        if not at_frame and now - self._last < PRINT_EVERY:
            return
        self._last = now
        # the pace (ETA, throughput) of later lines is since the first line, leaving out the numba
        # compile that the first steps take; the first line's throughput is since the start, its ETA "-"
        first = self._first is None
        since_wall, since_t, since_step = (0.0, t0, step0) if first else self._first
        if first:
            self._first = (wall, sim.t, sim.step)
        spent, done = wall - since_wall, sim.t - since_t
        eta = f"{'-':>8}  " if first or not done > 0 else f"{spent * (sim.params['t_end'] - sim.t) / done:8.1f} s"
        rate = self.n_total * (sim.step - since_step) / spent if spent > 0 else 0.0
        self._say(f"step {sim.step:8d}  t {sim.t:.5e} s  dt {sim.time_step:.3e} s  N {self.n_total}  "
                  f"wall {wall:8.1f} s  ETA {eta}  {rate:.3e} particle-steps/s"
                  + (f"  frame {sim.frame_index}" if at_frame else ""))

    def finish(self, sim, wall, step0, ended="done"):
        """Closing lines: how the run ``ended`` (done, stopped), where the time went (slowest rank
        per phase), the throughput, the scheme's own (Scheme.closing_report) and the memory."""
        phases = sim.timer.summary(self.comm)
        refresh = self.comm.allreduce(sim.halo.refresh_seconds, op=MPI.MAX)
        phases["exchange"] += refresh
        phases["physics"] = max(0.0, phases["physics"] - refresh)
        steps = sim.step - step0
        rate = self.n_total * steps / wall / self.comm.size if wall > 0 else 0.0
        shares = "  ".join(f"{k} {100 * v / wall:.1f}%" for k, v in phases.items())
        self._say(f"mpisph: {ended} at t = {sim.t:g} s after {sim.step} steps")
        self._say(f"timing: wall {wall:.2f} s  {shares}")
        self._say(f"throughput: {rate:.4g} particle-steps/s/core on {self.comm.size} rank(s), "
                  f"{self.n_total} particles, {steps} steps, {sim.advection_steps} neighbour configurations")
        for line in sim.parts.scheme.closing_report():
            self._say(line)
        self._say(per_rank_line(self.comm, self.baseline, self.start_bytes, sim.particles.n_owned))

    def _say(self, line):
        if self.comm.rank == 0 and not self.quiet:
            print(line, file=sys.stdout, flush=True)
