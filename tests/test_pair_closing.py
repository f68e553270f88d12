"""scripts/pair_closing.py splits the closing of a clustered pair into what the pair's velocities did
and what a shift without a velocity did."""

import numpy as np

from mpisph.particles import MOVING
from repo_script import load_script

pair_closing = load_script("pair_closing")


def approaching_pair(with_velocity):
    """Frames of nine particles of volume 1 (dp = 1), 10 apart, of which the second closes on the first
    from 1 dp to 0.2 dp at a constant speed; with ``with_velocity`` their velocities are that motion's,
    else zero (a shift moved them)."""
    t = np.linspace(0.0, 1.0, 201)
    lattice = np.array([[a, b] for a in range(3) for b in range(3)], float) * 10.0
    speed = -0.8 if with_velocity else 0.0
    out = []
    for tk in t:
        x, v = lattice.copy(), np.zeros_like(lattice)
        x[1] = x[0] + (1.0 - 0.8 * tk, 0.0)
        v[1] = (speed, 0.0)
        out.append({"t": tk, "x": x, "v": v, "gid": np.arange(9), "kind": np.full(9, MOVING),
                    "mass": np.ones(9), "rho": np.ones(9)})
    return out


def test_a_pair_that_moves_together_closes_by_its_velocities():
    change, by_velocity = pair_closing.closing(approaching_pair(with_velocity=True))
    np.testing.assert_allclose(change, -0.8, atol=1e-12)  # both particles of the pair
    np.testing.assert_allclose(by_velocity, -0.8, atol=1e-12)


def test_a_shift_without_a_velocity_is_the_rest():
    change, by_velocity = pair_closing.closing(approaching_pair(with_velocity=False))
    np.testing.assert_allclose(change, -0.8, atol=1e-12)
    np.testing.assert_allclose(by_velocity, 0.0, atol=1e-12)
