"""The Riemann dissipation limiter (001_ Eq. 6, 000_ Eq. 20) on either kind of pair: the
dissipative part of the Riemann pressure, -beta rho_bar c0 u_jump / 2, only removes energy
whichever pairs beta selects (the power of a pair is beta rho_bar c0 m_i m_j u_jump^2 W' /
(rho_i rho_j) <= 0), and it acts on the pairs the option ``limiter`` names only (none: on no
pair)."""

import numpy as np
import pytest

from mpisph.kernels import Kernel
from mpisph.neighbours import neighbour_lists
from mpisph.physics.fluid import LIMITED_PAIRS, pressure_acceleration
from mpisph.physics.solid import stress_acceleration

DP = 0.01
RHO, C0 = 1000.0, 20.0


def cloud(seed, n=12):
    rng = np.random.default_rng(seed)
    g = (np.arange(n) + 0.5) * DP
    x = np.stack([a.ravel() for a in np.meshgrid(g, g, indexing="ij")], axis=1)
    x += rng.uniform(-0.2, 0.2, x.shape) * DP
    k = Kernel("wendland_c2", 1.3 * DP, 2)
    kind = np.zeros(len(x), np.int8)
    start, nbr = neighbour_lists(x, np.arange(len(x)), kind, len(x), k.support, np.zeros(2) - DP)
    return rng, x, kind, start, nbr, k, np.full(len(x), RHO * DP**2), RHO * rng.uniform(0.98, 1.02, len(x))


def dissipative_acceleration(material, x, kind, start, nbr, k, mass, rho, v, damped):
    """The acceleration of the Riemann dissipation alone (zero pressure and stress)."""
    n = len(x)
    acc = np.zeros((n, 2))
    zero = np.zeros(n)
    if material == "fluid":
        pressure_acceleration(n, start, nbr, x, v, rho, zero, mass, kind, np.zeros_like(x), np.zeros(2), C0,
                              damped, k.params, acc)
    else:
        stress_acceleration(n, start, nbr, x, v, rho, zero, np.zeros((n, 6)), mass, kind, np.zeros_like(x), C0,
                            40.0, damped, k.params, acc)
    return acc


@pytest.mark.parametrize("material", ["fluid", "granular"])
@pytest.mark.parametrize("limiter", list(LIMITED_PAIRS))
def test_the_limited_dissipation_never_adds_energy(material, limiter):
    rng, x, kind, start, nbr, k, mass, rho = cloud(7)
    damped = LIMITED_PAIRS[limiter]
    for _ in range(5):
        v = rng.normal(size=x.shape) * 2.0
        acc = dissipative_acceleration(material, x, kind, start, nbr, k, mass, rho, v, damped)
        power = np.sum(mass[:, None] * v * acc)
        assert power < 0.0 if limiter != "none" else power == 0.0


@pytest.mark.parametrize("material", ["fluid", "granular"])
def test_the_limiter_acts_on_the_pairs_it_names(material):
    """A uniform expansion has only separating pairs, a uniform contraction only approaching ones;
    ``none`` damps neither."""
    _, x, kind, start, nbr, k, mass, rho = cloud(8)
    expanding = 0.5 * (x - x.mean(axis=0))
    for v, acting in ((expanding, "separating"), (-expanding, "approaching")):
        for limiter, damped in LIMITED_PAIRS.items():
            acc = dissipative_acceleration(material, x, kind, start, nbr, k, mass, rho, v, damped)
            assert np.any(acc != 0.0) == (limiter == acting)
