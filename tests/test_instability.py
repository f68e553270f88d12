"""The tensile-instability measure sees clusters and inner voids, and nothing on a lattice."""

import numpy as np
import pytest

from mpisph.instability import tensile_instability
from mpisph.launch import mpirun_mpisph
from repo_script import load_script


def lattice_frame(n=30, dp=0.01, remove=None, squeeze=()):
    g = (np.arange(n) + 0.5) * dp
    x = np.stack([a.ravel() for a in np.meshgrid(g, g, indexing="ij")], axis=1)
    keep = np.ones(len(x), bool) if remove is None else ~remove(x)
    x = x[keep].copy()
    for i in squeeze:  # move particle i to 0.3 dp from its right-hand neighbour
        x[i, 0] = x[i + n, 0] - 0.3 * dp if i + n < len(x) else x[i, 0]
    m = len(x)
    return {"x": x, "kind": np.zeros(m, np.int8), "mass": np.full(m, 1000 * dp**2),
            "rho": np.full(m, 1000.0), "gid": np.arange(m), "params": {"h_factor": 1.3}}


def test_regular_lattice_is_clean():
    m = tensile_instability(lattice_frame())
    assert m["dp"] == pytest.approx(0.01)
    assert m["clustering"] == 0.0 and m["inner_voids"] == 0.0
    assert m["min_spacing"] == pytest.approx(1.0)
    # the outermost layer is free surface (the second one stays above 0.75 d on a lattice)
    assert m["surface"] == pytest.approx((900 - 784) / 900)


def test_hole_inside_is_a_void():
    hole = tensile_instability(lattice_frame(remove=lambda x: np.all(np.abs(x - 0.15) < 0.02, axis=1)))
    assert hole["n"] == 900 - 16
    # the 16 particles facing the 4 x 4 hole across an edge; the outer layer is still surface
    assert hole["inner_voids"] * hole["n"] == pytest.approx(16)
    assert hole["surface"] * hole["n"] == pytest.approx(116)


def test_close_pairs_are_clusters():
    m = tensile_instability(lattice_frame(squeeze=[100, 200, 300]))
    assert m["clustering"] * m["n"] == pytest.approx(6)  # three pairs
    assert m["min_spacing"] == pytest.approx(0.3)


def test_the_clustered_script_finds_the_same_pairs():
    clustered = load_script("clustered")
    frame = lattice_frame(squeeze=[100, 200, 300])
    dp, i, j = clustered.clustered_pairs(frame)
    assert dp == pytest.approx(0.01)
    assert sorted(i) == [100, 130, 200, 230, 300, 330]  # each squeezed particle and its right-hand neighbour
    assert all(abs(a - b) == 30 for a, b in zip(i, j))


def test_report_command(tmp_path):
    r = mpirun_mpisph(["taylor_green", "--set", "nx=20", "--t-end", "0.1", "--out", tmp_path, "--quiet"])
    assert r.returncode == 0, r.stderr
    r = mpirun_mpisph(["report", tmp_path / "frame_00001.hdf"])
    assert r.returncode == 0, r.stderr
    assert "clustering 0.000%, inner voids 0.000%, free surface 0.00%, closest pair" in r.stdout
