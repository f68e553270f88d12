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
# Each rank writes its count to its own file: lines printed by two ranks at once can
# interleave on mpirun's stdout ("22" instead of "2" and "2").
WRITE_CORES = (
    "import os, sys; rank = os.environ.get('OMPI_COMM_WORLD_RANK', '0'); "
    "open(os.path.join(sys.argv[1], rank), 'w').write(str(len(os.sched_getaffinity(0))))"
)

pytestmark = [pytest.mark.skipif(CORES < 2, reason="binding to one core cannot be told apart on one core"),
              pytest.mark.ranks]  # tests/conftest.py


def unbound_environment():
    """This process's environment without any binding setting of its own."""
    return {k: v for k, v in os.environ.items() if k not in BINDING}


def write_cores(out):
    """The command by which every rank writes the number of cores it may use into out/<rank>."""
    return [sys.executable, "-c", WRITE_CORES, str(out)]


def cores_per_rank(cmd, env, out):
    r = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=120, cwd=ROOT)
    assert r.returncode == 0, r.stderr
    return [int((out / rank).read_text()) for rank in sorted(os.listdir(out))]


def test_launch_environment_leaves_every_core_to_each_rank(tmp_path):
    env = dict(MPI_ENV, **unbound_environment())
    cmd = ["mpirun", "-n", "2", *write_cores(tmp_path)]
    assert cores_per_rank(cmd, env, tmp_path) == [CORES, CORES]


def test_mpi_env_script_leaves_every_core_to_each_rank(tmp_path):
    script = f"source scripts/mpi_env.sh && mpirun -n 1 {shlex.join(write_cores(tmp_path))}"
    assert cores_per_rank(["bash", "-c", script], unbound_environment(), tmp_path) == [CORES]
