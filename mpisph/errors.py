"""Errors that end a run with one clear line instead of a traceback."""


class InputError(Exception):
    """Bad user input (case, parameter, restart file, output directory).

    The command line prints ``mpisph: error: <message>`` on stderr and exits
    with status 2, before any output is written.
    """


class BlowUp(Exception):
    """The simulation produced a non-finite value or lost a particle; its message names the step,
    the time and, when one particle is to blame, its rank and id."""


class NoConvergence(Exception):
    """An iterative solve inside a time step did not converge. Its decisions rest on
    partition-independent sums, so every rank raises it at the same iteration; the solver
    turns it into a BlowUp that names the step."""


class Stopped(Exception):
    """The run was asked to stop by a signal (parallel/stop.py) and wrote its state as a
    frame; the command line prints how to restart from it and exits with status 0."""

    def __init__(self, signal_name, *, step, time, frame):
        super().__init__(f"stopped by {signal_name} at step {step}, t = {time:.6g} s")
        self.frame = frame
