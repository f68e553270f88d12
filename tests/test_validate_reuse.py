"""scripts/validate.py --reuse (scripts/validation/runs.py): a finished run is read again only for
the same command, rank count and committed solver code (mpisph/ and cases/), so a long validation
can be resumed without mixing in runs of other code."""

import subprocess
from pathlib import Path

import pytest

from repo_script import BEAM, fix_code_version, load_package

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture
def runs(tmp_path, monkeypatch):
    """validate.py's runs module, writing its runs under ``tmp_path``, --reuse off."""
    runs = load_package("validation.runs")
    monkeypatch.setattr(runs, "RUNS", tmp_path)
    monkeypatch.setattr(runs, "REUSE", False)
    return runs


@pytest.fixture
def stamped(runs, monkeypatch):
    """``runs`` with a fixed code version (repo_script.fix_code_version)."""
    fix_code_version(monkeypatch)
    return runs


def test_code_version_follows_the_committed_solver_code(runs, tmp_path, monkeypatch):
    """A tree of its own: the version is None while mpisph/ or cases/ has uncommitted changes, and
    a commit there gives a new one; a change elsewhere leaves it."""
    repo = tmp_path / "repo"
    for part in ("mpisph", "cases", "docs"):
        (repo / part).mkdir(parents=True)
        (repo / part / "a.py").write_text("x = 1\n")

    def commit():
        for words in (["add", "-A"], ["-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "c"]):
            subprocess.run(["git", *words], cwd=repo, check=True, capture_output=True)

    subprocess.run(["git", "init", "-q"], cwd=repo, check=True)
    commit()
    monkeypatch.setattr(runs, "ROOT", repo)
    first = runs.code_version()
    assert first is not None and len(first) == 2
    (repo / "docs" / "a.py").write_text("x = 2\n")
    commit()
    assert runs.code_version() == first
    (repo / "cases" / "a.py").write_text("x = 2\n")
    assert runs.code_version() is None
    commit()
    second = runs.code_version()
    assert second is not None and second != first and second[0] == first[0]


def test_reuse_reads_only_the_same_command(stamped, tmp_path, capsys):
    runs = stamped
    frames, _, _ = runs.run("beam", "oscillating_beam", BEAM, 1)
    first = (tmp_path / "beam" / "frame_00000.hdf").stat().st_mtime_ns
    runs.REUSE = True
    again, _, _ = runs.run("beam", "oscillating_beam", BEAM, 1)
    assert "reusing" in capsys.readouterr().out
    assert (tmp_path / "beam" / "frame_00000.hdf").stat().st_mtime_ns == first
    assert [f["t"] for f in again] == [f["t"] for f in frames]
    other = [*BEAM[:-1], "0.002"]  # another output interval: another command, run again
    runs.run("beam", "oscillating_beam", other, 1)
    assert "reusing" not in capsys.readouterr().out
    assert (tmp_path / "beam" / "frame_00000.hdf").stat().st_mtime_ns != first


def test_reuse_continues_an_interrupted_run_to_the_same_bits(stamped, tmp_path, capsys):
    """A run whose partial stamp matches (interrupted: no final stamp, its last frames missing)
    continues from its last frame and ends with the frames of the uninterrupted run, bit for bit."""
    import json

    import numpy as np

    from mpisph.io.frames import list_frames

    runs = stamped
    frames, _, _ = runs.run("beam", "oscillating_beam", BEAM, 1)
    out = tmp_path / "beam"
    stamp = json.loads((out / runs.STAMP).read_text())
    del stamp["returncode"]
    (out / runs.STAMP).unlink()
    (out / runs.PARTIAL_STAMP).write_text(json.dumps(stamp))
    Path(list_frames(out)[-1]).unlink()  # the run stopped before its last frame
    assert len(list_frames(out)) == len(frames) - 1
    runs.REUSE = True
    again, _, _ = runs.run("beam", "oscillating_beam", BEAM, 1)
    assert "continuing" in capsys.readouterr().out
    assert (out / runs.STAMP).exists() and not (out / runs.PARTIAL_STAMP).exists()
    assert [f["t"] for f in again] == [f["t"] for f in frames]
    for name in ("x", "v", "rho", "p"):
        np.testing.assert_array_equal(again[-1][name], frames[-1][name])
