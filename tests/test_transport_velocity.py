"""The UTVF shift (mpisph/stabilisers/transport_velocity.py, 000_ Eqs. 30-37) repeated alone on a
block of particles, its free-surface classes and B recomputed before every shift as in a run.

- The limited shift of 001_ is TVF with the limiter, on inner particles (fluids and solids alike).
- A sheet two layers thick is all splashed: kept in place as printed, regularised along itself with
  utvf_splashed=shifted (the authors' code).
- A perfect lattice is regular, so the shift should leave it where it is: in 2D Eq. 37 as printed
  does, in 3D only with utvf_edge_neighbours=kept (the face particles beside an edge kept in place),
  with either near-surface normal.
- With that option a face particle away from the edges is still shifted along the face.
- From a jittered block, the kept rule regularises; as printed the 3D block's faces crowd into
  its edges.
- On a jittered block a near-surface particle's own normal B g is far from the face's normal and
  the mean of its outermost neighbours' normals is close to it; projected on the latter, the kept
  rule regularises the block further.
"""

import numpy as np
import pytest

from lattice import lattice
from mpisph import surface
from mpisph.correction import correction_matrix
from mpisph.neighbours import neighbour_lists
from mpisph.stabilisers.transport_velocity import (ALPHA, consistency_shift, kernel_gradient_sum,
                                                   outermost_mean_normal, outermost_normals)
from mpisph.tensors import size, times_vector

DP = 0.01
RHO = 1000.0


def configuration(x, k):
    """Neighbour lists, div r, free-surface classes, B and the outermost normals of a block of
    moving particles (no walls), with its kind, mass and density."""
    n, dim = x.shape
    kind = np.zeros(n, np.int8)
    mass, rho = np.full(n, RHO * DP**dim), np.full(n, RHO)
    start, nbr = neighbour_lists(x, np.arange(n), kind, n, k.support, x.min(axis=0) - DP)
    div_r, cls, B, normals = np.empty(n), np.empty(n, np.int8), np.empty((n, size(dim))), np.empty((n, dim))
    surface.position_divergence(n, start, nbr, x, mass, rho, kind, k.params, div_r)
    surface.surface_classes(n, start, nbr, x, kind, div_r, surface.SURFACE_THRESHOLD * dim, k.h, cls)
    correction_matrix(n, start, nbr, x, mass, rho, kind, k.params, B)
    outermost_normals(n, start, nbr, x, mass, rho, kind, div_r, B, k.params, normals)
    return start, nbr, kind, mass, rho, div_r, cls, B, normals


def shifted(x, k, steps, keep_edge_neighbours, outermost_normal=False, shift_splashed=False):
    """x after ``steps`` UTVF shifts; ``outermost_normal``: near-surface particles projected on the
    outermost particles' normals; ``shift_splashed``: splashed particles shifted too."""
    x = x.copy()
    n, dim = x.shape
    for _ in range(steps):
        start, nbr, kind, mass, rho, div_r, cls, B, normals = configuration(x, k)
        before = x.copy()
        consistency_shift(n, start, nbr, before, x, mass, rho, kind, cls, div_r, B, True, keep_edge_neighbours,
                          k.params, normals if outermost_normal else np.empty((0, dim)), shift_splashed)
    return x


def closest_pairs(x):
    """Each particle's distance to its nearest other particle."""
    d = np.linalg.norm(x[:, None, :] - x[None, :, :], axis=2)
    np.fill_diagonal(d, np.inf)
    return d.min(axis=1)


@pytest.mark.parametrize("outermost_normal", [False, True])
@pytest.mark.parametrize("dim, n", [(2, 16), (3, 10)])
def test_a_perfect_lattice_block_stays_in_place(dim, n, outermost_normal):
    x, _, _, _, k, _ = lattice(dim, 1.3, n=n, dp=DP)
    assert np.abs(shifted(x, k, 100, True, outermost_normal) - x).max() < 1e-9 * DP


def test_as_printed_the_faces_of_a_3d_block_crowd_into_its_edges():
    x, _, _, _, k, _ = lattice(3, 1.3, n=10, dp=DP)
    once = shifted(x, k, 1, False) - x
    moved = np.linalg.norm(once, axis=1) > 1e-6 * DP
    outer = (np.isclose(x, x.min()) | np.isclose(x, x.max())).sum(axis=1)  # 1 on a face, 2 on an edge
    assert moved.any() and np.all(outer[moved] == 1)  # face particles, ...
    lo, hi = x.min() + DP, x.max() - DP  # ... each one row from an edge, moving towards it
    beside = (np.isclose(x, lo) | np.isclose(x, hi)).sum(axis=1) >= 1
    assert np.all(beside[moved])
    assert 0.005 * DP < np.linalg.norm(once, axis=1).max() < 0.01 * DP  # 0.0067 dp
    assert closest_pairs(shifted(x, k, 200, False)).min() < 0.9 * DP


def test_a_displaced_face_particle_away_from_the_edges_is_still_shifted_back():
    x, _, _, _, k, _ = lattice(3, 1.3, n=10, dp=DP)
    top = np.isclose(x[:, 2], x[:, 2].max())
    i = int(np.argmin(np.where(top, np.sum((x[:, :2] - x[:, :2].mean(axis=0)) ** 2, axis=1), np.inf)))
    x[i, 0] += 0.2 * DP
    dr = shifted(x, k, 1, True)[i] - x[i]
    assert dr[0] < -0.01 * DP  # back along the face
    kind, mass, rho = np.zeros(len(x), np.int8), np.full(len(x), RHO * DP**3), np.full(len(x), RHO)
    start, nbr = neighbour_lists(x, np.arange(len(x)), kind, len(x), k.support, x.min(axis=0) - DP)
    g = kernel_gradient_sum(i, start, nbr, x, mass, rho, k.params)
    unprojected = -2.0 * ALPHA * k.h**2 * g[2]  # Eq. 30 would push it off the face, upwards
    assert unprojected > 0.1 * DP and abs(dr[2]) < 0.05 * unprojected


def test_from_a_jittered_3d_block_the_kept_rule_regularises_and_the_printed_one_clusters():
    x, _, _, _, k, _ = lattice(3, 1.3, n=10, dp=DP)
    x = x + np.random.default_rng(1).uniform(-0.3, 0.3, x.shape) * DP
    clustered = lambda y: np.mean(closest_pairs(y) < 0.5 * DP)  # noqa: E731  (instability.py's measure)
    start = clustered(x)
    assert clustered(shifted(x, k, 200, True)) < start < clustered(shifted(x, k, 200, False))


def angle_to_vertical(v):
    """The angle in degrees between the line of v and the z axis."""
    c = abs(v[2]) / np.linalg.norm(v)
    return np.degrees(np.arccos(min(c, 1.0)))


def test_on_a_jittered_block_the_outermost_normals_find_the_face_and_the_own_one_does_not():
    """The near-surface layer under the top face, 3 or more rows from its edges, of a 12^3 block
    jittered by 0.1 dp: the truncation signal h |g| is 0.035 there on the lattice, below the jitter's."""
    x, _, _, _, k, _ = lattice(3, 1.3, n=12, dp=DP)
    inside = np.all((x[:, :2] > x.min() + 2.5 * DP) & (x[:, :2] < x.max() - 2.5 * DP), axis=1)
    layer = np.where(inside & np.isclose(x[:, 2], x[:, 2].max() - DP))[0]
    x = x + np.random.default_rng(1).uniform(-0.1, 0.1, x.shape) * DP
    start, nbr, kind, mass, rho, div_r, cls, B, normals = configuration(x, k)
    assert np.all(cls[layer] == surface.NEAR_SURFACE)
    own = [angle_to_vertical(times_vector(B, i, 3, *kernel_gradient_sum(i, start, nbr, x, mass, rho, k.params)))
           for i in layer]
    mean = [angle_to_vertical(outermost_mean_normal(i, start, nbr, x, mass, rho, kind, div_r, normals, k.params))
            for i in layer]
    assert np.mean(own) > 30.0 and np.mean(mean) < 5.0  # 52 and 2.2 degrees


def test_from_a_jittered_3d_block_the_outermost_normals_regularise_further():
    x, _, _, _, k, _ = lattice(3, 1.3, n=12, dp=DP)
    x = x + np.random.default_rng(1).uniform(-0.3, 0.3, x.shape) * DP
    clustered = lambda y: np.mean(closest_pairs(y) < 0.5 * DP)  # noqa: E731  (instability.py's measure)
    own, outermost = clustered(shifted(x, k, 200, True)), clustered(shifted(x, k, 200, True, True))
    assert outermost <= 0.01 and outermost < own


@pytest.mark.parametrize("dim, n", [(2, 16), (3, 10)])
def test_the_limited_shift_is_tvf_with_the_limiter_on_inner_particles(dim, n):
    """001_ Eq. 16 and 000_ Eq. 30 are one form: on a jittered block, where the limiter is 1
    (C h^2 |2 g|^2 >= 1), the limited shift of an inner particle is TVF's to round-off, and the
    limiter scales it by beta where it is below 1; free-surface particles, whose g is the cut
    support's, are left in place by both. On the perfect lattice (h^2 |2 g|^2 under 5e-4 inside)
    the limited shift moves nothing."""
    from mpisph.stabilisers.transport_velocity import LIMITER_C, LIMITER_THRESHOLD, limited_shift

    x, _, _, _, k, _ = lattice(dim, 1.3, n=n, dp=DP)
    start, nbr, kind, mass, rho, div_r, cls, B, _ = configuration(x, k)
    still = x.copy()
    limited_shift(len(x), start, nbr, x, still, mass, rho, kind, cls, k.params)
    assert np.array_equal(still, x)
    x = x + np.random.default_rng(2).uniform(-0.1, 0.1, x.shape) * DP
    start, nbr, kind, mass, rho, div_r, cls, B, _ = configuration(x, k)
    tvf, limited = x.copy(), x.copy()
    consistency_shift(len(x), start, nbr, x, tvf, mass, rho, kind, cls, div_r, B, False, False, k.params,
                      np.empty((0, dim)))
    limited_shift(len(x), start, nbr, x, limited, mass, rho, kind, cls, k.params)
    inner = cls == surface.INNER
    assert inner.any() and (~inner).any()
    np.testing.assert_array_equal(limited[~inner], x[~inner])
    np.testing.assert_array_equal(tvf[~inner], x[~inner])
    g = np.array([kernel_gradient_sum(i, start, nbr, x, mass, rho, k.params)[:dim] for i in range(len(x))])
    norm2 = k.h**2 * np.sum((2.0 * g) ** 2, axis=1)
    beta = np.where(norm2 > LIMITER_THRESHOLD, np.minimum(LIMITER_C * norm2, 1.0), 0.0)
    full = inner & (beta == 1.0)
    assert full.sum() > 0.5 * inner.sum() and (inner & (beta < 1.0)).any()
    # atol: positions differenced, the ulp of x
    np.testing.assert_allclose(limited[full] - x[full], tvf[full] - x[full], rtol=1e-12, atol=1e-14 * DP)
    np.testing.assert_allclose(limited[inner] - x[inner], beta[inner, None] * (tvf[inner] - x[inner]),
                               rtol=1e-12, atol=1e-14 * DP)  # positions differenced: ulp of x


def test_a_sheet_two_layers_thick_is_splashed_and_shifted_along_itself_only_on_request():
    """Every particle of a 12 x 12 x 2 sheet is splashed (outermost, no near-surface neighbour within
    h), most with div r >= 0.6 d. As 000_'s text has it (utvf_splashed=kept) UTVF leaves the sheet
    jittered as it is; as the authors' code does (shifted) it regularises it along its plane: its
    clustered pairs open up while no particle leaves its layer by more than a tenth of dp."""
    x, _, _, _, k, _ = lattice(3, 1.3, n=12, dp=DP)
    sheet = x[x[:, 2] < 2 * DP]
    jitter = np.random.default_rng(3).uniform(-0.3, 0.3, sheet.shape) * DP
    jitter[:, 2] = 0.0
    sheet = sheet + jitter
    cls = configuration(sheet, k)[6]
    assert np.all(cls == surface.SPLASHED)
    np.testing.assert_array_equal(shifted(sheet, k, 50, False), sheet)
    regular = shifted(sheet, k, 50, False, shift_splashed=True)
    assert np.abs(regular[:, 2] - sheet[:, 2]).max() < 0.1 * DP  # B g of a disordered sheet is near its normal
    clustered = lambda y: np.mean(closest_pairs(y) < 0.5 * DP)  # noqa: E731  (instability.py's measure)
    assert clustered(sheet) > 0.01 and clustered(regular) == 0.0
    assert closest_pairs(regular).min() > closest_pairs(sheet).min() + 0.05 * DP
