"""Solid cases against their references (000_ Secs. 4.3 and 5.1; issue 3's tolerances).

The column collapse runs at dp = 0.005 m (800 particles), the beam at
H/dp = 10 and the cohesive cut at dp = L/50 to stay short; the validation
script runs the paper's resolutions. Runs are bitwise identical on any rank
count (test_rank_agreement.py).
"""

import numpy as np
import pytest

from mpisph import measure, references
from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import list_frames, read_frame
from mpisph.instability import tensile_instability
from mpisph.particles import MOVING
from mpirun import mpisph


def run(case, args, out, ranks=2, timeout=900):
    r = mpisph([case, *args, "--out", out, "--quiet"], ranks=ranks, timeout=timeout)
    assert r.returncode == 0, r.stderr
    return [read_frame(f) for f in list_frames(out)], read_diagnostics(out / "diagnostics.csv")


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
    peak = max(np.linalg.norm(f["v"], axis=1).max() for f in frames)
    settled, _ = run("column_collapse_2d", ["--restart", list_frames(tmp_path / "collapse")[-1],
                                            "--set", "stabiliser=none", "--t-end", "1.15"], tmp_path / "settled")
    assert np.linalg.norm(settled[-1]["v"], axis=1).max() < 0.01 * peak


def test_period_ends_are_the_upward_crossings_after_the_start():
    """An oscillation that starts at zero moving up ends its periods at T, 2T, ... (to the
    interpolation error of the samples); a run shorter than T has no first period."""
    T = 0.254
    t = np.linspace(0.0, 2.6 * T, 400)
    y = np.sin(2 * np.pi * t / T)
    assert measure.period_ends(t, y) == pytest.approx([T, 2 * T], abs=1e-4)
    assert measure.first_period(t, y) == pytest.approx(T, abs=1e-4)
    assert np.isnan(measure.first_period(t[t < 0.9 * T], y[t < 0.9 * T]))


@pytest.mark.parametrize("v_f", [0.01, 0.05])
def test_beam_first_period_and_energy(tmp_path, v_f):
    """UTVF beam at H/dp = 10 (H/dp = 20 and 30 in scripts/validate.py): first period within 8 % of
    0.2541 s, kinetic + strain energy kept within 2 % over the period, no clustering or voids."""
    _, diag = run("oscillating_beam", ["--set", "H_over_dp=10", "--set", f"v_f={v_f}",
                                       "--t-end", "0.3", "--output-interval", "0.1"], tmp_path)
    period = measure.first_period(diag["t"], diag["tip_uy"])
    assert period == pytest.approx(references.beam_period(), rel=0.08)
    energy = diag["kinetic_energy"] + diag["strain_energy"]
    assert np.all(np.abs(energy / energy[0] - 1.0) < 0.02)
    m = tensile_instability(read_frame(list_frames(tmp_path)[-1], walls=True))
    assert m["clustering"] == 0.0 and m["inner_voids"] == 0.0 and m["fragments"] == 1
    assert m["min_spacing"] > 0.75  # without correction pairs close in to 0.55 dp by t = 0.04 s


def test_the_uncorrected_beam_breaks_where_clustering_sees_nothing(tmp_path):
    """Without a stabiliser the H/dp = 10 beam (v_f = 0.05) breaks off at its clamp by t = 0.6 s: two
    fragments, the stub at the clamp more than a tenth of the particles, while no pair has come
    nearer than 0.5 dp (pairs close in to 0.55 dp) and clustering reads 0 (issue 13's item 10)."""
    run("oscillating_beam", ["--set", "H_over_dp=10", "v_f=0.05", "stabiliser=none", "--t-end", "0.6",
                             "--output-interval", "0.3"], tmp_path)
    m = tensile_instability(read_frame(list_frames(tmp_path)[-1], walls=True))
    assert m["clustering"] == 0.0 and m["min_spacing"] > 0.5
    assert m["fragments"] == 2 and m["detached"] > 0.1


def test_beam_with_eq_22_as_printed_gains_energy(tmp_path):
    """H/dp = 5 to a quarter period: with 000_ Eq. 22 as printed (no B on the shear part) kinetic +
    strain energy rises by more than 5 % (physics/solid.py says why); the corrected form, the
    default, keeps it within 2 % (test_beam_first_period_and_energy)."""
    _, diag = run("oscillating_beam", ["--set", "H_over_dp=5", "shear_force=as_printed", "diagnostics_every=1",
                                       "--t-end", "0.064", "--output-interval", "0.064"], tmp_path, ranks=1)
    energy = diag["kinetic_energy"] + diag["strain_energy"]
    assert energy.max() / energy[0] - 1.0 > 0.05


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
                                     "--t-end", "1.5", "--output-interval", "0.5"], tmp_path / "cut", ranks=1)
    assert len(frames) == 4
    for f in frames:
        rho = f["rho"][f["kind"] == MOVING] / 1850.0
        assert rho.min() > 0.94 and rho.max() < 1.06, (f["t"], rho.min(), rho.max())
