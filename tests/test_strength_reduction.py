"""scripts/strength_reduction.py: the reduced strength of each stage and the stage table read from a
run's frames and diagnostics, on a run built by hand."""

import math

import numpy as np
import pytest
from mpi4py import MPI

from mpisph.io.frames import frame_path, write_frame
from repo_script import load_script

strength_reduction = load_script("strength_reduction")
DP = 0.1


def test_the_factor_divides_the_cohesion_and_the_tangents_of_the_angles():
    c, phi, psi = strength_reduction.reduced({"cohesion": 5e3, "phi": 20.0, "psi": 10.0}, 1.25)
    assert c == pytest.approx(4e3, rel=1e-12)
    assert math.tan(math.radians(phi)) == pytest.approx(math.tan(math.radians(20.0)) / 1.25, rel=1e-12)
    assert math.tan(math.radians(psi)) == pytest.approx(math.tan(math.radians(10.0)) / 1.25, rel=1e-12)


def test_after_the_first_stage_settles_a_stage_that_moves_the_body_beyond_the_slide_share_slid(tmp_path):
    """A 10-layer block (H = 1 m) that moves its particles by 0.01 m in its first stage (the release),
    not at all in the second and by 0.03 m (0.03 H, beyond SLIDE) in the third; kinetic energy peaking
    0.25 s into each stage."""
    i, j = np.meshgrid(np.arange(10), np.arange(10), indexing="ij")
    x = (np.c_[i.ravel(), j.ravel()] + 0.5) * DP
    n = len(x)
    for index, (t, shift) in enumerate(((0.0, 0.0), (1.0, 0.01), (2.0, 0.01), (3.0, 0.04))):
        fields = {"x": x + [shift, 0.0], "gid": np.arange(n, dtype=np.int64), "kind": np.zeros(n, np.int8),
                  "v": np.zeros((n, 2)), "rho": np.ones(n), "mass": np.ones(n)}
        write_frame(frame_path(str(tmp_path), index), MPI.COMM_SELF, fields, time=t, step=index, dim=2,
                    params={"case": "block", "dp": DP})
    t = np.arange(0.0, 3.01, 0.25)
    energy = np.where(np.isclose(t % 1.0, 0.25), 5.0, 1.0)
    (tmp_path / "diagnostics.csv").write_text("t,step,kinetic_energy\n" + "".join(
        f"{float(a)!r},{k},{float(e)!r}\n" for k, (a, e) in enumerate(zip(t, energy))))
    soil = {"cohesion": 5e3, "phi": 20.0, "psi": 0.0}
    height, rows = strength_reduction.stage_rows(str(tmp_path), soil, [(0.9, 0.0, 1.0), (1.0, 1.0, 2.0),
                                                                       (1.1, 2.0, 3.0)])
    assert height == pytest.approx(1.0, rel=1e-12)
    release, stood, slid = ([cell.strip() for cell in row.strip("|").split("|")] for row in rows)
    assert release[7] == "settling" and float(release[5]) == pytest.approx(0.01, abs=1e-4)
    assert stood[0] == "1" and stood[3] == "5 at +0.25" and float(stood[5]) == 0.0 and stood[7] == "stood"
    assert slid[1] == f"{5 / 1.1:.3f}" and float(slid[5]) == pytest.approx(0.03, abs=1e-4)
    assert float(slid[6]) == pytest.approx(0.04, abs=1e-4) and slid[7] == "slid"


def test_the_stages_follow_each_other_the_first_settle_seconds_long():
    assert strength_reduction.stage_times([0.6, 0.7, 0.8], 2.0, 1.0) == [(0.6, 0.0, 2.0), (0.7, 2.0, 3.0),
                                                                         (0.8, 3.0, 4.0)]


def test_each_stage_restarts_the_last_frame_with_its_reduced_strength(tmp_path):
    """A coarse cut in two short stages: the second stage's frames carry c / F and atan(tan phi / F)
    of the case's own strength, and the table has a row per stage."""
    from mpisph.io.frames import list_frames, read_frame

    sets = ["dp=0.2", "kernel=wendland_c2", "h_factor=1.3"]
    soil = {"cohesion": 5e3, "phi": 20.0, "psi": 0.0}
    stages = strength_reduction.stage_times([1.0, 1.25], 0.02, 0.02)
    strength_reduction.run_stages("vertical_cut", sets, soil, stages, 0.02, 1, str(tmp_path))
    last = read_frame(list_frames(str(tmp_path))[-1])
    assert last["t"] == pytest.approx(0.04, rel=1e-9)
    c, phi, psi = strength_reduction.reduced(soil, 1.25)
    assert (last["params"]["cohesion"], last["params"]["phi"], last["params"]["psi"]) == (c, phi, psi)
    assert float(last["params"]["dp"]) == 0.2
    _, rows = strength_reduction.stage_rows(str(tmp_path), soil, stages)
    assert len(rows) == 2 and rows[0].endswith("| settling |")
