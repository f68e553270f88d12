"""Run ``python -m mpisph`` under mpirun from a test, with a hard time limit; signal a running one."""

import os
import re
import subprocess
import time

import pytest

from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import list_frames, read_frame
from mpisph.launch import mpirun_mpisph


def mpisph(args, ranks=1, timeout=600):
    """A run that does not finish within ``timeout`` seconds (a deadlock) fails the test."""
    return mpirun_mpisph(args, ranks=ranks, timeout=timeout)


# Open MPI 4.1's mpirun may add this libevent warning when its ranks exit at once with an error
# (a race in its own shutdown, open-mpi/ompi#2004): a line of the launcher's, not of mpisph's.
LAUNCHER_NOISE = re.compile(r"^\[warn\] Epoll [A-Z]+\(\d+\) on fd \d+ failed\.")


def stderr_lines(stderr):
    """The non-blank lines of a run's stderr, without mpirun's libevent shutdown warning."""
    return [ln for ln in stderr.splitlines() if ln.strip() and not LAUNCHER_NOISE.match(ln)]


def run(case, args, out, ranks=1, timeout=900):
    """``case`` with ``args``, written to ``out``: its frames (read) and diagnostics."""
    r = mpisph([case, *args, "--out", out, "--quiet"], ranks=ranks, timeout=timeout)
    assert r.returncode == 0, r.stderr
    return [read_frame(f) for f in list_frames(out)], read_diagnostics(out / "diagnostics.csv")


def runs_on(tmp_path_factory, name, case, args, ranks=(1, 2), timeout=600):
    """``case`` with ``args`` on each rank count of ``ranks``: {ranks: output directory}."""
    out = {}
    for n in ranks:
        d = tmp_path_factory.mktemp(f"{name}_{n}")
        r = mpisph([case, *args, "--out", d, "--quiet"], ranks=n, timeout=timeout)
        assert r.returncode == 0, r.stderr
        out[n] = d
    return out


def _has_diagnostics_rows(out):
    path = out / "diagnostics.csv"
    return path.exists() and len(path.read_text().splitlines()) > 3


def signal_when_running(proc, out, signum, timeout=300, ready=_has_diagnostics_rows):
    """Once the run started as ``proc`` (a Popen with captured text output) is ``ready(out)`` (by
    default: it has written a few rows of ``out``/diagnostics.csv), send it ``signum``; return its
    (exit status, stdout, stderr). A run that does not end within ``timeout`` seconds after the
    signal fails the test."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and proc.poll() is None:
        if ready(out):
            os.kill(proc.pid, signum)
            break
        time.sleep(0.2)
    try:
        stdout, stderr = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        proc.kill()
        pytest.fail("the run did not end after the signal")
    return proc.returncode, stdout, stderr
