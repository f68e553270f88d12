"""The run parameter max_time_step bounds the time step (a paper's fixed step below the CFL limit)."""

import numpy as np

from mpisph.io.diagnostics import read_diagnostics
from mpirun import mpisph


def test_max_time_step_bounds_every_step(tmp_path):
    """The soil cylinder at dp = 2 mm: its CFL step is about 2.6e-5 s; with max_time_step = 1e-6 s
    (002_ Table 2) every step is 1e-6 s, so 1e-4 s takes 100 steps."""
    args = ["soil_cylinder_impact", "--set", "dp=0.002", "max_time_step=1e-6", "diagnostics_every=1",
            "--t-end", "1e-4", "--output-interval", "1e-4", "--out", tmp_path, "--quiet"]
    r = mpisph(args, ranks=1, timeout=300)
    assert r.returncode == 0, r.stderr
    d = read_diagnostics(tmp_path / "diagnostics.csv")
    assert np.all(d["dt"][1:] <= 1e-6 * (1 + 1e-12))
    assert abs(d["t"][-1] - 1e-4) < 1e-15
    # 100 steps of 1e-6 s; their rounded sum may fall short of the frame time by a sliver, which
    # the solver then steps too
    assert np.count_nonzero(d["dt"][1:] > 1e-9) == 100
