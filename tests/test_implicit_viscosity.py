"""The implicit viscous kick of the mu(I) scheme (physics/implicit_viscosity.py): its operator is
the explicit pair term of Eq. 27 or the corrected stress's divergence (physics/viscous_stress.py),
the system it solves is symmetric and dissipative, and the conjugate gradients solve it, at steps
far beyond the explicit limit of Eq. 39."""

from types import SimpleNamespace

import numpy as np
import pytest
from mpi4py import MPI

from mpisph.correction import correction_matrix
from mpisph.errors import InputError
from mpisph.neighbours import neighbour_lists
from mpisph.particles import MOVING, WALL, WALL_SLIP
from mpisph.physics.implicit_viscosity import (TOLERANCE, ImplicitViscosity, add_along_velocity, viscous_acceleration,
                                               viscous_pairs)
from mpisph.physics.mu_i import momentum, pair_term_factors
from mpisph.physics.mu_i_law import MEAN_ARITHMETIC, MEAN_HARMONIC, MEAN_SECANT
from mpisph.physics.viscous_stress import strain_rate, stress_blocks, stress_divergence, viscous_force_tensor
from mpisph.tensors import component, size, unpacked
from mpisph.workspace import Workspace

from lattice import lattice

DP = 0.01
BED_ROWS = 3


def bed_lattice(dim, bed_kind, seed=1, jitter=0.0):
    """A lattice whose lowest BED_ROWS layers are Morris wall particles under the surface
    y (or z) = BED_ROWS dp, with random velocities, densities and viscosities spanning four decades;
    the material particles moved off the lattice by up to ``jitter`` dp."""
    x, _, _, _, k, _ = lattice(dim, 1.3, n=12, dp=DP)
    up = x[:, -1]
    kind = np.where(up < BED_ROWS * DP, bed_kind, MOVING).astype(np.int8)
    shift = np.random.default_rng(seed + 1).uniform(-jitter, jitter, x.shape) * DP
    x = x + np.where((kind == MOVING)[:, None], shift, 0.0)
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


def pairs(s, mean=MEAN_HARMONIC, deviatoric=False, dt=1e-3):
    """The pair coefficients of Eq. 27's term (of its deviatoric counterpart, mu_i.pair_term_factors)
    and the inverted diagonal blocks of the kick at step dt."""
    dim = s.x.shape[1]
    coef, inverse = np.zeros(len(s.nbr)), np.zeros((s.n, dim, dim))
    viscous_pairs(s.n, s.start, s.nbr, s.x, s.rho, s.eta, s.gamma_dot, s.mass, s.kind, s.normal, s.wall_distance,
                  1.5, *pair_term_factors(dim, deviatoric), mean, s.k.params, dt, coef, inverse)
    return coef, inverse


def apply(s, u, mean=MEAN_HARMONIC, deviatoric=False):
    """The pair term of Eq. 27 at u (its deviatoric counterpart)."""
    dim = s.x.shape[1]
    _, radial, along = pair_term_factors(dim, deviatoric)
    out = np.zeros((s.n, dim))
    coef = pairs(s, mean, deviatoric)[0]
    viscous_acceleration(s.n, s.start, s.nbr, s.x, s.kind, s.normal, coef, radial, u, out)
    if along > 0.0:
        add_along_velocity(s.n, s.start, s.nbr, s.x, s.kind, s.normal, coef, along, u, out)
    return out


def correction(s):
    """B of 000_ Eq. 24 of the material particles."""
    B = np.zeros((s.n, size(s.x.shape[1])))
    correction_matrix(s.n, s.start, s.nbr, s.x, s.mass, s.rho, s.kind, s.k.params, B)
    return B


def strain(s, u, B):
    """eps[u] of the corrected gradient, packed."""
    eps = np.zeros((s.n, B.shape[1]))
    strain_rate(s.n, s.start, s.nbr, s.x, u, s.rho, s.mass, s.kind, s.normal, s.wall_distance, 1.5, B, s.k.params,
                eps, np.zeros(s.n))
    return eps


def divergence(s, T):
    out = np.zeros((s.n, s.x.shape[1]))
    stress_divergence(s.n, s.start, s.nbr, s.x, s.rho, T, s.mass, s.kind, s.normal, s.k.params, out)
    return out


def stress_apply(s, u, B, deviatoric=False):
    """The divergence of the corrected viscous stress at u (of its deviatoric part)."""
    dim = s.x.shape[1]
    T = np.zeros((s.n, dim, dim))
    viscous_force_tensor(s.n, s.kind, strain(s, u, B), s.eta, B, deviatoric, T)
    return divergence(s, T)


def deviator(e):
    """e - tr(e) / D I of stacked D x D tensors."""
    dim = e.shape[-1]
    return e - np.einsum("iaa->i", e)[:, None, None] / dim * np.eye(dim)


@pytest.mark.parametrize("deviatoric", [False, True])
@pytest.mark.parametrize("mean", [MEAN_HARMONIC, MEAN_ARITHMETIC, MEAN_SECANT])
@pytest.mark.parametrize("bed_kind", [WALL, WALL_SLIP])
@pytest.mark.parametrize("dim", [2, 3])
def test_operator_is_the_explicit_pair_term(dim, bed_kind, mean, deviatoric):
    """The kick's operator is the explicit pair term: Eq. 27's, or the deviatoric one with its part
    along the relative velocity (normal to a free-slip wall)."""
    s = bed_lattice(dim, bed_kind)
    zeros = np.zeros(s.n)
    explicit = np.zeros((s.n, dim))
    momentum(s.n, s.start, s.nbr, s.x, s.v, s.rho, zeros, s.eta, s.gamma_dot, s.mass, s.kind, s.normal,
             s.wall_distance, 1.5, 0.0, 1.0, True, *pair_term_factors(dim, deviatoric), mean, s.k.params, explicit)
    implicit = apply(s, s.v, mean=mean, deviatoric=deviatoric)
    np.testing.assert_allclose(implicit, explicit, rtol=0, atol=1e-12 * np.abs(explicit).max())


@pytest.mark.parametrize("deviatoric", [False, True])
@pytest.mark.parametrize("mean", [MEAN_HARMONIC, MEAN_ARITHMETIC, MEAN_SECANT])
@pytest.mark.parametrize("bed_kind", [WALL, WALL_SLIP])
@pytest.mark.parametrize("dim", [2, 3])
def test_mass_weighted_operator_is_symmetric_and_dissipative(dim, bed_kind, mean, deviatoric):
    s = bed_lattice(dim, bed_kind)
    rng = np.random.default_rng(2)
    moving = (s.kind == MOVING)[:, None]
    p, q = (np.where(moving, rng.normal(size=(s.n, dim)), 0.0) for _ in range(2))
    m = s.mass[:, None]
    pAq, qAp, pAp = (np.sum(a * m * apply(s, b, mean=mean, deviatoric=deviatoric)) for a, b in ((p, q), (q, p), (p, p)))
    assert pAq == pytest.approx(qAp, rel=1e-12)
    assert pAp < 0.0


@pytest.mark.parametrize("deviatoric", [False, True])
@pytest.mark.parametrize("bed_kind", [WALL, WALL_SLIP])
@pytest.mark.parametrize("dim", [2, 3])
def test_corrected_stress_does_the_work_its_strain_rate_dissipates(dim, bed_kind, deviatoric):
    """sum_i m_i w_i . a_i[u] = -sum_i V_i 2 eta_i eps_i[u] : eps_i[w] for two random velocity
    fields on a jittered block with densities 13 % apart over a no-slip or free-slip Morris bed: the
    divergence is the gradient's exact adjoint, so the mass-weighted operator is symmetric and
    never positive (viscous_stress.py); the deviatoric stress likewise with dev(eps[u]) : dev(eps[w])."""
    s = bed_lattice(dim, bed_kind, jitter=0.2)
    B = correction(s)
    rng = np.random.default_rng(3)
    moving = s.kind == MOVING
    u, w = (np.where(moving[:, None], rng.normal(size=(s.n, dim)), 0.0) for _ in range(2))
    eu, ew = (unpacked(strain(s, f, B), dim) for f in (u, w))
    if deviatoric:
        eu, ew = deviator(eu), deviator(ew)
    dissipated = np.sum((s.mass / s.rho * 2 * s.eta)[moving] * np.einsum("iab,iab->i", eu, ew)[moving])
    m = s.mass[:, None]
    wAu, uAw, uAu = (np.sum(a * m * stress_apply(s, b, B, deviatoric)) for a, b in ((w, u), (u, w), (u, u)))
    assert abs(dissipated) > 0.0
    assert wAu == pytest.approx(-dissipated, rel=1e-12)
    assert uAw == pytest.approx(wAu, rel=1e-12)
    assert uAu < 0.0


@pytest.mark.parametrize("dim", [2, 3])
def test_the_deviatoric_stress_has_no_bulk_viscosity(dim):
    """A strain rate that is a uniform expansion c I gives the full stress 2 eta c B and the
    deviatoric stress none; a shear gives both the same (physics/mu_i.py, viscous_stress = deviatoric)."""
    s = bed_lattice(dim, WALL, jitter=0.2)
    B = correction(s)
    moving = s.kind == MOVING
    shear = np.zeros((dim, dim))
    shear[0, -1] = shear[-1, 0] = 1.0  # a flow along x sheared along the last axis
    for e, bulk in ((np.eye(dim), True), (shear, False)):
        eps = np.zeros((s.n, size(dim)))
        for a in range(dim):
            for b in range(a, dim):
                eps[:, component(dim, a, b)] = 3.0 * e[a, b]
        full, dev = (np.zeros((s.n, dim, dim)) for _ in range(2))
        viscous_force_tensor(s.n, s.kind, eps, s.eta, B, False, full)
        viscous_force_tensor(s.n, s.kind, eps, s.eta, B, True, dev)
        assert np.abs(full[moving]).max() > 0.0
        np.testing.assert_allclose(dev[moving], 0.0 if bulk else full[moving], atol=1e-12 * np.abs(full).max())


@pytest.mark.parametrize("dim", [2, 3])
def test_a_uniform_stress_pushes_nothing_next_to_a_wall(dim):
    """A uniform viscous stress on a lattice over a Morris bed gives no force in the layers next to
    a no-slip bed, as in the bulk (the wall partner takes the stress of particle i); a free-slip
    bed balances the normal stresses but not the shear stress, which it cannot carry."""
    shear, normal = (np.zeros((dim, dim)) for _ in range(2))
    shear[0, -1] = shear[-1, 0] = 100.0  # of a flow along x over the bed [Pa]
    normal[0, 0], normal[-1, -1] = 30.0, -50.0
    scale = 100.0 / (1500.0 * DP)  # the acceleration a stress difference of 100 Pa across dp gives
    for bed_kind in (WALL, WALL_SLIP):
        s = bed_lattice(dim, bed_kind)
        s.rho[:] = 1500.0
        s.mass[:] = 1500.0 * DP**dim
        up = s.x[:, -1]
        near = (s.kind == MOVING) & (up < (BED_ROWS + 2) * DP) & (np.abs(s.x[:, 0] - s.x[:, 0].mean()) < 2 * DP)
        for stress, held in ((shear + normal, bed_kind == WALL), (normal, True)):
            a = divergence(s, np.broadcast_to(stress, (s.n, dim, dim)).copy())[near]
            if held:
                np.testing.assert_allclose(a, 0.0, atol=1e-9 * scale)
            else:
                assert np.abs(a[:, 0]).max() > 0.1 * scale
                np.testing.assert_allclose(a[:, 1:], 0.0, atol=1e-9 * scale)


@pytest.mark.parametrize("deviatoric", [False, True])
@pytest.mark.parametrize("bed_kind", [WALL, WALL_SLIP])
@pytest.mark.parametrize("dim", [2, 3])
def test_pair_preconditioner_is_the_diagonal_block(dim, bed_kind, deviatoric):
    """viscous_pairs inverts m_i (I - dt J_i), J_i = d a_i / d u_i probed column by column from the
    operator itself, for Eq. 27's pair term and the deviatoric one, over either bed."""
    s = bed_lattice(dim, bed_kind)
    dt = 1e-3
    _, inverse = pairs(s, deviatoric=deviatoric, dt=dt)
    for i in np.flatnonzero(s.kind == MOVING)[::7]:
        J = np.zeros((dim, dim))
        for a in range(dim):
            u = np.zeros((s.n, dim))
            u[i, a] = 1.0
            J[:, a] = apply(s, u, deviatoric=deviatoric)[i]
        block = s.mass[i] * (np.eye(dim) - dt * J)
        np.testing.assert_allclose(inverse[i] @ block, np.eye(dim), atol=1e-12)


@pytest.mark.parametrize("deviatoric", [False, True])
@pytest.mark.parametrize("dim", [2, 3])
def test_corrected_stress_preconditioner_is_the_diagonal_block(dim, deviatoric):
    """stress_blocks inverts m_i (I - dt J_i) with J_i = d a_i / d u_i probed column by column from
    the divergence itself, of the whole stress or its deviator, on a no-slip bed (it leaves out only
    free-slip wall partners)."""
    s = bed_lattice(dim, WALL, jitter=0.2)
    B = correction(s)
    dt = 1e-4
    inverse = np.zeros((s.n, dim, dim))
    stress_blocks(s.n, s.start, s.nbr, s.x, s.rho, s.eta, B, s.mass, s.kind, s.k.params, deviatoric, dt, inverse)
    for i in np.flatnonzero(s.kind == MOVING)[::7]:
        J = np.zeros((dim, dim))
        for a in range(dim):
            u = np.zeros((s.n, dim))
            u[i, a] = 1.0
            J[:, a] = stress_apply(s, u, B, deviatoric)[i]
        block = s.mass[i] * (np.eye(dim) - dt * J)
        np.testing.assert_allclose(inverse[i] @ block, np.eye(dim), atol=1e-12)


class NoHalo:
    comm = MPI.COMM_SELF

    def refresh(self, particles, names):
        pass


def kick_setup(dim, bed_kind, form):
    """A bed lattice at 1000 times the explicit limit of Eq. 39 and what ImplicitViscosity.kick
    reads of it: (lattice, B, particles, context, scheme, dt) for the viscous ``form``."""
    corrected, deviatoric = "pair" not in form, "deviatoric" in form
    s = bed_lattice(dim, bed_kind, jitter=0.2 if corrected else 0.0)
    dt = 1000.0 * 0.05 * s.rho.min() * s.k.h**2 / s.eta.max()
    B = correction(s)
    pa = SimpleNamespace(n_owned=s.n, dim=dim, v=s.v.copy(), rho=s.rho, eta=s.eta, gamma_dot=s.gamma_dot,
                         mass=s.mass, kind=s.kind, B=B,
                         normal=s.normal, wall_distance=s.wall_distance, viscous_direction=np.zeros((s.n, dim)),
                         viscous_acceleration=np.zeros((s.n, dim)), viscous_acceleration_change=np.zeros((s.n, dim)),
                         viscous_direction_stress=np.zeros((s.n, dim, dim)))
    ctx = SimpleNamespace(particles=pa, start=s.start, nbr=s.nbr, xc=s.x, kernel=s.k, workspace=Workspace(),
                          halo=NoHalo())
    ctx.refresh = lambda names: None
    ctx.correction_matrices = lambda: B
    factor, radial, along = pair_term_factors(dim, deviatoric)
    scheme = SimpleNamespace(corrected=corrected, deviatoric_stress=deviatoric, beta_max=1.5,
                             viscous_factor=factor, radial=radial, along=along, mean=MEAN_SECANT)
    return s, B, pa, ctx, scheme, dt


def kick_error(s, B, scheme, u, b, dt):
    """The RMS over the moving particles of u - dt a_visc[u] - b."""
    a_visc = stress_apply(s, u, B, scheme.deviatoric_stress) if scheme.corrected else \
        apply(s, u, MEAN_SECANT, scheme.deviatoric_stress)
    moving = s.kind == MOVING
    error = (u - dt * a_visc - b)[moving]
    return np.sqrt(np.sum(s.mass[moving, None] * error**2) / s.mass[moving].sum())


@pytest.mark.parametrize("form", ["pair", "deviatoric_pair", "corrected", "deviatoric"])
@pytest.mark.parametrize("bed_kind", [WALL, WALL_SLIP])
@pytest.mark.parametrize("dim", [2, 3])
def test_conjugate_gradients_solve_the_backward_euler_kick(dim, bed_kind, form):
    """At 1000 times the explicit limit of Eq. 39 the kick solves u - dt a_visc[u] = b to the
    tolerance and takes kinetic energy out, never in, with either viscous form, whole or deviatoric."""
    s, B, pa, ctx, scheme, dt = kick_setup(dim, bed_kind, form)
    solver = ImplicitViscosity(scheme, u_ref=1.0)
    solver.history = False  # a run from t = 0 (MuIScheme.start)
    solver.kick(ctx, dt)
    u, b = pa.v, s.v
    moving = s.kind == MOVING
    assert 2 < solver.iterations < 200
    assert kick_error(s, B, scheme, u, b, dt) < 50 * TOLERANCE  # the stop is on the preconditioned residual
    assert np.sum(s.mass[:, None] * u**2) < np.sum(s.mass[:, None] * b**2)
    # the next kick starts from b + dt a_visc of this one: from the same b it is already solved
    first = solver.iterations
    np.testing.assert_allclose(pa.viscous_acceleration[moving], ((u - b) / dt)[moving])
    pa.v = b.copy()
    solver.kick(ctx, dt)
    assert solver.iterations <= 1 < first
    rms = np.sqrt(np.sum(s.mass[moving, None] * (pa.v - u)[moving] ** 2) / s.mass[moving].sum())
    assert rms < 50 * TOLERANCE


@pytest.mark.parametrize("dim", [2, 3])
def test_viscous_tolerance_sets_where_the_kick_stops(dim):
    """The option viscous_tolerance moves the stop of the corrected deviatoric stress's kick: each
    tolerance's solution is within a few times its own RMS residual, and a looser one takes fewer
    iterations; a tolerance outside (0, 1) is refused."""
    iterations = []
    for tolerance in (TOLERANCE, 1e-4):
        s, B, pa, ctx, scheme, dt = kick_setup(dim, WALL, "deviatoric")
        solver = ImplicitViscosity(scheme, u_ref=1.0, tolerance=tolerance)
        solver.history = False
        solver.kick(ctx, dt)
        assert kick_error(s, B, scheme, pa.v, s.v, dt) < 50 * tolerance
        iterations.append(solver.iterations)
    assert 0 < iterations[1] < iterations[0]
    for bad in (0.0, 1.0):
        with pytest.raises(InputError, match="viscous_tolerance"):
            ImplicitViscosity(scheme, u_ref=1.0, tolerance=bad)


@pytest.mark.parametrize("dim", [2, 3])
def test_the_first_guess_extrapolates_the_last_two_kicks(dim):
    """The kick's solution is linear in the kicked velocity b: kicks from b_0, b_1 = b_0 + db and
    b_2 = b_0 + 2 db make a viscous acceleration linear in the kick's count, which the first guess
    extrapolates from the last two, so the third kick starts within a few tolerances of its
    solution (the last two solutions' errors extrapolated) and takes fewer iterations than from
    the last kick's acceleration alone."""
    s = bed_lattice(dim, WALL)
    dt = 1000.0 * 0.05 * s.rho.min() * s.k.h**2 / s.eta.max()
    moving = (s.kind == MOVING)[:, None]
    db = np.where(moving, np.random.default_rng(5).normal(size=(s.n, dim)), 0.0)
    pa = SimpleNamespace(n_owned=s.n, dim=dim, v=None, rho=s.rho, eta=s.eta, gamma_dot=s.gamma_dot, mass=s.mass,
                         kind=s.kind, normal=s.normal, wall_distance=s.wall_distance,
                         viscous_direction=np.zeros((s.n, dim)), viscous_acceleration=np.zeros((s.n, dim)),
                         viscous_acceleration_change=np.zeros((s.n, dim)))
    ctx = SimpleNamespace(particles=pa, start=s.start, nbr=s.nbr, xc=s.x, kernel=s.k, workspace=Workspace(),
                          halo=NoHalo(), refresh=lambda names: None)
    factor, radial, along = pair_term_factors(dim, False)
    scheme = SimpleNamespace(corrected=False, beta_max=1.5, viscous_factor=factor, radial=radial, along=along,
                             mean=MEAN_SECANT)
    iterations = {}
    for extrapolated in (True, False):
        solver = ImplicitViscosity(scheme, u_ref=1.0)
        solver.history = False
        pa.viscous_acceleration[:] = pa.viscous_acceleration_change[:] = 0.0
        for k in range(3):
            if k == 2 and not extrapolated:
                pa.viscous_acceleration_change[:] = 0.0
            pa.v = s.v + k * db
            solver.kick(ctx, dt)
        iterations[extrapolated] = solver.iterations
    assert 4 * iterations[True] < iterations[False]
