"""The cluster job scripts (jobs/): their command lines in a dry run (MPISPH_DRY_RUN=1) under a
faked Slurm and PBS environment, and jobs/chain.sh for real on this machine: a signal to the batch
shell stops the run with a frame and submits the next job of the chain from it."""

import os
import signal
import subprocess
import sys

import pytest

from mpisph.io.frames import list_frames
from mpisph.launch import MPI_ENV, ROOT
from mpirun import signal_when_running

STOPPED = ("mpisph: stopped by SIGUSR1 at step 512, t = 1.25 s; frame runs/x/frame_00003.hdf written; "
           "continue with: mpirun -n 64 python -m mpisph flume_3d --restart runs/x/frame_00003.hdf --out runs/x")


def _render(script, env, args=()):
    env = {"PATH": os.environ["PATH"], "MPISPH_DRY_RUN": "1", "TMPDIR": "/scratch/node", "USER": "alice", **env}
    r = subprocess.run(["bash", str(ROOT / "jobs" / script), *args], env=env, capture_output=True, text=True,
                       timeout=60)
    assert r.returncode == 0, r.stderr
    return r.stdout.splitlines()


@pytest.mark.parametrize("stopped", [False, True])
def test_slurm_job_lines(stopped):
    env = {"SLURM_SUBMIT_DIR": str(ROOT), "SLURM_NNODES": "2", "SLURM_NTASKS": "64", "SLURM_JOB_ID": "1234",
           "SLURM_JOB_PARTITION": "long", "SLURM_JOB_ACCOUNT": "geo42"}
    if stopped:
        env["MPISPH_DRY_RUN_LAST_LINE"] = STOPPED
    lines = _render("slurm/mpisph.sbatch", env, ["flume_3d", "--set", "dp=0.02"])
    assert lines[0] == ("mpisph job: job 1 of at most 20; output in runs/flume_3d-1234; numba cache in "
                        "/scratch/node/mpisph-numba-alice")
    commands = [line for line in lines if line.startswith("+ ")]
    expected = [
        "+ srun --mpi=pmix --nodes=2 --ntasks-per-node=1 --ntasks=2 .venv/bin/python -m mpisph flume_3d --t-end 1e-9 "
        "--out runs/flume_3d-1234/warm-up --quiet",
        "+ mkdir -p runs/flume_3d-1234",
        "+ srun --mpi=pmix .venv/bin/python -m mpisph flume_3d --set dp=0.02 --out runs/flume_3d-1234",
    ]
    if stopped:
        expected.append("+ sbatch --dependency=afterany:1234 --nodes=2 --ntasks=64 --partition=long --account=geo42 "
                        "--export=ALL jobs/slurm/mpisph.sbatch flume_3d --restart runs/x/frame_00003.hdf")
    assert commands == expected
    script = (ROOT / "jobs" / "slurm" / "mpisph.sbatch").read_text()
    assert "#SBATCH --signal=B:USR1@120" in script


def test_a_chain_stops_at_chain_max():
    env = {"SLURM_SUBMIT_DIR": str(ROOT), "SLURM_NNODES": "1", "SLURM_NTASKS": "2", "SLURM_JOB_ID": "7",
           "MPISPH_DRY_RUN_LAST_LINE": STOPPED, "CHAIN_INDEX": "3", "CHAIN_MAX": "3"}
    lines = _render("slurm/mpisph.sbatch", env, ["flume_3d"])
    assert not any(line.startswith("+ sbatch") for line in lines)
    assert lines[-1] == ("mpisph job: stopped at runs/x/frame_00003.hdf; the chain has reached CHAIN_MAX=3 jobs, "
                         "not resubmitting")


def test_pbs_job_lines(tmp_path):
    nodefile = tmp_path / "nodes"
    nodefile.write_text("n1\nn1\nn2\nn2\n")
    env = {"PBS_O_WORKDIR": str(ROOT), "PBS_NODEFILE": str(nodefile), "PBS_JOBID": "99.server", "CASE": "flume_3d",
           "ARGS": "--set dp=0.02", "WALLTIME_SECONDS": "3600", "SELECT": "2:ncpus=2:mpiprocs=2", "PBS_QUEUE": "long",
           "MPISPH_DRY_RUN_LAST_LINE": STOPPED}
    lines = _render("pbs/mpisph.pbs", env)
    assert "mpisph job: SIGUSR1 to this job in 3480 s" in lines  # the walltime less 120 s, shown in a dry run too
    commands = [line for line in lines if line.startswith("+ ")]
    assert commands == [
        "+ mpirun -np 2 --map-by ppr:1:node .venv/bin/python -m mpisph flume_3d --t-end 1e-9 "
        "--out runs/flume_3d-99/warm-up --quiet",
        "+ mkdir -p runs/flume_3d-99",
        "+ mpirun -np 4 .venv/bin/python -m mpisph flume_3d --set dp=0.02 --out runs/flume_3d-99",
        "+ qsub -W depend=afterany:99.server -l select=2:ncpus=2:mpiprocs=2 -q long -v CASE=flume_3d,ARGS=--restart "
        "runs/x/frame_00003.hdf,OUT=runs/flume_3d-99,CHAIN_INDEX=2,CHAIN_MAX=20,SELECT=2:ncpus=2:mpiprocs=2 "
        "jobs/pbs/mpisph.pbs",
    ]


@pytest.mark.parametrize("walltime, after", [("3600", 3480), ("12:00:00", 43080), ("90:00", 5280), ("0:2:05", 5)])
def test_the_pbs_walltime_takes_seconds_or_hours_minutes_seconds(tmp_path, walltime, after):
    """PBS_WALLTIME as the site sets it, seconds or HH:MM:SS: its SIGUSR1 comes 120 s before it (a
    cluster probe's 12:00:00 was a shell syntax error, and the job ran on without a timer); a
    walltime of another form stops the job in one line."""
    nodefile = tmp_path / "nodes"
    nodefile.write_text("n1\n")
    env = {"PBS_O_WORKDIR": str(ROOT), "PBS_NODEFILE": str(nodefile), "PBS_JOBID": "9.server", "CASE": "dam_break_2d",
           "PBS_WALLTIME": walltime}
    assert f"mpisph job: SIGUSR1 to this job in {after} s" in _render("pbs/mpisph.pbs", env)
    r = subprocess.run(["bash", str(ROOT / "jobs" / "pbs" / "mpisph.pbs")], capture_output=True, text=True, timeout=60,
                       env={"PATH": os.environ["PATH"], "MPISPH_DRY_RUN": "1", **env, "PBS_WALLTIME": "12h"})
    assert r.returncode == 2 and r.stderr.strip().splitlines() == ["mpisph job: walltime '12h' is not [[HH:]MM:]SS"]


@pytest.mark.parametrize("script, env", [
    ("slurm/mpisph.sbatch", {"SLURM_SUBMIT_DIR": str(ROOT), "SLURM_NNODES": "1", "SLURM_NTASKS": "2",
                             "SLURM_JOB_ID": "7"}),
    ("pbs/mpisph.pbs", {"PBS_O_WORKDIR": str(ROOT), "PBS_JOBID": "7.server", "CASE": "flume3d"})])
def test_a_job_of_a_case_that_does_not_exist_stops_in_one_line(tmp_path, script, env):
    """A mistyped case stops the job before the warm-up takes the nodes, with mpisph's own line."""
    nodefile = tmp_path / "nodes"
    nodefile.write_text("n1\n")
    env = {"PATH": os.environ["PATH"], "MPISPH_DRY_RUN": "1", "TMPDIR": "/scratch/node", "USER": "alice",
           "PBS_NODEFILE": str(nodefile), **env}
    args = ["flume3d"] if script.startswith("slurm") else []
    r = subprocess.run(["bash", str(ROOT / "jobs" / script), *args], env=env, capture_output=True, text=True,
                       timeout=60)
    assert r.returncode == 2 and "+ " not in r.stdout
    assert r.stderr.strip().splitlines()[-1] == "mpisph: error: unknown case 'flume3d'; did you mean 'flume_3d'?"


DRIVER = """
LAUNCH=(mpirun -n 2)
LAUNCH_PER_NODE=(mpirun -n 1)
JOB_ID=local
PY="$PYTHON"
submit_after() { run echo "$@" > "$OUT/submitted"; }
source jobs/chain.sh
"""


def test_chain_stops_the_run_on_a_signal_and_submits_the_next_job(tmp_path):
    """chain.sh for real: SIGUSR1 to the batch shell while the run goes (as Slurm's --signal=B:USR1
    does) reaches the ranks through mpirun; the run stops with a frame, and the next job is
    submitted with --restart from it (submit_after records the arguments here)."""
    out = tmp_path / "run"
    env = dict(MPI_ENV, **os.environ, OUT=str(out), PYTHON=sys.executable,
               WARMUP_ARGS="--set dp=0.05 --t-end 1e-9")
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    proc = subprocess.Popen(["bash", "-c", DRIVER, "driver", "dam_break_2d", "--set", "dp=0.05", "--t-end", "50",
                             "--output-interval", "10"], cwd=ROOT, env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    code, stdout, stderr = signal_when_running(proc, out, signal.SIGUSR1)
    assert code == 0, stdout + stderr
    frame = list_frames(out)[-1]
    assert (out / "submitted").read_text().split() == ["dam_break_2d", "--restart", frame]
    assert "signal received: asking the run to stop" in stdout
