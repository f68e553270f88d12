"""Solid cases against their references (000_ Secs. 4.3 and 5.1; issue 3's tolerances).

The column collapse runs at dp = 0.005 m (800 particles) to stay short; the
validation script runs the paper's resolutions. Runs are bitwise identical on
any rank count (test_rank_agreement.py).
"""

import numpy as np
import pytest

from mpisph import measure, references
from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import list_frames, read_frame
from mpirun import mpisph


def run(case, args, out, ranks=2, timeout=900):
    r = mpisph([case, *args, "--out", out, "--quiet"], ranks=ranks, timeout=timeout)
    assert r.returncode == 0, r.stderr
    return [read_frame(f) for f in list_frames(out)], read_diagnostics(out / "diagnostics.csv")


def test_column_collapse_deposit(tmp_path):
    """L = 0.2, H = 0.1: runout in [0.30, 0.40] m, undisturbed top, at rest, energy ratio 0.69 +- 0.05."""
    dp = 0.005
    frames, diag = run("column_collapse_2d", ["--set", f"dp={dp}"], tmp_path)
    last = frames[-1]
    assert last["t"] == pytest.approx(1.0)
    assert 0.30 <= measure.runout(last, dp) <= 0.40
    assert measure.deposit_height(last, dp, x_max=0.05) == pytest.approx(0.1, rel=0.05)
    speeds = [np.linalg.norm(f["v"], axis=1).max() for f in frames]
    assert speeds[-1] < 0.01 * max(speeds)
    energy = diag["kinetic_energy"] + diag["potential_energy"]
    assert energy[-1] / energy[0] == pytest.approx(0.69, abs=0.05)
    assert np.all(last["plastic_strain"] >= 0.0)


@pytest.mark.xfail(strict=True, reason="open gap: with the corrected velocity gradient (000_ Eq. 23-24) the "
                   "beam gains energy (about +7 % at H/dp = 10 in the first quarter period) and the first period "
                   "is 0.284 s, +12 % on 0.254 s; see the issue-3 note")
def test_beam_first_period_within_8_percent(tmp_path):
    frames, diag = run("oscillating_beam", ["--set", "H_over_dp=10", "--set", "v_f=0.01", "--t-end", "0.32",
                                            "--output-interval", "0.08"], tmp_path, ranks=2)
    period = measure.first_period(diag["t"], diag["tip_uy"])
    assert period == pytest.approx(references.beam_period(), rel=0.08)
