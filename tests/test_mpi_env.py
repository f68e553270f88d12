"""The environment mpisph runs mpirun with (scripts/mpi_env.sh, and launch.MPI_ENV for tests,
benchmarks and scripts) leaves every rank free to use every core: Open MPI 4 otherwise binds
rank r to core r, so two runs started side by side share core 0 at half speed."""

import os
import shlex
import subprocess
import sys

import pytest

from mpisph.launch import MPI_ENV, ROOT

CORES = len(os.sched_getaffinity(0))
BINDING = ("OMPI_MCA_hwloc_base_binding_policy", "PRTE_MCA_hwloc_default_binding_policy")
PRINT_CORES = [sys.executable, "-c", "import os; print(len(os.sched_getaffinity(0)))"]

pytestmark = pytest.mark.skipif(CORES < 2, reason="binding to one core cannot be told apart on one core")


def unbound_environment():
    """This process's environment without any binding setting of its own."""
    return {k: v for k, v in os.environ.items() if k not in BINDING}


def cores_per_rank(cmd, env):
    r = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=120, cwd=ROOT)
    assert r.returncode == 0, r.stderr
    return [int(line) for line in r.stdout.split()]


def test_launch_environment_leaves_every_core_to_each_rank():
    env = dict(MPI_ENV, **unbound_environment())
    assert cores_per_rank(["mpirun", "-n", "2", *PRINT_CORES], env) == [CORES, CORES]


def test_mpi_env_script_leaves_every_core_to_each_rank():
    script = f"source scripts/mpi_env.sh && mpirun -n 1 {shlex.join(PRINT_CORES)}"
    assert cores_per_rank(["bash", "-c", script], unbound_environment()) == [CORES]
