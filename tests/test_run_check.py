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
              "kind": np.zeros(n, np.int8), "v": np.zeros((n, 2)), "rho": np.ones(n), "mass": np.ones(n),
              "p": np.zeros(n)}
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


@pytest.mark.parametrize("script, args, message", [
    ("cut_stability.py", ["RUN"], "is a run of 'dam_break_2d', which has no cohesion, phi, psi: this script reads soil"),
    ("remedy_panels.py", ["OUT.png", "water=RUN"], "its frames have no field 'plastic_strain' (--field)"),
    ("remedy_panels.py", ["OUT.png", "RUN"], "give each run as TITLE=RUN_DIR"),
    ("stress_budget.py", ["dam_break_2d"], "dam_break_2d runs riemann_fluid in 2D: this script watches riemann_granular"),
])
def test_the_analysis_scripts_stop_in_one_line_on_a_run_they_do_not_read(tmp_path, script, args, message):
    """Scripts that crashed on a fluid run (a KeyError deep inside, or a budget with nothing in it)."""
    import subprocess
    import sys
    from pathlib import Path
    run = a_run(tmp_path / "run", {"case": "dam_break_2d", "rho0": 1000.0, "g": 9.8})
    scripts = Path(__file__).resolve().parent.parent / "scripts"
    words = [str(run) if a == "RUN" else str(tmp_path / a) if a == "OUT.png" else a.replace("RUN", str(run))
             for a in args]
    r = subprocess.run([sys.executable, str(scripts / script), *words], capture_output=True, text=True, timeout=120,
                       cwd=scripts)
    err = r.stderr.strip().splitlines()
    assert r.returncode == 2 and "Traceback" not in r.stderr and message in err[-1], r.stderr
    assert not (tmp_path / "OUT.png").exists()


def test_at_rest_takes_the_bulk_density_at_rest_of_mu_i_grains(tmp_path):
    """A mu(I) run has no rho0: at_rest.py measures its densities against phi_max rho_s0, where it
    refused such runs; a run with neither is refused in one line."""
    import subprocess
    import sys
    from pathlib import Path
    scripts = Path(__file__).resolve().parent.parent / "scripts"
    grains = a_run(tmp_path / "grains", {"case": "inclined_plane", "rho_s0": 800.0, "phi_max": 0.6, "dp": 1.0})
    r = subprocess.run([sys.executable, str(scripts / "at_rest.py"), str(grains)], capture_output=True, text=True,
                       timeout=120, cwd=scripts)
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines()[0] == "peak speed 0 m/s; rho0 480 kg/m^3"
    neither = a_run(tmp_path / "neither", {"case": "x"})
    r = subprocess.run([sys.executable, str(scripts / "at_rest.py"), str(neither)], capture_output=True, text=True,
                       timeout=120, cwd=scripts)
    assert r.returncode == 2 and "which has neither rho0 nor rho_s0 and phi_max" in r.stderr.splitlines()[-1]


def test_cut_stability_refuses_a_body_that_is_not_a_block(tmp_path):
    """A soil run whose body's top is not level over its width (a slope; here four particles on a
    diagonal) has no vertical cut's critical height to be judged against: one line, no table (a
    slope on its foundation read 'stands' at H / H_c = 1.64, H counted from the foundation's base)."""
    import subprocess
    import sys
    from pathlib import Path
    scripts = Path(__file__).resolve().parent.parent / "scripts"
    run = a_run(tmp_path / "run", {"case": "slope", "dp": 1.0, "cohesion": 8e3, "phi": 22.0, "psi": 0.0,
                                   "rho0": 1900.0, "g": 9.81})
    r = subprocess.run([sys.executable, str(scripts / "cut_stability.py"), str(run)], capture_output=True, text=True,
                       timeout=120, cwd=scripts)
    assert r.returncode == 2 and "Traceback" not in r.stderr and r.stdout == "", r.stderr
    assert "its body's top is level over 25% of its width: not a vertical cut" in r.stderr.strip().splitlines()[-1]
