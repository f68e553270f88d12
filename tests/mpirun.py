"""Run ``python -m mpisph`` under mpirun from a test, with a hard time limit."""

from mpisph.launch import mpirun_mpisph


def mpisph(args, ranks=1, timeout=600):
    """A run that does not finish within ``timeout`` seconds (a deadlock) fails the test."""
    return mpirun_mpisph(args, ranks=ranks, timeout=timeout)
