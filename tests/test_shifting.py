"""Particle shifting (mpisph/stabilisers/shifting.py): no shift on a regular lattice, a displaced
particle pushed back, shifts along a free surface only and none for a splashed particle, and the
B-corrected Taylor correction of a linear field to its value at the new place."""

import numpy as np

from lattice import lattice
from mpisph import surface
from mpisph.correction import correction_matrix
from mpisph.neighbours import neighbour_lists
from mpisph.stabilisers.shifting import shifts, taylor_corrections
from mpisph.tensors import size

DP = 0.01
RHO = 1000.0


def shifts_of(x, kind, start, nbr, k, cls):
    n, dim = x.shape
    mass = np.full(n, RHO * DP**dim)
    rho = np.full(n, RHO)
    B = np.empty((n, size(dim)))
    correction_matrix(n, start, nbr, x, mass, rho, kind, k.params, B)
    out = np.empty((n, dim))
    shifts(n, start, nbr, x, mass, rho, kind, cls, B, 0.04 * 0.25 * k.h, k.params, out)  # C alpha, dual criteria
    return out


def test_a_regular_lattice_is_left_where_it_is():
    for dim in (2, 3):
        x, kind, start, nbr, k, inner = lattice(dim, 1.3, n=12 if dim == 2 else 9, dp=DP)
        dr = shifts_of(x, kind, start, nbr, k, np.full(len(x), surface.INNER, np.int8))
        assert np.abs(dr[inner]).max() < 1e-12 * DP


def test_a_displaced_particle_is_pushed_back_towards_its_place():
    x, kind, start, nbr, k, inner = lattice(2, 1.3, n=12, dp=DP)
    i = int(np.argmin(np.sum((x - 6 * DP) ** 2, axis=1)))
    moved = np.array([0.2, -0.1]) * DP
    x[i] += moved
    start, nbr = neighbour_lists(x, np.arange(len(x)), kind, len(x), k.support, np.zeros(2) - DP)
    dr = shifts_of(x, kind, start, nbr, k, np.full(len(x), surface.INNER, np.int8))
    assert np.dot(dr[i], moved) < 0.0
    assert 0.0 < np.linalg.norm(dr[i]) < np.linalg.norm(moved)
    assert np.linalg.norm(x[i] + dr[i] - (x[i] - moved)) < np.linalg.norm(moved)


def test_surface_particles_move_along_the_surface_and_splashed_ones_not_at_all():
    x, kind, start, nbr, k, inner = lattice(2, 1.3, n=12, dp=DP)
    top = np.isclose(x[:, 1], x[:, 1].max())
    cls = np.where(top, surface.SURFACE, surface.INNER).astype(np.int8)
    i = int(np.flatnonzero(top)[6])
    x[i, 0] += 0.2 * DP  # towards its right-hand neighbour on the flat top
    start, nbr = neighbour_lists(x, np.arange(len(x)), kind, len(x), k.support, np.zeros(2) - DP)
    free = shifts_of(x, kind, start, nbr, k, np.full(len(x), surface.INNER, np.int8))
    dr = shifts_of(x, kind, start, nbr, k, cls)
    assert free[i, 1] > 0.1 * abs(free[i, 0])  # unprojected, it would leave the surface upwards
    assert dr[i, 0] < 0.0  # back along the surface
    assert abs(dr[i, 1]) < 0.05 * free[i, 1]  # along the surface (whose normal B g the displacement tilts)
    cls[i] = surface.SPLASHED
    assert not shifts_of(x, kind, start, nbr, k, cls)[i].any()


def test_a_linear_field_is_corrected_to_its_value_at_the_new_place():
    for dim in (2, 3):
        x, kind, start, nbr, k, inner = lattice(dim, 1.3, n=12 if dim == 2 else 9, dp=DP)
        n = len(x)
        gradient = np.array([[3.0, -1.0, 2.0], [0.5, 4.0, -2.0]])[:, :dim]  # two fields, rows = fields
        f = x @ gradient.T + 7.0
        dr = np.random.default_rng(3).uniform(-0.1, 0.1, (n, dim)) * DP
        mass, rho = np.full(n, RHO * DP**dim), np.full(n, RHO)
        B = np.empty((n, size(dim)))
        correction_matrix(n, start, nbr, x, mass, rho, kind, k.params, B)
        out = np.empty((n, 2))
        taylor_corrections(n, start, nbr, x, mass, rho, kind, B, k.params, dr, f, out)
        # exact at every particle, the lattice's edges and corners (free surfaces) included
        np.testing.assert_allclose(out, dr @ gradient.T, rtol=0, atol=1e-9 * np.abs(dr @ gradient.T).max())
