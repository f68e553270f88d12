"""scripts/run_check.py: an analysis script given a directory without frames, or a run of a case
whose parameters lack what it reads, stops with one usage line naming the case and what it reads."""

import argparse

import numpy as np
import pytest
from mpi4py import MPI

from mpisph.io.frames import frame_path, write_frame
from repo_script import load_script


def a_run(directory, params):
    directory.mkdir()
    n = 4
    fields = {"x": np.arange(2 * n, dtype=float).reshape(n, 2), "gid": np.arange(n, dtype=np.int64),
              "kind": np.zeros(n, np.int8), "v": np.zeros((n, 2)), "rho": np.ones(n), "mass": np.ones(n)}
    write_frame(frame_path(str(directory), 0), MPI.COMM_SELF, fields, time=0.0, step=0, dim=2, params=params)
    return directory


def test_a_run_with_what_the_script_reads_passes_and_others_stop_in_one_line(tmp_path, capsys):
    run_params = load_script("run_check").run_params
    ap = argparse.ArgumentParser(prog="a_script.py")
    run = a_run(tmp_path / "run", {"case": "column_collapse_2d", "rho0": 2040.0})
    assert run_params(ap, str(run), ("rho0",), "soils")["rho0"] == 2040.0
    for directory, needs, message in ((run, ("theta", "I_0"), "is a run of 'column_collapse_2d', which has no theta, "
                                                              "I_0: this script reads inclined planes"),
                                      (tmp_path, ("rho0",), "no complete frames")):
        with pytest.raises(SystemExit) as stop:
            run_params(ap, str(directory), needs, "inclined planes")
        err = capsys.readouterr().err.strip().splitlines()
        assert stop.value.code == 2 and message in err[-1] and err[-1].startswith("a_script.py: error: ")
