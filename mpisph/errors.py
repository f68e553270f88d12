"""Errors that end a run with one clear line instead of a traceback."""


class InputError(Exception):
    """Bad user input (case, parameter, restart file, output directory).

    The command line prints ``mpisph: error: <message>`` on stderr and exits
    with status 2, before any output is written.
    """


class BlowUp(Exception):
    """The simulation produced a non-finite value or lost a particle.

    Carries where it happened so the message names step, time, rank and
    particle id.
    """

    def __init__(self, message, *, step, time, rank, gid):
        super().__init__(message)
        self.step = step
        self.time = time
        self.rank = rank
        self.gid = gid
