"""Stop requests by signal: SIGTERM (a scheduler ending the job, or kill) and SIGUSR1 (a batch
system's warning before the walltime, e.g. Slurm's ``--signal=B:USR1@120``).

A handler only records the signal; the ranks agree on it at the end of an advection
step (``requested``, one MAX reduction), so every rank stops after the same step, the
solver writes a frame and the run ends with status 0 and a line saying how to restart.
"""

import signal

from mpi4py import MPI

SIGNALS = (signal.SIGTERM, signal.SIGUSR1)


class StopOnSignal:
    """Installs the handlers (main thread only) and restores the previous ones on ``close``."""

    def __init__(self):
        self.received = 0
        self._previous = {s: signal.signal(s, self._handle) for s in SIGNALS}

    def _handle(self, signum, frame):
        self.received = max(self.received, int(signum))

    def requested(self, comm):
        """The name of a signal any rank received (collective), else None."""
        signum = comm.allreduce(self.received, op=MPI.MAX)
        return signal.Signals(signum).name if signum else None

    def close(self):
        for s, handler in self._previous.items():
            signal.signal(s, handler)
