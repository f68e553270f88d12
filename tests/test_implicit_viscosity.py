"""The implicit viscous kick of the mu(I) scheme (physics/implicit_viscosity.py): its operator is
the explicit pair term of Eq. 27, the system it solves is symmetric and dissipative, and the
conjugate gradients solve it, at steps far beyond the explicit limit of Eq. 39."""

from types import SimpleNamespace

import numpy as np
import pytest
from mpi4py import MPI

from mpisph.neighbours import neighbour_lists
from mpisph.particles import MOVING, WALL, WALL_SLIP
from mpisph.physics.implicit_viscosity import TOLERANCE, ImplicitViscosity, viscous_acceleration, viscous_pairs
from mpisph.physics.mu_i import momentum
from mpisph.physics.mu_i_law import MEAN_ARITHMETIC, MEAN_HARMONIC, MEAN_SECANT
from mpisph.workspace import Workspace

from lattice import lattice

DP = 0.01
BED_ROWS = 3


def bed_lattice(dim, bed_kind, seed=1):
    """A lattice whose lowest BED_ROWS layers are Morris wall particles under the surface
    y (or z) = BED_ROWS dp, with random velocities, densities and viscosities spanning four decades."""
    x, _, _, _, k, _ = lattice(dim, 1.3, n=12, dp=DP)
    up = x[:, -1]
    kind = np.where(up < BED_ROWS * DP, bed_kind, MOVING).astype(np.int8)
    start, nbr = neighbour_lists(x, np.arange(len(x)), kind, len(x), k.support, np.zeros(dim) - DP)
    rng = np.random.default_rng(seed)
    n = len(x)
    normal = np.zeros((n, dim))
    normal[:, -1] = 1.0
    state = SimpleNamespace(
        x=x, kind=kind, start=start, nbr=nbr, k=k, n=n, normal=normal,
        wall_distance=np.where(kind != MOVING, BED_ROWS * DP - up, 0.0),
        v=np.where((kind == MOVING)[:, None], rng.normal(size=(n, dim)), 0.0),
        rho=rng.uniform(1400.0, 1600.0, n), eta=10.0 ** rng.uniform(-1.0, 3.0, n),
        gamma_dot=10.0 ** rng.uniform(-2.0, 2.0, n))
    state.mass = state.rho * DP**dim
    return state


def apply(s, u, homogeneous=True, mean=MEAN_HARMONIC):
    out = np.zeros((s.n, s.x.shape[1]))
    coef, inverse = np.zeros(len(s.nbr)), np.zeros((s.n, s.x.shape[1], s.x.shape[1]))
    viscous_pairs(s.n, s.start, s.nbr, s.x, s.rho, s.eta, s.gamma_dot, s.mass, s.kind, s.normal, s.wall_distance,
                  1.5, 2.0 * (s.x.shape[1] + 2), mean, s.k.params, 1e-3, coef, inverse)
    viscous_acceleration(s.n, s.start, s.nbr, s.x, s.kind, s.normal, coef, u, homogeneous, out)
    return out


@pytest.mark.parametrize("mean", [MEAN_HARMONIC, MEAN_ARITHMETIC, MEAN_SECANT])
@pytest.mark.parametrize("dim", [2, 3])
def test_operator_is_the_explicit_pair_term_of_eq_27(dim, mean):
    s = bed_lattice(dim, WALL)
    zeros = np.zeros(s.n)
    explicit = np.zeros((s.n, dim))
    momentum(s.n, s.start, s.nbr, s.x, s.v, s.rho, zeros, s.eta, s.gamma_dot, np.zeros((0, 1, 1)), s.mass, s.kind,
             s.normal, s.wall_distance, 1.5, 0.0, 1.0, 2.0 * (dim + 2), mean, s.k.params, explicit)
    implicit = apply(s, s.v, homogeneous=False, mean=mean)
    np.testing.assert_allclose(implicit, explicit, rtol=0, atol=1e-12 * np.abs(explicit).max())


@pytest.mark.parametrize("mean", [MEAN_HARMONIC, MEAN_ARITHMETIC, MEAN_SECANT])
@pytest.mark.parametrize("bed_kind", [WALL, WALL_SLIP])
@pytest.mark.parametrize("dim", [2, 3])
def test_mass_weighted_operator_is_symmetric_and_dissipative(dim, bed_kind, mean):
    s = bed_lattice(dim, bed_kind)
    rng = np.random.default_rng(2)
    moving = (s.kind == MOVING)[:, None]
    p, q = (np.where(moving, rng.normal(size=(s.n, dim)), 0.0) for _ in range(2))
    m = s.mass[:, None]
    pAq, qAp, pAp = (np.sum(a * m * apply(s, b, mean=mean)) for a, b in ((p, q), (q, p), (p, p)))
    assert pAq == pytest.approx(qAp, rel=1e-12)
    assert pAp < 0.0


class NoHalo:
    comm = MPI.COMM_SELF

    def refresh(self, particles, names):
        pass


@pytest.mark.parametrize("bed_kind", [WALL, WALL_SLIP])
@pytest.mark.parametrize("dim", [2, 3])
def test_conjugate_gradients_solve_the_backward_euler_kick(dim, bed_kind):
    """At 1000 times the explicit limit of Eq. 39 the kick solves u - dt a_visc[u] = b to the
    tolerance and takes kinetic energy out, never in."""
    s = bed_lattice(dim, bed_kind)
    dt = 1000.0 * 0.05 * s.rho.min() * s.k.h**2 / s.eta.max()
    pa = SimpleNamespace(n_owned=s.n, dim=dim, v=s.v.copy(), rho=s.rho, eta=s.eta, gamma_dot=s.gamma_dot,
                         mass=s.mass, kind=s.kind,
                         normal=s.normal, wall_distance=s.wall_distance, viscous_direction=np.zeros((s.n, dim)),
                         viscous_acceleration=np.zeros((s.n, dim)))
    ctx = SimpleNamespace(particles=pa, start=s.start, nbr=s.nbr, xc=s.x, kernel=s.k, workspace=Workspace(),
                          halo=NoHalo())
    ctx.refresh = lambda names: None
    scheme = SimpleNamespace(corrected=False, beta_max=1.5, viscous_factor=2.0 * (dim + 2), mean=MEAN_SECANT)
    solver = ImplicitViscosity(scheme, u_ref=1.0)
    solver.kick(ctx, dt)
    u, b = pa.v, s.v
    moving = s.kind == MOVING
    error = (u - dt * apply(s, u, homogeneous=False, mean=MEAN_SECANT) - b)[moving]
    rms = np.sqrt(np.sum(s.mass[moving, None] * error**2) / s.mass[moving].sum())
    assert 2 < solver.iterations < 200
    assert rms < 50 * TOLERANCE  # the stop is on the preconditioned residual
    assert np.sum(s.mass[:, None] * u**2) < np.sum(s.mass[:, None] * b**2)
    # the next kick starts from b + dt a_visc of this one: from the same b it is already solved
    first = solver.iterations
    np.testing.assert_allclose(pa.viscous_acceleration[moving], ((u - b) / dt)[moving])
    pa.v = b.copy()
    solver.kick(ctx, dt)
    assert solver.iterations <= 1 < first
    rms = np.sqrt(np.sum(s.mass[moving, None] * (pa.v - u)[moving] ** 2) / s.mass[moving].sum())
    assert rms < 50 * TOLERANCE
