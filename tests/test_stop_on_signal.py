"""A run asked to stop by SIGUSR1 (forwarded by mpirun, as a batch system's walltime warning) or
SIGTERM (sent to the ranks, as srun and scancel do) finishes its step, writes a frame, says how
to restart and exits 0; the restart continues from that frame (parallel/stop.py) to the bits of a
run never stopped. A run killed with SIGKILL while it writes a frame leaves only complete frames
(io/frames.py writes ``.part`` files and renames them). mpirun itself passes SIGUSR1 on at once and
SIGTERM only after Open MPI's grace, which decides whether a long step can end (README.md)."""

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import check_frame, list_frames, read_frame
from mpisph.launch import MPI_ENV, ROOT, stopped_by_signal
from mpirun import mpisph, signal_when_running

pytestmark = pytest.mark.ranks  # tests/conftest.py

RUN = ["dam_break_2d", "--set", "dp=0.05", "--t-end", "50", "--output-interval", "10"]


def _start(cmd, out):
    env = dict(MPI_ENV, **os.environ)
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    return subprocess.Popen([*cmd, "-m", "mpisph", *RUN, "--out", str(out)], cwd=ROOT, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


@pytest.mark.parametrize("how", ["SIGUSR1 to mpirun, 2 ranks", "SIGTERM to the rank"])
def test_a_signal_stops_the_run_with_a_frame_to_restart_from(tmp_path, how):
    out = tmp_path / "run"
    if how.startswith("SIGUSR1"):
        proc = _start(["mpirun", "-n", "2", sys.executable], out)
        code, stdout, stderr = signal_when_running(proc, out, signal.SIGUSR1)
        name = "SIGUSR1"
    else:  # one rank started without mpirun, signalled directly
        proc = _start([sys.executable], out)
        code, stdout, stderr = signal_when_running(proc, out, signal.SIGTERM)
        name = "SIGTERM"
    assert code == 0, stderr
    line = stdout.strip().splitlines()[-1]
    m = re.fullmatch(rf"mpisph: stopped by {name} at step (\d+), t = (\S+) s; frame (\S+) written; continue with: "
                     rf"mpirun -n \d (\S+) -m mpisph dam_break_2d --restart (\S+) --out (\S+)", line)
    assert m, line
    assert m.group(4) == sys.executable  # the interpreter that has mpisph, where a bare python may not
    assert stopped_by_signal(stdout) == line  # how scripts/validation/runs.py tells a stopped run
    assert re.search(r"^memory: largest rank [\d.e+-]+ GB at start-up, [\d.e+-]+ GB at the peak; above the "
                     r"interpreter and libraries \d+ and \d+ bytes per owned particle$", stdout, re.M), stdout
    frame = m.group(3)
    assert m.group(5) == frame and list_frames(out)[-1] == frame
    check_frame(frame)
    state = read_frame(frame)
    assert state["step"] == int(m.group(1)) > 0 and 0 < state["t"] < 10  # between two output times
    # the restart goes on from the frame's time (a little further, to keep the test short)
    t_end = state["t"] + 0.01
    r = mpisph(["dam_break_2d", "--restart", frame, "--t-end", repr(t_end), "--out", out, "--quiet"], ranks=1)
    assert r.returncode == 0 and stopped_by_signal(r.stdout) is None, r.stderr
    last = read_frame(list_frames(out)[-1])
    assert last["t"] == pytest.approx(t_end) and last["step"] > state["step"]
    diag = read_diagnostics(out / "diagnostics.csv")
    assert diag["t"][-1] == pytest.approx(t_end)


def test_a_run_stopped_by_a_signal_and_restarted_ends_with_the_bits_of_an_uninterrupted_one(tmp_path):
    """SIGTERM at whatever step the run has reached, a restart from the frame it writes, and the
    run without the stop, both to a little past that step: the same particles, bit for bit, and
    diagnostics.csv's rows at the same times with the same energies (tests/test_restart_directory.py
    restarts from a frame whose count of advection steps is not a multiple of the rows')."""
    stopped = tmp_path / "stopped"
    proc = _start([sys.executable], stopped)
    code, stdout, stderr = signal_when_running(proc, stopped, signal.SIGTERM)
    assert code == 0, stderr
    frame = list_frames(stopped)[-1]
    state = read_frame(frame)
    t_end = repr(state["t"] + 0.1)
    r = mpisph(["dam_break_2d", "--restart", frame, "--t-end", t_end, "--out", stopped, "--quiet"], ranks=2)
    assert r.returncode == 0, r.stderr
    straight = tmp_path / "straight"
    r = mpisph([*RUN, "--t-end", t_end, "--out", straight, "--quiet"], ranks=1)
    assert r.returncode == 0, r.stderr
    a, b = read_frame(list_frames(stopped)[-1]), read_frame(list_frames(straight)[-1])
    assert a["step"] == b["step"] > state["step"] and a["t"] == b["t"]
    for name in ("gid", "x", "v", "rho", "p"):
        np.testing.assert_array_equal(a[name], b[name], err_msg=name)
    rows, straight_rows = read_diagnostics(stopped / "diagnostics.csv"), read_diagnostics(straight / "diagnostics.csv")
    assert np.sum(rows["t"] > state["t"]) >= 3  # rows between the restart and the end's frame
    np.testing.assert_array_equal(rows["t"], straight_rows["t"])
    np.testing.assert_array_equal(rows["step"], straight_rows["step"])
    np.testing.assert_allclose(rows["kinetic_energy"], straight_rows["kinetic_energy"], rtol=1e-12)


def test_a_run_killed_while_writing_a_frame_leaves_only_complete_frames(tmp_path):
    """kill -9 while a frame is being written (its ``.part`` file exists): every file under a
    frame's name is complete, and the half-written one is not listed."""
    big = ["dam_break_2d", "--set", "dp=0.004", "--t-end", "50", "--output-interval", "0.0005"]
    for attempt in range(5):
        out = tmp_path / f"attempt{attempt}"
        env = dict(MPI_ENV, **os.environ)
        env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
        proc = subprocess.Popen([sys.executable, "-m", "mpisph", *big, "--out", str(out), "--quiet"], cwd=ROOT,
                                env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        caught = False
        deadline = time.monotonic() + 300
        while time.monotonic() < deadline and proc.poll() is None:
            if len(list_frames(out)) >= 2 and list(out.glob("*.part")):
                os.kill(proc.pid, signal.SIGKILL)
                caught = True
                break
        proc.wait(timeout=60)
        if caught and list(out.glob("*.part")):
            break
    else:
        pytest.fail("no frame write was caught in five attempts")
    frames = list_frames(out)
    assert len(frames) >= 2
    for frame in frames:
        check_frame(frame)
    assert all(not p.name.endswith(".part") for p in map(Path, frames))


# a rank that ends its "step" 3 s after a stop signal, as a large run's step can: it only records the
# signal in its handler and checks it between steps, as parallel/stop.py does
_LONG_STEP = """
import pathlib, signal, sys, time
received = []
for s in (signal.SIGTERM, signal.SIGUSR1):
    signal.signal(s, lambda signum, frame: received.append(signum))
out = pathlib.Path(sys.argv[1])
(out / "started").touch()
give_up = time.monotonic() + 120  # never outlive the test
while not received and time.monotonic() < give_up:
    time.sleep(0.05)
time.sleep(3.0)
(out / "finished").touch()
"""


@pytest.mark.parametrize("signum, grace, finishes", [(signal.SIGUSR1, None, True), (signal.SIGTERM, None, False),
                                                     (signal.SIGTERM, "5", True)],
                         ids=["SIGUSR1", "SIGTERM", "SIGTERM with a grace of 5 s"])
def test_mpirun_lets_a_rank_end_a_long_step_after_sigusr1_and_after_sigterm_only_within_its_grace(
        tmp_path, signum, grace, finishes):
    """What README.md and jobs/README.md say of stopping a run through mpirun: it passes SIGUSR1 on
    and waits for the rank; on SIGTERM Open MPI 4 sends the rank SIGTERM once
    OMPI_MCA_odls_base_sigkill_timeout has passed (1 s unless set) and SIGKILL after as long again,
    so a step of 3 s ends only with a longer grace."""
    script = tmp_path / "long_step.py"
    script.write_text(_LONG_STEP)
    env = {k: v for k, v in dict(MPI_ENV, **os.environ).items() if k != "OMPI_MCA_odls_base_sigkill_timeout"}
    if grace is not None:
        env["OMPI_MCA_odls_base_sigkill_timeout"] = grace
    proc = subprocess.Popen(["mpirun", "-n", "1", sys.executable, str(script), str(tmp_path)], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    code, _, stderr = signal_when_running(proc, tmp_path, signum, timeout=60,
                                          ready=lambda out: (out / "started").exists())
    assert (tmp_path / "started").exists(), stderr
    assert (tmp_path / "finished").exists() == finishes, stderr
    if signum == signal.SIGUSR1:
        assert code == 0, stderr
