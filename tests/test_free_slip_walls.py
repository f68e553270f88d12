"""Free-slip walls (walls.along_wall_normal) on a wall lattice that is not regular: the wall pushes
only along its normal (Riemann solids and fluids, mu(I)), and its pairs do the work that the strain
rate (solids) or the density (fluids) stores, as pairs of material particles do."""

import numpy as np
import pytest

from mpisph.kernels import Kernel
from mpisph.neighbours import neighbour_lists
from mpisph.particles import MOVING, WALL_SLIP
from mpisph.physics.fluid import continuity, pressure_acceleration
from mpisph.physics.mu_i import momentum
from mpisph.physics.mu_i_law import MEAN_ARITHMETIC
from mpisph.physics.solid import stress_acceleration, velocity_gradient
from mpisph.tensors import packed

DP = 0.01
H = 1.3 * DP
KERNEL = Kernel("wendland_c2", H, 2).params


def jittered_floor(rng, nx=12, rows=3):
    """Wall particles of a floor y < 0 (normal +y) moved off their lattice by up to 0.3 dp, as at a
    joint of two wall parts."""
    gx, gy = np.meshgrid((np.arange(nx) + 0.5) * DP, -(np.arange(rows) + 0.5) * DP, indexing="ij")
    floor = np.column_stack([gx.ravel(), gy.ravel()])
    return floor + rng.uniform(-0.3, 0.3, floor.shape) * DP


def block_on_floor(rng):
    """(x, kind, normal, n_body): a disordered 12 x 6 block of material particles on a jittered
    free-slip floor (normal +y), the block first."""
    gx, gy = np.meshgrid((np.arange(12) + 0.5) * DP, (np.arange(6) + 0.5) * DP, indexing="ij")
    body = np.column_stack([gx.ravel(), gy.ravel()]) + rng.uniform(-0.15, 0.15, (72, 2)) * DP
    return with_floor(body, jittered_floor(rng))


def alone_above_floor(rng):
    """(x, kind, normal, 1): one material particle 0.6 dp above a jittered free-slip floor."""
    return with_floor(np.array([[6 * DP, 0.6 * DP]]), jittered_floor(rng))


def with_floor(body, floor):
    """(x, kind, normal, n_body): material particles ``body`` then free-slip wall particles ``floor``."""
    x = np.concatenate([body, floor])
    kind = np.full(len(x), WALL_SLIP, np.int8)
    kind[:len(body)] = MOVING
    normal = np.zeros_like(x)
    normal[:, 1] = 1.0
    return x, kind, normal, len(body)


def test_a_free_slip_wall_pushes_only_along_its_normal_however_irregular():
    """A particle with normal stresses and pressure above a jittered free-slip floor: no force along
    the floor (the wall lattice's tangential gradients no longer push along it)."""
    x, kind, normal, _ = alone_above_floor(np.random.default_rng(11))
    n = len(x)
    stress = np.zeros((n, 3, 3))
    stress[0] = np.diag([-3e3, -5e3, -4e3])
    p = np.full(n, 4e3)
    start, nbr = neighbour_lists(x, np.arange(n), kind, n, 2 * H, x.min(axis=0) - DP)
    acc = np.zeros((n, 2))
    stress_acceleration(n, start, nbr, x, np.zeros((n, 2)), np.full(n, 1000.0), p, packed(stress),
                        np.full(n, 1000 * DP**2), kind, normal, 30.0, 40.0, 1.0, KERNEL, acc)
    assert acc[0, 1] > 1.0
    assert acc[0, 0] == 0.0


def test_free_slip_wall_pairs_do_the_work_the_strain_rate_stores():
    """Power of the stress forces = minus the stress power on the velocity gradient (both
    uncorrected, as for granular materials, no dissipation) for a disordered block on a jittered
    free-slip floor: the wall pairs keep kinetic plus strain energy as the particle pairs do."""
    rng = np.random.default_rng(7)
    x, kind, normal, n_body = block_on_floor(rng)
    n = len(x)
    mass, rho = np.full(n, 1000 * DP**2), 1000.0 * rng.uniform(0.95, 1.05, n)
    v = rng.normal(size=(n, 2))
    v[n_body:] = 0.0  # the floor stands still
    stress = rng.normal(size=(n, 3, 3)) * 1e3
    stress = stress + stress.transpose(0, 2, 1)
    stress[:, 2, :2] = stress[:, :2, 2] = 0.0
    p = -np.trace(stress, axis1=1, axis2=2) / 3
    start, nbr = neighbour_lists(x, np.arange(n), kind, n, 2 * H, x.min(axis=0) - DP)
    L = np.zeros((n, 3, 3))
    for i in range(n_body):
        velocity_gradient(i, start, nbr, x, v, mass, rho, kind, normal, np.zeros(0), 0.0, np.zeros((0, 3)),
                          KERNEL, L[i])
    acc = np.zeros((n, 2))
    stress_acceleration(n, start, nbr, x, v, rho, p, packed(stress), mass, kind, normal, 0.0, -1.0, 1.0,
                        KERNEL, acc)
    moving = kind == MOVING
    power = np.sum(mass[moving, None] * v[moving] * acc[moving])
    stress_power = np.sum((mass / rho)[moving] * np.einsum("iab,iab->i", stress[moving], L[moving]))
    assert abs(stress_power) > 1.0
    assert power == pytest.approx(-stress_power, rel=1e-10)


def test_a_free_slip_wall_takes_the_fluid_pressure_along_its_normal_only():
    """Power of the pressure forces = minus the rate of the internal energy that the continuity
    (Eq. 21: without the Riemann term, no dissipation) stores, on a disordered patch of fluid on a
    jittered free-slip floor; and no force along the floor on a particle alone above it."""
    rng = np.random.default_rng(9)
    x, kind, normal, n_body = block_on_floor(rng)
    n = len(x)
    mass, rho = np.full(n, 1000 * DP**2), 1000.0 * rng.uniform(0.98, 1.02, n)
    p = rng.uniform(0.0, 2e3, n)
    v = rng.normal(size=(n, 2))
    v[n_body:] = 0.0  # the floor stands still
    start, nbr = neighbour_lists(x, np.arange(n), kind, n, 2 * H, x.min(axis=0) - DP)
    acc, drho_dt = np.zeros((n, 2)), np.zeros(n)
    no_gravity, c0, no_limiter = np.zeros(2), 20.0, 0.0
    pressure_acceleration(n, start, nbr, x, v, rho, p, mass, kind, normal, no_gravity, c0, no_limiter, KERNEL, acc)
    continuity(n, start, nbr, x, v, rho, p, mass, kind, normal, no_gravity, c0, 0.0, KERNEL, drho_dt)
    moving = kind == MOVING
    power = np.sum(mass[moving, None] * v[moving] * acc[moving])
    internal = np.sum((mass * p / rho**2 * drho_dt)[moving])
    assert abs(power) > 1.0
    assert power == pytest.approx(-internal, rel=1e-10)

    x, kind, normal, _ = alone_above_floor(rng)
    n = len(x)
    start, nbr = neighbour_lists(x, np.arange(n), kind, n, 2 * H, x.min(axis=0) - DP)
    alone = np.zeros((n, 2))
    pressure_acceleration(n, start, nbr, x, np.zeros((n, 2)), np.full(n, 1000.0), np.full(n, 1e3),
                          np.full(n, 1000 * DP**2), kind, normal, no_gravity, c0, no_limiter, KERNEL, alone)
    assert alone[0, 1] > 1.0
    assert alone[0, 0] == 0.0


def test_a_free_slip_morris_wall_takes_the_mu_i_pressure_along_its_normal_only():
    """The mu(I) scheme's pressure pairs (004_ Eq. 27) with a jittered free-slip Morris floor: no
    force along the floor on a particle alone above it."""
    x, kind, normal, _ = alone_above_floor(np.random.default_rng(13))
    n = len(x)
    wall_distance = np.maximum(-x[:, 1], 0.0)
    start, nbr = neighbour_lists(x, np.arange(n), kind, n, 2 * H, x.min(axis=0) - DP)
    acc = np.zeros((n, 2))
    zero = np.zeros(n)
    momentum(n, start, nbr, x, np.zeros((n, 2)), np.full(n, 1000.0), np.full(n, 1e3), zero, zero,
             np.full(n, 1000 * DP**2), kind, normal, wall_distance, 1.5, 0.0, 20.0, True, 0.0, 1.0, 0.0,
             MEAN_ARITHMETIC, KERNEL, acc)
    assert acc[0, 1] > 1.0
    assert acc[0, 0] == 0.0
