"""mpisph/pairing.py tells the flow's squeeze of a lattice from pairing, in 2D and 3D."""

import numpy as np
import pytest

from mpisph import pairing
from test_instability import SIZE, lattice_frame


@pytest.mark.parametrize("dim", [2, 3])
def test_a_squeezed_lattice_is_clustered_but_not_paired(dim):
    """Squeezed to 0.45 of its spacing along x and stretched along y (at constant volume), every
    particle of a lattice has its x-neighbour 0.45 dp away: all clustered, none paired. The fitted
    deformation is the squeeze, and every pair is exactly as close as it makes it."""
    first = lattice_frame(SIZE[dim], dim=dim)
    F = np.diag([0.45, 1.0 / 0.45, 1.0][:dim])
    squeezed = dict(first, x=first["x"] @ F.T)
    i, j = pairing.clustered_pairs(squeezed)
    assert len(i) == len(first["x"])
    np.testing.assert_allclose(pairing.fitted_deformation(squeezed, first, i), np.tile(F, (len(i), 1, 1)),
                               atol=1e-12)
    ratio, separation = pairing.affine_ratio(squeezed, first, i, j)
    np.testing.assert_allclose(ratio, 1.0, rtol=1e-12)
    np.testing.assert_allclose(separation, 0.01, rtol=1e-12)  # x-neighbours on the first lattice
    assert pairing.paired_share(squeezed, first) == 0.0


@pytest.mark.parametrize("dim", [2, 3])
def test_a_particle_moved_onto_its_neighbour_is_paired(dim):
    """On the undeformed lattice, the central particle moved to 0.3 dp of its neighbour in +x: the two
    are paired, nothing else is clustered."""
    n = SIZE[dim]
    centre = sum(n // 2 * n**k for k in range(dim))
    first = lattice_frame(n, dim=dim)
    moved = lattice_frame(n, dim=dim, squeeze=[centre])
    i, j = pairing.clustered_pairs(moved)
    assert sorted(i) == [centre, centre + n ** (dim - 1)]
    assert np.all(pairing.affine_ratio(moved, first, i, j)[0] < 0.4)
    assert pairing.paired_share(moved, first) == pytest.approx(2 / n**dim)


def test_wall_particles_take_no_part():
    """A wall particle 0.3 dp from a moving one clusters it for instability.py but pairs nothing here."""
    frame = lattice_frame()
    wall = {"x": [[0.002, 0.005]], "kind": [1], "mass": [0.1], "rho": [1000.0], "gid": [10**6]}
    for key, value in wall.items():
        frame[key] = np.concatenate([frame[key], np.asarray(value, frame[key].dtype)])
    assert pairing.clustered_pairs(frame)[0].size == 0
    assert pairing.paired_share(frame, frame) == 0.0
