"""Where a restart without --out writes: on in its frame's directory (the run it continues), read
from wherever it is started and through a link to the frame; a one-line refusal, touching nothing,
when that directory holds frames after the restart's time, which it would replace, or when another
output interval would number a frame over one it keeps."""

import os
import subprocess
import sys

import numpy as np
import pytest

from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import list_frames, read_frame
from mpisph.launch import MPI_ENV, ROOT
from mpirun import stderr_lines

RUN = ["dam_break_2d", "--set", "dp=0.1", "--output-interval", "0.01", "--quiet"]


def mpisph(*args, cwd):
    """``python -m mpisph`` on one rank, started in ``cwd``."""
    env = dict(MPI_ENV, **os.environ)
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    return subprocess.run([sys.executable, "-m", "mpisph", *map(str, args)], capture_output=True, text=True,
                          timeout=300, cwd=cwd, env=env)


def times(directory):
    return [read_frame(f)["t"] for f in list_frames(directory)]


@pytest.fixture
def stopped(tmp_path):
    """A run to t = 0.02 s in tmp_path/run, frames every 0.01 s."""
    r = mpisph(*RUN, "--t-end", "0.02", "--out", "run", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert times(tmp_path / "run") == pytest.approx([0.0, 0.01, 0.02])
    return tmp_path / "run"


def test_a_restart_from_the_last_frame_continues_its_run(stopped, tmp_path):
    r = mpisph(*RUN, "--restart", "run/frame_00002.hdf", "--t-end", "0.04", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert times(stopped) == pytest.approx([0.0, 0.01, 0.02, 0.03, 0.04])
    t = read_diagnostics(stopped / "diagnostics.csv")["t"]
    assert t[0] == 0.0 and t[-1] == pytest.approx(0.04) and np.all(np.diff(t) > 0)
    link = tmp_path / "latest.hdf"
    link.symlink_to(stopped / "frame_00004.hdf")
    r = mpisph(*RUN, "--restart", link.name, "--t-end", "0.05", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert times(stopped)[-1] == pytest.approx(0.05) and not list_frames(tmp_path)


def test_a_restart_that_would_replace_later_frames_needs_out(stopped, tmp_path):
    before = {f: os.path.getmtime(f) for f in list_frames(stopped)}
    r = mpisph(*RUN, "--restart", "run/frame_00001.hdf", "--t-end", "0.04", cwd=tmp_path)
    lines = stderr_lines(r.stderr)
    assert r.returncode == 2 and len(lines) == 1, r.stderr
    assert lines[0].startswith("mpisph: error: ") and "holds 1 frame(s) after t = 0.01 s" in lines[0]
    assert {f: os.path.getmtime(f) for f in list_frames(stopped)} == before
    r = mpisph(*RUN, "--restart", "run/frame_00001.hdf", "--t-end", "0.03", "--out", "run", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert times(stopped) == pytest.approx([0.0, 0.01, 0.02, 0.03])


def test_a_restart_that_would_renumber_the_frames_it_keeps_is_refused(stopped, tmp_path):
    """Frames are numbered by t / output_interval: a restart from t = 0.02 s with frames every 0.02 s
    would write t = 0.04 s as frame_00002.hdf, over the frame it starts from; with every 0.005 s its
    frames are numbered from 5 on and keep the earlier ones."""
    args = [a for a in RUN if a not in ("--output-interval", "0.01")]
    before = {f: os.path.getmtime(f) for f in list_frames(stopped)}
    r = mpisph(*args, "--restart", "run/frame_00002.hdf", "--t-end", "0.06", "--output-interval", "0.02",
               cwd=tmp_path)
    lines = stderr_lines(r.stderr)
    assert r.returncode == 2 and len(lines) == 1, r.stderr
    assert "would write over frame_00002.hdf (t = 0.02 s)" in lines[0], lines[0]
    assert {f: os.path.getmtime(f) for f in list_frames(stopped)} == before
    r = mpisph(*args, "--restart", "run/frame_00002.hdf", "--t-end", "0.03", "--output-interval", "0.005",
               cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert times(stopped) == pytest.approx([0.0, 0.01, 0.02, 0.025, 0.03])
    assert [os.path.basename(f) for f in list_frames(stopped)][-2:] == ["frame_00005.hdf", "frame_00006.hdf"]


def test_a_run_that_replaces_another_cases_frames_says_so(stopped, tmp_path):
    """A new run into a directory of another case's run replaces its frames, as documented, with a
    warning that names them; the same case run again there replaces its own without one."""
    r = mpisph("taylor_green", "--set", "nx=10", "--t-end", "0.01", "--output-interval", "0.01", "--quiet",
               "--out", "run", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert stderr_lines(r.stderr) == [f"mpisph: warning: run held frames (3 of case dam_break_2d), which this run "
                                      "of taylor_green replaces"]
    assert times(stopped) == pytest.approx([0.0, 0.01])
    r = mpisph("taylor_green", "--set", "nx=10", "--t-end", "0.01", "--output-interval", "0.01", "--quiet",
               "--out", "run", cwd=tmp_path)
    assert r.returncode == 0 and stderr_lines(r.stderr) == [], r.stderr


def test_a_case_file_runs_into_runs_and_its_name(tmp_path):
    """A case given by its path, absolute or not, writes to runs/NAME (NAME its file's name without
    .py) unless --out says otherwise, as a shipped case writes to runs/CASE."""
    own = tmp_path / "cases" / "my_vortex.py"
    own.parent.mkdir()
    own.write_text((ROOT / "cases" / "taylor_green.py").read_text())
    for given in (own, own.relative_to(tmp_path)):
        r = mpisph(given, "--set", "nx=10", "--t-end", "0.01", "--output-interval", "0.01", "--quiet", cwd=tmp_path)
        assert r.returncode == 0, r.stderr
        assert times(tmp_path / "runs" / "my_vortex") == pytest.approx([0.0, 0.01])


def test_a_restart_records_diagnostics_rows_at_the_steps_of_the_run_it_continues(tmp_path):
    """diagnostics.csv's rows fall every diagnostics_every advection steps counted from t = 0, which
    the frame carries to the restart: restarted from the frame at 0.1 s (its 39th advection step, not
    a multiple of 10), the run writes the rows of the run never stopped, where a count from the
    restart put them 39 steps apart from those."""
    run = ["dam_break_2d", "--set", "dp=0.05", "--t-end", "0.3", "--output-interval", "0.1", "--quiet"]
    r = mpisph(*run, "--out", "straight", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    restarted = tmp_path / "restarted"
    restarted.mkdir()
    for name in ("frame_00000.hdf", "frame_00001.hdf", "diagnostics.csv"):
        (restarted / name).write_bytes((tmp_path / "straight" / name).read_bytes())
    configurations = read_frame(restarted / "frame_00001.hdf")["configurations"]
    assert configurations % 10 != 0  # the case's diagnostics_every
    r = mpisph(*run, "--restart", restarted / "frame_00001.hdf", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    rows, straight = (read_diagnostics(d / "diagnostics.csv") for d in (restarted, tmp_path / "straight"))
    assert np.sum(rows["t"] > 0.1 + 1e-9) >= 5
    np.testing.assert_array_equal(rows["step"], straight["step"])
    np.testing.assert_array_equal(rows["t"], straight["t"])
