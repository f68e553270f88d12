"""scripts/production.py --reuse: a 3D run of hours is measured again only when the same command,
rank count and committed solver code made it (the stamp of scripts/validation/runs.py); before,
any run.log in runs/production/ was read, whatever code had written it."""

import pytest

from repo_script import BEAM, fix_code_version, load_package, load_script


@pytest.fixture
def production(tmp_path, monkeypatch):
    """production.py writing its runs under ``tmp_path``, with a fixed code version."""
    production = load_script("production")
    monkeypatch.setattr(production, "RUNS", tmp_path)
    fix_code_version(monkeypatch)
    return production


def test_reuse_reads_only_a_run_of_the_same_stamp(production, tmp_path, capsys):
    log = tmp_path / "beam" / "run.log"
    first = production.run("oscillating_beam", BEAM, 1, True, name="beam")
    assert "reusing" not in capsys.readouterr().out
    written = log.stat().st_mtime_ns
    assert production.run("oscillating_beam", BEAM, 1, True, name="beam") == first
    assert "reusing" in capsys.readouterr().out and log.stat().st_mtime_ns == written
    production.run("oscillating_beam", [*BEAM[:-1], "0.002"], 1, True, name="beam")  # another command
    assert "reusing" not in capsys.readouterr().out and log.stat().st_mtime_ns != written


@pytest.mark.parametrize("other_code", [["another-tree-of-mpisph", "tree-of-cases"], None],
                         ids=["committed", "uncommitted"])
def test_a_run_of_other_code_is_run_again(production, tmp_path, monkeypatch, capsys, other_code):
    """A finished, stamped run read with other committed code, or with uncommitted changes (no
    version, no stamp), is run again."""
    log, stamp = tmp_path / "beam" / "run.log", tmp_path / "beam" / production.STAMP
    production.run("oscillating_beam", BEAM, 1, True, name="beam")
    written = log.stat().st_mtime_ns
    assert stamp.exists()
    monkeypatch.setattr(load_package("validation.runs"), "code_version", lambda: other_code)
    production.run("oscillating_beam", BEAM, 1, True, name="beam")
    assert "reusing" not in capsys.readouterr().out and log.stat().st_mtime_ns != written
    assert stamp.exists() == (other_code is not None)
