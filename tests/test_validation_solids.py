"""Soils against their references (000_ Secs. 4.3 and 5.2; issue 3's tolerances); the beam is in
test_validation_beam.py.

The column collapse runs at dp = 0.005 m (800 particles) and the cohesive cut at dp = L/50 to stay
short; the validation script runs the paper's resolutions. Runs are bitwise identical on any rank
count (test_rank_agreement.py), so they run on one rank (tests/conftest.py says why).
"""

import numpy as np
import pytest

from mpisph import measure
from mpisph.io.frames import list_frames, read_frame
from mpisph.instability import tensile_instability
from mpisph.particles import MOVING
from mpirun import run


def test_column_collapse_deposit(tmp_path):
    """L = 0.2, H = 0.1: runout in [0.30, 0.40] m, undisturbed top, energy ratio 0.69 +- 0.05, and a
    deposit that is at rest once the UTVF shift stops (see below)."""
    dp = 0.005
    frames, diag = run("column_collapse_2d", ["--set", f"dp={dp}"], tmp_path / "collapse")
    last = frames[-1]
    assert last["t"] == pytest.approx(1.0)
    assert 0.30 <= measure.runout(last, dp) <= 0.40
    assert measure.deposit_height(last, dp, x_max=0.05) == pytest.approx(0.1, rel=0.05)
    energy = diag["kinetic_energy"] + diag["potential_energy"]
    assert energy[-1] / energy[0] == pytest.approx(0.69, abs=0.05)
    assert np.all(last["plastic_strain"] >= 0.0)
    # At this coarse spacing the thin toe still creeps under UTVF at 1.5-3 % of the peak speed at
    # t = 1 s, driven by the tangential shift of the toe's surface particles; at the paper's
    # dp = 0.002 the deposit is at rest (0.35 %, docs/VALIDATION.md). The granular mechanics itself
    # has come to rest here too: continued for 0.15 s without the stabiliser, every particle is
    # below 1 % of the peak speed.
    peak = max(measure.max_speed(f) for f in frames)
    settled, _ = run("column_collapse_2d", ["--restart", list_frames(tmp_path / "collapse")[-1],
                                            "--set", "stabiliser=none", "--t-end", "1.15"], tmp_path / "settled")
    assert measure.max_speed(settled[-1]) < 0.01 * peak


def test_cohesive_cut_fails_without_tensile_instability_only_with_utvf(tmp_path):
    """Sec. 5.2 at dp = L/50 (the validation script runs L/100): UTVF gives the crest crack
    1.0-1.7 m behind the face with no clustering or voids at 2 s; without correction clustering is
    at least ten times the UTVF figure (counted as at least one particle); TVF still clusters."""
    dp = 0.08
    m = {}
    for st in ("utvf", "none", "tvf"):
        frames, _ = run("cohesive_failure_2d", ["--set", f"dp={dp}", "--set", f"stabiliser={st}"], tmp_path / st)
        assert frames[-1]["t"] == pytest.approx(2.0)
        m[st] = tensile_instability(read_frame(list_frames(tmp_path / st)[-1], walls=True))
        if st == "utvf":
            assert 1.0 <= measure.crest_crack(frames[0], frames[-1], dp, 4.0, 0.05 * 2.0) <= 1.7
    assert m["utvf"]["clustering"] <= 0.001 and m["utvf"]["inner_voids"] == 0.0 and m["utvf"]["fragments"] == 1
    assert m["none"]["clustering"] >= 10 * max(m["utvf"]["clustering"], 1 / m["utvf"]["n"])
    assert m["tvf"]["clustering"] > m["utvf"]["clustering"] and m["tvf"]["min_spacing"] < 0.5


def test_soil_at_rest_keeps_its_density_by_kernel_summation(tmp_path):
    """A cut that stands (c = 50 kPa) for 1.5 s: with density_reinit=free_surface every grain's
    density stays within 6 % of rho0. Evolved by Eq. 16 alone it drifts without bound where the
    grains jostle (1.5 rho0 at 1 s, 3.8 rho0 at 3 s here; docs/FLUME.md), since a soil's pressure
    comes from its stress and nothing pulls the density back."""
    frames, _ = run("vertical_cut", ["--set", "dp=0.1", "cohesion=50000", "density_reinit=free_surface",
                                     "--t-end", "1.5", "--output-interval", "0.5"], tmp_path / "cut")
    assert len(frames) == 4
    for f in frames:
        rho = f["rho"][f["kind"] == MOVING] / 1850.0
        assert rho.min() > 0.94 and rho.max() < 1.06, (f["t"], rho.min(), rho.max())
