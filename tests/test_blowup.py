"""The blow-up check names the first moving particle in trouble, and what the trouble is."""

import numpy as np
import pytest

from mpisph.blowup import NON_FINITE, NON_POSITIVE_DENSITY, OUTSIDE, first_bad_particle
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
