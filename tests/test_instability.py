"""The tensile-instability measure sees clusters, inner voids and fractures, and nothing on a
lattice, in 2D and 3D."""

import numpy as np
import pytest

from mpisph import pairing
from mpisph.instability import spacing, tensile_instability
from mpisph.launch import mpirun_mpisph


def lattice_frame(n=30, dp=0.01, remove=None, squeeze=(), dim=2):
    """An n^dim square or cubic lattice of spacing dp, less the particles ``remove(x)`` selects;
    each particle of ``squeeze`` moved to 0.3 dp from its neighbour in +x."""
    g = (np.arange(n) + 0.5) * dp
    x = np.stack([a.ravel() for a in np.meshgrid(*[g] * dim, indexing="ij")], axis=1)
    keep = np.ones(len(x), bool) if remove is None else ~remove(x)
    x = x[keep].copy()
    stride = n ** (dim - 1)  # the neighbour in +x, on the whole lattice
    for i in squeeze:
        x[i, 0] = x[i + stride, 0] - 0.3 * dp
    m = len(x)
    return {"x": x, "kind": np.zeros(m, np.int8), "mass": np.full(m, 1000 * dp**dim),
            "rho": np.full(m, 1000.0), "gid": np.arange(m), "params": {"h_factor": 1.3}}


SIZE = {2: 30, 3: 14}


@pytest.mark.parametrize("dim", [2, 3])
def test_regular_lattice_is_clean(dim):
    n = SIZE[dim]
    m = tensile_instability(lattice_frame(n, dim=dim))
    assert m["dp"] == pytest.approx(0.01)
    assert m["clustering"] == 0.0 and m["inner_voids"] == 0.0
    assert m["min_spacing"] == pytest.approx(1.0)
    assert m["fragments"] == 1 and m["detached"] == 0.0
    # the outermost layer is free surface, on every face alike (the second one stays above 0.75 d)
    assert m["surface"] * m["n"] == pytest.approx(n**dim - (n - 2) ** dim)


@pytest.mark.parametrize("dim, voids", [(2, 16), (3, 24)])
def test_hole_inside_is_a_void(dim, voids):
    """A hole 4 dp wide: in 2D the 16 particles facing it across an edge, in 3D the 24 facing the
    middles of its faces (2 x 2 a face: the rim of a face keeps more neighbours) count; the
    outermost layer is still surface."""
    n = SIZE[dim]
    hole = tensile_instability(lattice_frame(n, dim=dim, remove=lambda x: np.all(np.abs(x - n * 0.005) < 0.02,
                                                                                  axis=1)))
    assert hole["n"] == n**dim - 4**dim
    assert hole["inner_voids"] * hole["n"] == pytest.approx(voids)
    assert hole["surface"] * hole["n"] == pytest.approx(n**dim - (n - 2) ** dim)
    assert hole["fragments"] == 1


@pytest.mark.parametrize("dim", [2, 3])
def test_close_pairs_are_clusters(dim):
    n = SIZE[dim]
    m = tensile_instability(lattice_frame(n, dim=dim, squeeze=[100, 200, 300]))
    assert m["clustering"] * m["n"] == pytest.approx(6)  # three pairs
    assert m["min_spacing"] == pytest.approx(0.3)
    assert m["fragments"] == 1


@pytest.mark.parametrize("dim", [2, 3])
def test_a_crack_across_the_body_makes_two_fragments(dim):
    """Without the layer at x = 4.5 dp the lattice is two pieces 2 dp apart: two fragments, the
    smaller (4 layers of n) detached, while clustering sees nothing. Closed to 1.4 dp (under
    the 1.5 dp link) it is one piece again."""
    n = SIZE[dim]
    layer = lambda x: np.abs(x[:, 0] - 0.045) < 0.001  # noqa: E731
    cracked = tensile_instability(lattice_frame(n, dim=dim, remove=layer))
    assert cracked["fragments"] == 2 and cracked["clustering"] == 0.0
    assert cracked["detached"] == pytest.approx(4 / (n - 1))
    closed = lattice_frame(n, dim=dim, remove=layer)
    closed["x"][closed["x"][:, 0] > 0.045, 0] -= 0.006
    assert tensile_instability(closed)["fragments"] == 1


@pytest.mark.parametrize("dim", [2, 3])
def test_a_periodic_axis_joins_the_pieces_across_its_ends(dim):
    """The cracked lattice of the test above is one piece when x is periodic over its n dp: its
    ends are 1 dp apart across the period."""
    n = SIZE[dim]
    frame = lattice_frame(n, dim=dim, remove=lambda x: np.abs(x[:, 0] - 0.045) < 0.001)
    m = tensile_instability(frame, np.zeros(dim), [n * 0.01] + [0.0] * (dim - 1))
    assert m["fragments"] == 1 and m["detached"] == 0.0


def test_the_clustered_pairs_with_walls_are_the_squeezed_ones():
    """pairing.clustered_pairs(walls=True), what scripts/clustered.py describes."""
    frame = lattice_frame(squeeze=[100, 200, 300])
    i, j = pairing.clustered_pairs(frame, walls=True)
    assert spacing(frame) == pytest.approx(0.01)
    assert sorted(i) == [100, 130, 200, 230, 300, 330]  # each squeezed particle and its right-hand neighbour
    assert all(abs(a - b) == 30 for a, b in zip(i, j))


def test_report_command(tmp_path):
    r = mpirun_mpisph(["taylor_green", "--set", "nx=20", "--t-end", "0.1", "--out", tmp_path, "--quiet"])
    assert r.returncode == 0, r.stderr
    r = mpirun_mpisph(["report", tmp_path / "frame_00001.hdf"])
    assert r.returncode == 0, r.stderr
    assert "clustering 0.000%, inner voids 0.000%, free surface 0.00%, closest pair" in r.stdout
    assert "1 fragment (0.00% outside the largest)" in r.stdout
    assert "paired" not in r.stdout  # a fluid: pairing.applies says no


def test_report_command_on_a_soil_gives_its_paired_share(tmp_path):
    r = mpirun_mpisph(["cohesive_failure_2d", "--set", "dp=0.1", "--t-end", "0.1", "--output-interval", "0.05",
                       "--out", tmp_path, "--quiet"])
    assert r.returncode == 0, r.stderr
    r = mpirun_mpisph(["report", tmp_path / "frame_00000.hdf", tmp_path / "frame_00002.hdf"])
    assert r.returncode == 0, r.stderr
    assert r.stdout.count("% paired)") == 2 and "clustering 0.000% (0.000% paired)" in r.stdout
    whole = mpirun_mpisph(["report", tmp_path])  # the directory: each of its frames, in time order
    assert whole.returncode == 0, whole.stderr
    lines = whole.stdout.splitlines()
    assert [line.split(":")[0] for line in lines] == [str(tmp_path / f"frame_0000{i}.hdf") for i in range(3)]
    assert [lines[0], lines[2]] == r.stdout.splitlines()


def test_report_on_a_run_restarted_elsewhere_says_since_when_it_measures_pairing(tmp_path):
    """A run restarted into a directory of its own starts its frames after the restart's: the paired
    share is measured from its first frame there, and the line says so; of that first frame itself
    the line says there is nothing earlier to measure from."""
    first, restarted = tmp_path / "first", tmp_path / "restarted"
    r = mpirun_mpisph(["cohesive_failure_2d", "--set", "dp=0.1", "--t-end", "0.05", "--output-interval", "0.05",
                       "--out", first, "--quiet"])
    assert r.returncode == 0, r.stderr
    r = mpirun_mpisph(["cohesive_failure_2d", "--t-end", "0.15", "--output-interval", "0.05",
                       "--restart", first / "frame_00001.hdf", "--out", restarted, "--quiet"])
    assert r.returncode == 0, r.stderr
    r = mpirun_mpisph(["report", first / "frame_00001.hdf", restarted / "frame_00003.hdf", restarted / "frame_00002.hdf"])
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert "% paired)" in lines[0]  # measured from t = 0
    assert "% paired since its first frame here, t = 0.1 s)" in lines[1]
    assert "(paired share: no earlier frame in its directory)" in lines[2]
