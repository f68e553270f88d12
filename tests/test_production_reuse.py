"""scripts/production.py --reuse: a 3D run of hours is measured again only when the same command,
rank count and committed solver code made it (the stamp of scripts/validation/runs.py); before,
any run.log in runs/production/ was read, whatever code had written it."""

import pytest

from repo_script import load_package, load_script

BEAM = ["--set", "H_over_dp=5", "--t-end", "0.002", "--output-interval", "0.001"]


@pytest.fixture
def production(tmp_path, monkeypatch):
    """production.py writing its runs under ``tmp_path``, with a fixed code version."""
    production = load_script("production")
    monkeypatch.setattr(production, "RUNS", tmp_path)
    monkeypatch.setattr(load_package("validation.runs"), "code_version", lambda: ["tree-of-mpisph", "tree-of-cases"])
    return production


def test_reuse_reads_only_a_run_of_the_same_stamp(production, tmp_path, monkeypatch, capsys):
    log = tmp_path / "beam" / "run.log"
    first = production.run("oscillating_beam", BEAM, 1, True, name="beam")
    assert "reusing" not in capsys.readouterr().out
    written = log.stat().st_mtime_ns
    assert production.run("oscillating_beam", BEAM, 1, True, name="beam") == first
    assert "reusing" in capsys.readouterr().out and log.stat().st_mtime_ns == written
    production.run("oscillating_beam", [*BEAM[:-1], "0.002"], 1, True, name="beam")  # another command
    assert "reusing" not in capsys.readouterr().out and log.stat().st_mtime_ns != written


def test_a_run_of_uncommitted_code_is_never_reused(production, tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(load_package("validation.runs"), "code_version", lambda: None)
    for _ in range(2):
        production.run("oscillating_beam", BEAM, 1, True, name="beam")
        assert "reusing" not in capsys.readouterr().out
    assert not (tmp_path / "beam" / production.STAMP).exists()
