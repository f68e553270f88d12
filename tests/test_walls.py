"""Dummy-particle walls hold still water: hydrostatic pressure, water at rest.

A sanity check of walls, gravity and the free-surface density
reinitialisation, with coarse bounds: the speeds are WCSPH's acoustic noise
(c0 = 10 sqrt(2 g H)), which measured 4 % of sqrt(2 g H) at most and 1 % in
the median when this test was written.
"""

import numpy as np

from mpisph.io.frames import list_frames, read_frame
from mpirun import mpisph


def test_still_water_stays_hydrostatic(tmp_path):
    r = mpisph(["hydrostatic_tank", "--t-end", "2", "--out", tmp_path, "--quiet"])
    assert r.returncode == 0, r.stderr
    last = read_frame(list_frames(tmp_path)[-1])
    rho, g, depth = 1000.0, 9.81, 0.5
    scale = np.sqrt(2 * g * depth)
    speed = np.linalg.norm(last["v"], axis=1)
    assert speed.max() < 0.1 * scale
    assert np.median(speed) < 0.02 * scale
    bottom = last["x"][:, 1] < 0.02
    hydrostatic = rho * g * (depth - last["x"][bottom, 1])
    assert abs(last["p"][bottom].mean() / hydrostatic.mean() - 1) < 0.05
    assert abs(last["x"][:, 1].max() - (depth - 0.01)) < 0.02  # the surface stays within a spacing
