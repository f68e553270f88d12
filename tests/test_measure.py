"""The validation measures of mpisph/measure.py on frames and series built by hand, whose answers
are known without the code: a bug in a measure would otherwise pass as, or hide, a solver's."""

import numpy as np
import pytest

from mpisph import measure
from mpisph.case import build_case, load_case_module, resolve_params
from mpisph.kernels import Kernel
from mpisph.particles import MOVING, WALL

DP = 0.01


def lattice(nx, ny, x0=0.0, y0=0.0):
    """Positions (n, 2) of an nx x ny lattice of spacing DP whose first cell starts at (x0, y0)."""
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    return np.stack([x0 + (i.ravel() + 0.5) * DP, y0 + (j.ravel() + 0.5) * DP], axis=1)


def lube_column(dp):
    """The positions of lube_collapse_2d's column (L_0 = 9.72 cm) as the case builds it at ``dp``."""
    module = load_case_module("lube_collapse_2d")
    (body,) = build_case(module, resolve_params(module, {"dp": repr(dp)})).bodies
    return body.x.everything()[0]


def test_semi_axes_and_surge_front_add_half_a_spacing_to_the_outermost_centres():
    """An ellipse x^2/a^2 + y^2/b^2 < 1 filled on a lattice centred on the origin: its outermost
    centres lie within a spacing of a and b, and each measure adds dp/2 to them."""
    g = (np.arange(-60, 60) + 0.5) * DP
    x = np.stack([a.ravel() for a in np.meshgrid(g, g, indexing="ij")], axis=1)
    a, b = 0.5, 0.3
    x = x[(x[:, 0] / a) ** 2 + (x[:, 1] / b) ** 2 < 1.0]
    sa, sb = measure.semi_axes({"x": x}, DP)
    assert sa == pytest.approx(np.abs(x[:, 0]).max() + 0.005, rel=1e-15) and abs(sa - a) <= DP
    assert sb == pytest.approx(np.abs(x[:, 1]).max() + 0.005, rel=1e-15) and abs(sb - b) <= DP
    assert measure.surge_front({"x": lattice(40, 20)}, DP) == pytest.approx(0.4)


def test_front_speed_and_decay_rate_are_least_squares_slopes():
    T = np.linspace(0.0, 4.0, 81)
    z = 1.5 + 2.0 * T + np.where(T < 1.0, 5.0 * T**2, 0.0)  # slope 2 once T >= 1
    assert measure.front_speed(T, z, 1.0, 4.0) == pytest.approx(2.0, rel=1e-12)
    t = np.linspace(0.0, 5.0, 51)
    assert measure.decay_rate(t, 3.0 * np.exp(-1.5791 * t)) == pytest.approx(-1.5791, rel=1e-12)


def test_max_speed_counts_moving_particles_only_and_rest_is_the_last_over_the_largest():
    """A wall particle faster than every moving one (frames read with their walls) is not counted."""
    v = np.array([[3.0, 4.0], [0.0, -2.0], [30.0, 40.0]])
    frame = {"v": v, "kind": np.array([MOVING, MOVING, WALL])}
    assert measure.max_speed(frame) == 5.0
    assert measure.final_over_peak([0.0, 5.0, 2.0, 0.04]) == pytest.approx(0.008, rel=1e-15)
    frames = ({"v": scale * v, "kind": frame["kind"]} for scale in (1.0, 0.1))
    assert measure.final_over_peak_speed(frames) == pytest.approx(0.1, rel=1e-15)


def test_dam_break_fronts_scale_by_the_column_width_and_skip_the_walls():
    """A column of width L = 2 m (dp = 0.1) whose fluid reaches x = 1 m beside a wall at x = 3 m:
    Z = (1 + dp/2) / L, and T = t sqrt(2 g / L)."""
    x = np.array([[0.5, 0.1], [1.0, 0.1], [3.0, 0.1]])
    kind = np.array([MOVING, MOVING, WALL])
    frames = [{"t": t, "x": x, "kind": kind, "params": {"L": 2.0, "g": 9.81, "dp": 0.1}} for t in (0.0, 0.5)]
    T, Z = measure.dam_break_fronts(frames)
    np.testing.assert_allclose(T, [0.0, 0.5 * np.sqrt(9.81)], rtol=1e-15)
    np.testing.assert_allclose(Z, [0.525, 0.525], rtol=1e-15)


def test_time_offset_recovers_a_known_shift():
    """A front z(T) = T^2 and reference points taken from it 0.25 later in T: the offset that aligns
    them is -0.25, to the search step."""
    T = np.linspace(0.0, 4.0, 401)
    T_ref = np.array([1.2, 2.0, 2.5, 3.3])
    z_ref = (T_ref - 0.25) ** 2
    assert measure.time_offset(T, T**2, T_ref, z_ref) == pytest.approx(-0.25, abs=0.001)


def test_line_average_is_exact_for_a_linear_field_on_a_symmetric_lattice():
    """v_x = 2 + 3 x - y on a lattice symmetric about the points (corners of its cells): the kernel
    weights are symmetric about each point, so the linear part averages to its value there; outside
    the support: nan."""
    x = lattice(40, 40)
    v = np.zeros_like(x)
    v[:, 0] = 2.0 + 3.0 * x[:, 0] - x[:, 1]
    kernel = Kernel("wendland_c2", 1.3 * DP, 2)
    points = np.array([[0.2, 0.2], [0.15, 0.25], [1.0, 1.0]])  # cell corners, then far away
    got = measure.line_average({"x": x, "v": v}, points, 0, kernel)
    np.testing.assert_allclose(got[:2], 2.0 + 3.0 * points[:2, 0] - points[:2, 1], rtol=1e-12)
    assert np.isnan(got[2])


def test_nearest_value_averages_the_nearest_particles():
    x = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [5.0, 5.0]])
    p = np.array([1.0, 2.0, 3.0, 4.0, 100.0])
    assert measure.nearest_value({"x": x, "p": p}, "p", (0.0, 0.0)) == pytest.approx(2.5)
    assert measure.nearest_value({"x": x, "p": p}, "p", (5.0, 5.0), count=1) == pytest.approx(100.0)


def test_layer_means_go_layer_by_layer_from_the_bed():
    x = lattice(4, 3)
    mean_y, mean_v = measure.layer_means({"x": x}, DP, values=x[:, 1] * 10.0)
    np.testing.assert_allclose(mean_y, [0.005, 0.015, 0.025])
    np.testing.assert_allclose(mean_v, [0.05, 0.15, 0.25])


def test_runout_and_profile_of_a_heap_with_a_grain_ahead():
    """A staircase heap of 10 lattice columns (10 particles high down to 1) and a grain in the fourth
    bin after its last (three empty between). The bins are dp wide from the leftmost particle, so
    each column starts a bin (its first frame's lattice, which round-off had put in the bin before);
    the connected deposit ends a bin after its last column's, the grain lies beyond it, and the
    profile is the staircase."""
    x = np.concatenate([lattice(1, 10 - c, x0=c * DP) for c in range(10)] + [lattice(1, 1, x0=13 * DP)])
    frame = {"x": x}
    assert measure.runout(frame, DP) == pytest.approx(0.105)
    centres, top = measure.surface_profile(frame, DP)
    np.testing.assert_allclose(centres, 0.005 + (np.r_[np.arange(10), 13] + 0.5) * DP)
    np.testing.assert_allclose(top, np.r_[(10 - np.arange(10)) * DP, DP])
    assert measure.front_position(frame, DP) == pytest.approx(0.095)
    np.testing.assert_array_equal(measure.beyond_the_edge(frame, DP), x[:, 0] > 0.1)
    assert measure.farthest_edge(frame, DP) == pytest.approx(0.14)
    assert measure.deposit_height(frame, DP, x_max=0.05) == pytest.approx(0.10)
    mirrored = {"x": np.c_[0.1 - x[:, 0], x[:, 1]]}  # the tallest column on the right, at x = 0.095
    assert measure.deposit_height(mirrored, DP, x_max=0.05) == pytest.approx(0.05)  # 5 high at x = 0.045


def test_the_front_bin_of_a_lattice_holds_its_last_column():
    """The connected deposit's outermost bin of a first frame holds its last lattice column however
    round-off places it (lube_collapse_2d's column at spacings where it had fallen out of that bin)."""
    assert measure.front_position({"x": lattice(2, 3)}, DP) == pytest.approx(0.015)
    for n in (87, 93, 160):
        dp = 0.0972 / n
        x = lube_column(dp)
        assert measure.front_position({"x": x}, dp) == pytest.approx(0.0972 - 0.5 * dp, rel=1e-9)
        assert not measure.beyond_the_edge({"x": x}, dp).any()


def test_runout_of_a_cases_first_frame_is_its_length_and_a_half_spacing():
    """lube_collapse_2d's column as the case builds it (L_0 = 9.72 cm, dp = L_0 / 20): the runout of
    its first frame is L_0 + dp / 2 (the last column's bin ends a spacing beyond its centre)."""
    assert measure.runout({"x": lube_column(0.00486)}, 0.00486) == pytest.approx(0.0972 + 0.00243, rel=1e-9)


def test_radial_runout_of_a_disc_with_a_detached_ring():
    """A disc of radius R filled on a lattice, and a ring of grains at 1.5 R: every sector's connected
    deposit ends within a spacing of R, the ring lies beyond the edge."""
    g = (np.arange(-80, 80) + 0.5) * DP
    x = np.stack([a.ravel() for a in np.meshgrid(g, g, [0.005], indexing="ij")], axis=1)
    R = 0.5
    disc = x[np.hypot(x[:, 0], x[:, 1]) < R]
    angle = np.linspace(0.0, 2 * np.pi, 64, endpoint=False)
    ring = np.stack([1.5 * R * np.cos(angle), 1.5 * R * np.sin(angle), np.full(64, 0.005)], axis=1)
    frame = {"x": np.concatenate([disc, ring])}
    assert abs(measure.radial_runout(frame, DP) - R) <= DP
    assert abs(measure.front_position(frame, DP, radial=True) - R) <= DP
    np.testing.assert_array_equal(measure.beyond_the_edge(frame, DP, radial=True)[len(disc):], True)
    assert not measure.beyond_the_edge(frame, DP, radial=True)[:len(disc)].any()


def test_zero_crossings_and_periods_of_a_sine():
    t = np.linspace(0.0, 3.0, 3001)
    y = np.sin(2 * np.pi * t / 0.8)  # starts at 0 moving up; period 0.8
    np.testing.assert_allclose(measure.zero_crossings(t, y, rising=False), [0.4, 1.2, 2.0, 2.8], atol=1e-6)
    np.testing.assert_allclose(measure.period_ends(t, y), [0.8, 1.6, 2.4], atol=1e-6)
    assert measure.first_period(t, y) == pytest.approx(0.8, abs=1e-6)
    assert np.isnan(measure.first_period(t[:500], y[:500]))


def test_crest_crack_is_the_farthest_sunk_crest_particle_behind_the_face():
    first = {"x": lattice(20, 10)}
    last = {"x": first["x"].copy()}
    top = first["x"][:, 1] > 0.09
    sinks = top & (first["x"][:, 0] > 0.125)  # the top layer's particles from x = 0.135 on sink
    last["x"][sinks, 1] -= 0.02
    assert measure.crest_crack(first, last, DP, face=0.2, drop=0.01) == pytest.approx(0.2 - 0.135)
    assert measure.crest_crack(first, first, DP, face=0.2, drop=0.01) == 0.0


def test_thrust_ratio_of_a_stress_state_at_rest():
    """sigma_xx = K0 sigma_yy everywhere: the ratio is K0, whatever the volumes."""
    n = 50
    rng = np.random.default_rng(3)
    stress = np.zeros((n, 6))
    stress[:, 1] = -rng.uniform(1e3, 1e4, n)
    stress[:, 0] = 0.4 * stress[:, 1]
    frame = {"x": np.zeros((n, 2)), "stress": stress, "mass": rng.uniform(1, 2, n), "rho": np.full(n, 2000.0)}
    assert measure.thrust_ratio(frame) == pytest.approx(0.4, rel=1e-12)


def test_jostle_pressure_is_nil_for_a_shear_and_follows_a_checkerboards_square():
    """On a 30 x 30 lattice, away from its edges: a linear shear v_x = 5 y averages to each particle's
    own velocity (no jostle, to round-off); a checkerboard v_y = +-a on top of it departs from its
    kernel mean by a (1 - m), m = sum W s_j / sum W over the particle and its neighbours, summed here
    offset by offset, so rho |v'|^2 / 2 = rho a^2 (1 - m)^2 / 2."""
    x = lattice(30, 30)
    ij = np.rint(x / DP - 0.5).astype(int)
    sign = np.where((ij[:, 0] + ij[:, 1]) % 2 == 0, 1.0, -1.0)
    kernel = Kernel("wendland_c2", 1.3 * DP, 2)
    inner = np.all((ij >= 4) & (ij <= 25), axis=1)
    a = 0.02
    frame = {"x": x, "v": np.stack([5.0 * x[:, 1], a * sign], axis=1), "mass": np.full(len(x), 2.0 * DP * DP),
             "rho": np.full(len(x), 2.0), "gid": np.arange(len(x)), "kind": np.full(len(x), MOVING, np.int8)}
    offsets = np.array([(p, q) for p in range(-3, 4) for q in range(-3, 4)])
    w = kernel.value(np.hypot(*offsets.T) * DP)
    m = np.sum(w * np.where(offsets.sum(axis=1) % 2 == 0, 1.0, -1.0)) / np.sum(w)
    got = measure.jostle_pressure(frame, kernel)[inner]
    np.testing.assert_allclose(got, 2.0 * a * a * (1.0 - m) ** 2 / 2.0, rtol=1e-10)
    frame["v"][:, 1] = 0.0
    assert np.max(measure.jostle_pressure(frame, kernel)[inner]) < 1e-24


def test_a_cuts_height_adds_half_a_spacing_to_its_top_centre():
    """A 4 x 6 block of the lattice on the floor: its top centres at 5.5 dp, its height 6 dp."""
    assert measure.cut_height({"x": lattice(4, 6), "params": {"dp": DP}}) == pytest.approx(6 * DP, rel=1e-12)


def test_the_displacement_percentile_is_that_of_each_particles_own_displacement():
    """Particle k of 1000 moves k mm up: the 99th percentile of 0, 1, ..., 999 mm, whatever the
    particles' places."""
    x = np.stack([np.arange(1000.0), np.zeros(1000)], axis=1)
    moved = x.copy()
    moved[:, 1] = np.linspace(0.0, 0.999, 1000)
    share = measure.displacement_percentile({"x": x}, {"x": moved})
    assert share == np.percentile(np.linspace(0.0, 0.999, 1000), 99.0)
    assert abs(share - 0.989) < 1e-3


def test_the_kinetic_energy_peak_and_its_time():
    diag = {"t": np.array([0.0, 0.1, 0.5, 1.0]), "kinetic_energy": np.array([0.0, 5.0, 7.5, 0.2])}
    assert measure.kinetic_energy_peak(diag) == (7.5, 0.5)
