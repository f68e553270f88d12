"""scripts/validate.py --reuse: a finished run is read again only for the same command, rank count
and committed solver code (mpisph/ and cases/), so a long validation can be resumed without
mixing in runs of other code."""

import importlib.util
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
BEAM = ["--set", "H_over_dp=5", "--t-end", "0.002", "--output-interval", "0.001"]


@pytest.fixture
def validate(tmp_path, monkeypatch):
    spec = importlib.util.spec_from_file_location("validate", ROOT / "scripts" / "validate.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    monkeypatch.setattr(module, "RUNS", tmp_path)
    return module


def test_code_version_is_the_committed_trees_or_none(validate):
    dirty = subprocess.run(["git", "status", "--porcelain", "--", "mpisph", "cases"], capture_output=True,
                           text=True, cwd=ROOT, check=True).stdout.strip()
    trees = subprocess.run(["git", "rev-parse", "HEAD:mpisph", "HEAD:cases"], capture_output=True, text=True,
                           cwd=ROOT, check=True).stdout.split()
    assert validate.code_version() == (None if dirty else trees)


def test_reuse_reads_only_the_same_command(validate, tmp_path, capsys):
    if validate.code_version() is None:
        pytest.skip("mpisph/ or cases/ has uncommitted changes: runs are not stamped")
    frames, _, _ = validate.run("beam", "oscillating_beam", BEAM, 1)
    first = (tmp_path / "beam" / "frame_00000.vtkhdf").stat().st_mtime_ns
    validate.REUSE = True
    again, _, _ = validate.run("beam", "oscillating_beam", BEAM, 1)
    assert "reusing" in capsys.readouterr().out
    assert (tmp_path / "beam" / "frame_00000.vtkhdf").stat().st_mtime_ns == first
    assert [f["t"] for f in again] == [f["t"] for f in frames]
    other = [*BEAM[:-1], "0.002"]  # another output interval: another command, run again
    validate.run("beam", "oscillating_beam", other, 1)
    assert "reusing" not in capsys.readouterr().out
    assert (tmp_path / "beam" / "frame_00000.vtkhdf").stat().st_mtime_ns != first
