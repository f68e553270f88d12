"""Wall time per phase of the step loop, for the summary printed after a run."""

import time
from contextlib import contextmanager

from mpi4py import MPI

PHASES = ("exchange", "neighbours", "physics", "io")


class PhaseTimer:
    def __init__(self):
        self.seconds = dict.fromkeys(PHASES, 0.0)

    @contextmanager
    def __call__(self, phase):
        t0 = time.perf_counter()
        try:
            yield
        finally:
            self.seconds[phase] += time.perf_counter() - t0

    def summary(self, comm):
        """Per-phase seconds, maximum over ranks (the slowest rank sets the pace)."""
        return {k: comm.allreduce(v, op=MPI.MAX) for k, v in self.seconds.items()}
