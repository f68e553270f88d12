"""scripts/pair_closing.py splits the closing of a clustered pair into what the pair's velocities did
and what a shift without a velocity did."""

import numpy as np

from mpisph.particles import MOVING
from repo_script import load_script

pair_closing = load_script("pair_closing")


def frames_of(t, x):
    """Frames of a 3 x 3 lattice of spacing 1 in 2D whose first two particles have positions x(t)
    (the others still), their velocities dx/dt by differences."""
    lattice = np.array([[a, b] for a in range(3) for b in range(3)], float) * 10.0  # far apart but the pair
    out = []
    for k, tk in enumerate(t):
        pos = lattice.copy()
        pos[:2] = x[k]
        v = np.zeros_like(pos)
        v[:2] = np.gradient(x, t, axis=0)[k]
        out.append({"t": tk, "x": pos, "v": v, "gid": np.arange(9), "kind": np.full(9, MOVING),
                    "mass": np.ones(9), "rho": np.ones(9)})
    return out


def test_a_pair_that_moves_together_closes_by_its_velocities():
    t = np.linspace(0.0, 1.0, 201)
    gap = 1.0 - 0.8 * t  # from 1 dp to 0.2 dp at a constant relative speed
    x = np.stack([np.stack([np.zeros_like(t), np.zeros_like(t)], 1), np.stack([gap, np.zeros_like(t)], 1)], 1)
    change, by_velocity = pair_closing.closing(frames_of(t, x))
    np.testing.assert_allclose(change, -0.8, atol=1e-12)  # each particle of the pair: the same pair
    np.testing.assert_allclose(by_velocity, -0.8, atol=1e-9)


def test_a_shift_without_a_velocity_is_the_rest():
    t = np.linspace(0.0, 1.0, 201)
    gap = 1.0 - 0.8 * t
    x = np.stack([np.stack([np.zeros_like(t), np.zeros_like(t)], 1), np.stack([gap, np.zeros_like(t)], 1)], 1)
    frames = frames_of(t, x)
    for f in frames:
        f["v"][:] = 0.0  # the same motion with no velocity: a shift did it all
    change, by_velocity = pair_closing.closing(frames)
    np.testing.assert_allclose(change, -0.8, atol=1e-12)
    np.testing.assert_allclose(by_velocity, 0.0, atol=1e-12)
