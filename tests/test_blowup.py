"""The blow-up check names the first moving particle in trouble, and what the trouble is."""

import numpy as np
import pytest

from mpisph.blowup import NON_FINITE, NON_POSITIVE_DENSITY, OUTSIDE, first_bad_particle, first_coincident_pair
from mpisph.neighbours import neighbour_lists
from mpisph.particles import MOVING, WALL


def check(rho=1.0, x=0.5, v=0.0, kind=MOVING, periodic=False):
    n = 3
    xs, vs = np.full((n, 2), 0.5), np.zeros((n, 2))
    rhos, kinds = np.ones(n), np.full(n, MOVING, np.int8)
    xs[1, 0], vs[1, 0], rhos[1], kinds[1] = x, v, rho, kind
    return first_bad_particle(n, kinds, xs, vs, rhos, np.zeros(2), np.ones(2), np.array([periodic, False]))


@pytest.mark.parametrize("change, expected", [
    ({}, (-1, 0)), ({"rho": np.nan}, (1, NON_FINITE)), ({"v": np.inf}, (1, NON_FINITE)),
    ({"rho": 0.0}, (1, NON_POSITIVE_DENSITY)), ({"rho": -3.0}, (1, NON_POSITIVE_DENSITY)),
    ({"x": 1.2}, (1, OUTSIDE)), ({"x": 1.2, "periodic": True}, (-1, 0)),
    ({"rho": -3.0, "kind": WALL}, (-1, 0))])
def test_first_bad_particle(change, expected):
    assert tuple(check(**change)) == expected


@pytest.mark.parametrize("dim", [2, 3])
def test_first_coincident_pair_finds_a_particle_twice_and_nothing_on_a_lattice(dim):
    axes = np.meshgrid(*([np.arange(4.0)] * dim), indexing="ij")
    x = np.stack([a.ravel() for a in axes], axis=1)
    n = len(x)
    start, nbr = neighbour_lists(x, np.arange(n), np.zeros(n, np.int8), n, 1.5, np.full(dim, -1.0))
    assert first_coincident_pair(n, start, nbr, x) == (-1, -1)
    x = np.concatenate([x, x[5:6]])  # particle 5 again, as the last one
    start, nbr = neighbour_lists(x, np.arange(n + 1), np.zeros(n + 1, np.int8), n + 1, 1.5, np.full(dim, -1.0))
    assert first_coincident_pair(n + 1, start, nbr, x) == (5, n)
