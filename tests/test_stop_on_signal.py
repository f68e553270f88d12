"""A run asked to stop by SIGUSR1 (forwarded by mpirun, as a batch system's walltime warning) or
SIGTERM (sent to the ranks, as srun and scancel do) finishes its step, writes a frame, says how
to restart and exits 0; the restart continues from that frame (parallel/stop.py)."""

import os
import re
import signal
import subprocess
import sys

import pytest

from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import check_frame, list_frames, read_frame
from mpisph.launch import MPI_ENV, ROOT
from mpirun import mpisph, signal_when_running

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
                     rf"mpirun -n \d python -m mpisph dam_break_2d --restart (\S+) --out (\S+)", line)
    assert m, line
    assert re.search(r"^memory: largest rank [\d.e+-]+ GB at start-up, [\d.e+-]+ GB at the peak; above the "
                     r"interpreter and libraries \d+ and \d+ bytes per owned particle$", stdout, re.M), stdout
    frame = m.group(3)
    assert m.group(4) == frame and list_frames(out)[-1] == frame
    check_frame(frame)
    state = read_frame(frame)
    assert state["step"] == int(m.group(1)) > 0 and 0 < state["t"] < 10  # between two output times
    # the restart goes on from the frame's time (a little further, to keep the test short)
    t_end = state["t"] + 0.01
    r = mpisph(["dam_break_2d", "--restart", frame, "--t-end", repr(t_end), "--out", out, "--quiet"], ranks=1)
    assert r.returncode == 0, r.stderr
    last = read_frame(list_frames(out)[-1])
    assert last["t"] == pytest.approx(t_end) and last["step"] > state["step"]
    diag = read_diagnostics(out / "diagnostics.csv")
    assert diag["t"][-1] == pytest.approx(t_end)
