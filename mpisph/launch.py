"""Launch ``python -m mpisph`` under mpirun from tests, benchmarks and scripts."""

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# What scripts/mpi_env.sh exports for Open MPI 4: run as root, more ranks than cores,
# no cross-memory attach (not allowed in containers), no mpirun banner after a rank
# exits non-zero, idle ranks yield their core, no binding of rank r to core r (two runs at once
# would share core 0). Values already set in the environment win.
MPI_ENV = {
    "OMPI_ALLOW_RUN_AS_ROOT": "1",
    "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
    "OMPI_MCA_rmaps_base_oversubscribe": "1",
    "OMPI_MCA_btl_vader_single_copy_mechanism": "none",
    "OMPI_MCA_orte_execute_quiet": "1",
    "OMPI_MCA_mpi_yield_when_idle": "1",
    "OMPI_MCA_hwloc_base_binding_policy": "none",
}


def mpirun_mpisph(args, ranks=1, timeout=None, root=ROOT, accept=None):
    """``mpirun -n ranks python -m mpisph args`` from the repository root (or from the tree
    ``root``, another checkout of mpisph, whose code then runs).

    Returns the CompletedProcess (stdout and stderr captured as text); a run
    still going after ``timeout`` seconds is killed (subprocess.TimeoutExpired),
    so a deadlock fails instead of hanging. With ``accept``, a tuple of exit statuses
    (mpisph exits 3 on a blow-up), a run that ends with another status raises SystemExit
    with the command, the tree, the last 2000 characters of its output and its standard
    error, which is how scripts and benchmarks stop.
    """
    return mpirun_python(["-m", "mpisph", *args], ranks=ranks, timeout=timeout, root=root, accept=accept)


def mpirun_python(args, ranks=1, timeout=None, root=ROOT, accept=None, env=None):
    """``mpirun -n ranks python args`` as ``mpirun_mpisph`` starts it; ``env`` holds variables that
    override the caller's environment."""
    cmd = ["mpirun", "-n", str(ranks), sys.executable, *map(str, args)]
    env = dict(MPI_ENV, **os.environ, **(env or {}))
    env["PYTHONPATH"] = str(root) + os.pathsep + env.get("PYTHONPATH", "")
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env, cwd=root)
    if accept is not None and r.returncode not in accept:
        raise SystemExit(f"{command_line(args, ranks)} (in {root}) exited with status {r.returncode}:\n"
                         f"{r.stdout[-2000:]}{r.stderr}")
    return r


STOPPED = "mpisph: stopped by"  # how the line of a run that a signal stopped starts (__main__.py; jobs/chain.sh)


def stopped_by_signal(stdout):
    """The line saying how to go on, when the output ``stdout`` is a run's that a signal stopped (its
    exit status is 0 all the same), else None."""
    return next((line for line in stdout.splitlines() if line.startswith(STOPPED)), None)


def command_line(args, ranks=1):
    """``mpirun -n ranks python args`` as a user would type it, for pages and messages."""
    return " ".join(["mpirun", "-n", str(ranks), "python", *map(str, args)])
