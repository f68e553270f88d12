"""scripts/cut_stability.py: the displacement share and the kinetic-energy peak it reports."""

import numpy as np

from repo_script import load_script

cut_stability = load_script("cut_stability")


def test_the_displacement_share_is_the_99th_percentile_over_the_height():
    x = np.stack([np.arange(1000.0), np.zeros(1000)], axis=1)
    moved = x.copy()
    moved[:, 1] = np.linspace(0.0, 0.999, 1000)  # particle k moves k mm
    share = cut_stability.displacement_share({"x": x}, {"x": moved}, 2.0)
    assert share == np.percentile(np.linspace(0.0, 0.999, 1000), 99.0) / 2.0
    assert abs(share - 0.989 / 2.0) < 1e-3


def test_the_kinetic_energy_peak_and_its_time_from_the_diagnostics(tmp_path):
    (tmp_path / "diagnostics.csv").write_text("t,step,kinetic_energy\n0.0,0,0.0\n0.1,10,5.0\n0.5,50,7.5\n1.0,90,0.2\n")
    assert cut_stability.kinetic_energy_peak(str(tmp_path)) == (7.5, 0.5)
