"""Particle sources (mpisph/sources.py, lattice.py): a slab of a source is exactly the source's
particles in that slab, whatever the cuts, so ranks that each build only their own slab together
build the case."""

from pathlib import Path

import numpy as np
import pytest

from mpisph.case import build_case, load_case_module, resolve_params
from mpisph.geometry import block, box, box_walls, walls_around
from mpisph.lattice import Frame, Lattice
from mpisph.sources import ArrayPoints


def slabs(source, axis, cuts):
    """(indices, positions, normals or None) of ``source`` gathered from its slabs between ``cuts``."""
    edges = [-np.inf, *cuts, np.inf]
    parts = [source.window(axis, a, b) for a, b in zip(edges[:-1], edges[1:])]
    index = np.concatenate([p[0] for p in parts])
    order = np.argsort(index, kind="stable")
    x = np.concatenate([p[1] for p in parts])[order]
    normal = None if parts[0][2] is None else np.concatenate([p[2] for p in parts])[order]
    return index[order], x, normal


def assert_slabs_make_the_whole(source, axis, n_cuts=5, seed=0):
    whole_index, whole_x, whole_n = source.window(axis, -np.inf, np.inf)
    assert np.all(np.diff(whole_index) > 0) and (len(whole_index) == 0 or whole_index[-1] < source.size)
    cuts = np.sort(np.random.default_rng(seed).uniform(whole_x[:, axis].min(), whole_x[:, axis].max(), n_cuts))
    index, x, normal = slabs(source, axis, cuts)
    assert np.array_equal(index, whole_index) and np.array_equal(x, whole_x)
    if whole_n is not None:
        assert np.array_equal(normal, whole_n)
    return whole_x


@pytest.mark.parametrize("axis", [0, 1, 2])
def test_a_tilted_lattice_cut_into_slabs_along_any_axis_is_the_lattice(axis):
    c, s = np.cos(0.7), np.sin(0.7)
    frame = Frame(origin=(0.3, -0.2, 0.1), axes=((c, 0.0, -s), (0.0, 1.0, 0.0), (s, 0.0, c)))
    lattice = Lattice((-3, 0, 2), (9, 5, 11), 0.1, frame)
    x = assert_slabs_make_the_whole(ArrayPoints(lattice.points(np.arange(lattice.size))), axis)
    index, y, _ = slabs(ArrayPoints(x), axis, [0.05, 0.2])
    assert np.array_equal(y, x)
    whole = lattice.window(axis, -np.inf, np.inf)
    assert np.array_equal(whole, np.arange(lattice.size))
    tuples = np.column_stack(np.unravel_index(np.arange(lattice.size), lattice.shape)) + lattice.first
    hollow = ((-1, 4), (1, 3), (4, 11))  # reaching the last index along the third axis
    in_hollow = np.all([(tuples[:, a] >= h[0]) & (tuples[:, a] < h[1]) for a, h in enumerate(hollow)], axis=0)
    assert 0 < in_hollow.sum() < lattice.size
    for lo, hi in [(-0.1, 0.3), (0.25, 0.25), (5.0, 6.0), (-np.inf, np.inf)]:
        inside = (x[:, axis] >= lo) & (x[:, axis] < hi)
        assert np.array_equal(lattice.window(axis, lo, hi), np.nonzero(inside)[0])
        assert np.array_equal(lattice.window(axis, lo, hi, hollow=hollow), np.nonzero(inside & ~in_hollow)[0])


def test_the_block_and_walls_around_it_are_box_and_box_walls_in_any_slabs():
    lo, hi, dp = (0.0, 0.0, 0.0), (1.0, 0.6, 0.8), 0.1
    x = assert_slabs_make_the_whole(block(lo, hi, dp), 0)
    assert np.array_equal(x, box(lo, hi, dp))
    walls = walls_around(lo, hi, dp, 3, open_sides=("+z",))
    for axis in range(3):
        x = assert_slabs_make_the_whole(walls, axis)
    ref_x, ref_n = box_walls(lo, hi, dp, 3, open_sides=("+z",))
    x, n = walls.everything()
    assert np.array_equal(x, ref_x) and np.array_equal(n, ref_n)
    assert walls.estimate == len(x) and walls.size > len(x)


def test_the_flumes_soil_and_walls_in_any_slabs_are_the_whole():
    """The STL fill on the slope's lattice and the five wall parts, whose joints depend on earlier
    parts' particles: each part's slabs together are the part."""
    module = load_case_module("flume_3d")
    case = build_case(module, resolve_params(module, {"dp": "0.1"}))
    counts = []
    for source in case.sources:
        for axis in (0, 2):
            x = assert_slabs_make_the_whole(source, axis, seed=axis)
        counts.append(len(x))
    estimate = sum(source.estimate for source in case.sources)  # what the memory check takes
    assert 0.8 * sum(counts) < estimate < 1.25 * sum(counts)


def test_a_body_given_by_a_function_of_position_and_probes_in_a_lattice():
    module = load_case_module("cube_failure_3d")
    case = build_case(module, resolve_params(module, {"dp": "0.25"}))
    soil = case.bodies[0]
    index, x, _ = soil.x.window(0, 0.0, 0.5)
    stress = soil.stress(x)
    assert np.allclose(stress[:, 2, 2], -case.material.rho0 * 9.8 * (2.0 - x[:, 2]))  # the top at z = 2 m
    assert np.array_equal(soil.x.position(index[3]), x[3])
    assert case._initial_position(int(index[3])).tolist() == x[3].tolist()


@pytest.mark.parametrize("hi", [(1.03, 0.67), (1.03, 0.66, 0.85)])
def test_walls_around_a_box_not_whole_spacings_start_half_a_spacing_behind_every_side(hi):
    """Every wall particle of a box whose sides are not whole spacings lies (k + 1/2) dp behind the
    box, k < layers, with a unit normal; the far sides' layers hold as many particles as the near
    sides'; any slabs of the walls make the whole."""
    dp, layers = 0.1, 3
    lo = (0.0,) * len(hi)
    walls = walls_around(lo, hi, dp, layers, open_sides=(f"+{'xyz'[len(hi) - 1]}",))
    for axis in range(len(hi)):
        assert_slabs_make_the_whole(walls, axis, seed=axis)
    x, normal = walls.everything()
    assert len(x) == walls.estimate and np.all(np.isfinite(normal))
    assert np.allclose(np.linalg.norm(normal, axis=1), 1.0)
    behind = np.abs(x - np.clip(x, lo, hi)) / dp  # along each axis: 0 or k + 1/2
    layer = np.where(behind > 0.0, behind - 0.5, 0.0)
    assert np.allclose(layer, np.round(layer), atol=1e-9) and layer.min() > -1e-9 and layer.max() < layers
    assert np.all(behind.max(axis=1) > 0.49)
    for a in range(len(hi) - 1):
        near, far = np.sum(x[:, a] < lo[a]), np.sum(x[:, a] > hi[a])
        assert near == far > 0
        assert np.isclose(x[:, a].max(), hi[a] + (layers - 0.5) * dp)


@pytest.mark.parametrize("hi", [(1.056, 0.67), (1.03, 0.66, 0.85)])
def test_walls_around_a_box_not_whole_spacings_leave_no_gap_at_the_far_corners(hi):
    """Along every row of wall particles, across the box and on round the far corner, neighbours
    stand between dp and dp (1 + excess / (n dp)) apart: the layers across a side spread over it,
    where a row stopping a spacing short of the far side's layers left a gap of dp plus the excess
    (1.56 dp here), through which soil leaked into the floor."""
    dp, layers = 0.1, 3
    lo = (0.0,) * len(hi)
    x, _ = walls_around(lo, hi, dp, layers, open_sides=(f"+{'xyz'[len(hi) - 1]}",)).everything()
    counts = [int(np.floor(b / dp + 1e-9)) for b in hi]
    widest = max(1.0 + (b - n * dp) / (n * dp) for b, n in zip(hi, counts)) * dp
    floor = x[x[:, -1] < 0.0]  # below the box: rows along each other axis
    for a in range(len(hi) - 1):
        rest = [b for b in range(len(hi)) if b != a]
        rows = {}
        for key, value in zip(map(tuple, np.round(floor[:, rest] / dp, 6)), floor[:, a]):
            rows.setdefault(key, []).append(value)
        gaps = np.concatenate([np.diff(np.sort(v)) for v in rows.values()])
        assert gaps.min() > dp * (1 - 1e-9) and gaps.max() < widest * (1 + 1e-9)


def test_a_soil_block_side_that_is_not_whole_spacings_is_warned_and_its_tank_is_not():
    """cube_failure_3d's 5 m floor at dp = 0.08 m is 62.5 spacings: no warning, its walls start dp/2
    outside every side. A 2.1 m cube at 0.08 m is 26.25 spacings: the fill falls short, warned."""
    module = load_case_module("cube_failure_3d")
    case = build_case(module, resolve_params(module, {"dp": "0.08"}))
    assert case.warnings == []
    tank = case.walls[0]
    x, normal = tank.x.everything()
    floor = x[np.all(np.abs(x[:, :2]) < 2.5, axis=1)]
    assert np.all(np.isfinite(normal)) and np.allclose(x[:, :2].max(axis=0), -x[:, :2].min(axis=0))
    assert np.allclose(np.unique(np.round(tank.distance(floor) / 0.08, 9)), [0.5, 1.5, 2.5])
    odd = build_case(module, resolve_params(module, {"dp": "0.08", "edge": "2.1"}))
    assert [w.split(" =")[0] for w in odd.warnings] == [f"the soil cube's {a} side" for a in "xyz"]

def test_probes_by_id_are_checked_and_probes_by_position_take_the_nearest_body_particle():
    """A probe id in a gap of a lattice fill (where ``keep`` put no particle) or beyond the bodies
    is refused in one line, where it recorded minus the gap's position as a displacement or ended
    in a KeyError; a probe given as a position takes the nearest body particle's id."""
    from mpisph.case import Body, Case
    from mpisph.errors import InputError
    from mpisph.materials import Fluid
    from mpisph.sources import LatticePoints

    dp = 0.1
    wedge = LatticePoints(Lattice((0, 0), (10, 10), dp, Frame(origin=(0.0, 0.0))),
                          keep=lambda x: x[:, 0] + x[:, 1] < 1.0)
    array = ArrayPoints(np.array([[2.05, 0.05], [2.15, 0.05]]))

    def case(probes):
        return Case(dim=2, domain=((-1.0, -1.0), (3.0, 3.0)), dp=dp, material=Fluid(rho0=1000.0, c0=10.0),
                    scheme="riemann_fluid", bodies=[Body("wedge", wedge), Body("pair", array)], probes=probes)

    gap = int(np.ravel_multi_index((9, 9), (10, 10)))  # (0.95, 0.95): outside the wedge
    assert not wedge.holds(gap) and wedge.holds(0)
    for gid in (gap, 102, -1):
        with pytest.raises(InputError, match="is no body particle's"):
            case({"p": gid})
    made = case({"corner": 0, "second": 101, "near": (0.52, 0.33), "right": (2.16, 0.0)})
    assert made.probes == {"corner": 0, "second": 101, "near": int(np.ravel_multi_index((5, 3), (10, 10))),
                           "right": 101}
    assert np.allclose(made.probe_origins["near"], [0.55, 0.35])
    assert np.allclose(made.probe_origins["right"], [2.15, 0.05])
    with pytest.raises(InputError, match="no body particle within 2 dp"):
        case({"far": (2.0, 2.5)})
    with pytest.raises(InputError, match="takes 2 coordinates"):
        case({"flat": (0.1, 0.1, 0.1)})


def test_a_parameter_set_where_it_does_nothing_is_warned():
    """The classic scheme's artificial viscosity and Morris's chi_max set for the Riemann scheme,
    the Riemann limiter for the classic one and a UTVF option without UTVF each build with a warning
    (a geotechnical user's --set av_alpha=5 chi_max=3 changed nothing, silently); set where they act,
    or left at their defaults, they are not warned of."""
    module = load_case_module("cohesive_failure_2d")

    def idle(**overrides):
        case = build_case(module, resolve_params(module, {"dp": "0.2", **overrides}))
        return [w for w in case.warnings if "does nothing" in w]

    assert idle(av_alpha="5", chi_max="3") == [
        "av_alpha = 5 does nothing with scheme = riemann_granular: it acts only with scheme = classic_granular",
        "chi_max = 3 does nothing with scheme = riemann_granular: it acts only with scheme = classic_granular"]
    assert idle(scheme="classic_granular", limiter="none") == [
        "limiter = none does nothing with scheme = classic_granular: it acts only with scheme = riemann_granular"]
    assert idle(stabiliser="tvf", utvf_splashed="shifted") == [
        "utvf_splashed = shifted does nothing with stabiliser = tvf: it acts only with stabiliser = utvf"]
    assert idle() == [] and idle(scheme="classic_granular", av_alpha="2", chi_max="2") == []
    assert idle(stabiliser="artificial_stress+utvf", utvf_splashed="shifted", artificial_stress_epsilon="0.3") == []


def test_an_angle_that_looks_like_radians_is_warned():
    """A friction angle of 0.35 (20 degrees typed in radians, or tan 19 degrees) builds, with a
    warning that gives both readings, the dilatancy angle's only the first; 0 (a frictionless wall,
    undrained clay) and the defaults do not."""
    module = load_case_module("cohesive_failure_2d")
    case = build_case(module, resolve_params(module, {"dp": "0.2", "phi": "0.35", "psi": "0.2"}))
    assert [w for w in case.warnings if "angles are in degrees" in w] == [
        "phi = 0.35 deg: angles are in degrees (0.35 rad would be 20.05 deg, a friction coefficient 0.35 is "
        "19.29 deg)", "psi = 0.2 deg: angles are in degrees (0.2 rad would be 11.46 deg)"]
    for overrides in ({"dp": "0.2"}, {"dp": "0.2", "phi": "0", "psi": "0"}):
        case = build_case(module, resolve_params(module, overrides))
        assert not [w for w in case.warnings if "angles are in degrees" in w]


def test_a_gauge_outside_the_domain_is_warned_of():
    """Points beyond the domain record nan; the case says which gauge has them when it is built."""
    from mpisph.gauges import Gauge, SurfaceGauge
    module = load_case_module(str(Path(__file__).parent / "cases" / "gauged_tank.py"))
    values = resolve_params(module, {})
    case = build_case(module, values)
    assert case.warnings == []
    lo, hi = case.domain
    case.gauges += [Gauge.line("tall", (0.5, 0.1), (0.5, 9.0), 5), SurfaceGauge("wide", np.array([[0.5], [50.0]]))]
    from mpisph.gauges import gauge_warnings
    warned = gauge_warnings(case)
    assert [w.split(":")[0] for w in warned] == ["gauge 'tall'", "gauge 'wide'"]
    assert "4 of its 5 points lie outside the domain" in warned[0]  # y = 2.3, 4.6, 6.8 and 9 m, above 1 m and "1 of its 2 points" in warned[1]


def test_the_cube_records_its_spread_and_the_settlement_of_its_tops_middle():
    """cube_failure_3d's front is the radius from the cube's vertical axis, and its probe 'top' the
    particle nearest the middle of the top face, a half spacing below it and off the axis (a 3D
    probe found the cube recorded neither)."""
    module = load_case_module("cube_failure_3d")
    case = build_case(module, resolve_params(module, {"dp": "0.2"}))
    assert case.front.origin == (0.0, 0.0, 0.0) and case.front.axes == (0, 1)
    assert np.allclose(np.abs(case.probe_origins["top"]), (0.1, 0.1, 1.9))


def test_a_lattice_finds_its_points_near_a_place_without_a_slab():
    """LatticePoints.near gives the kept points within reach of a place, the same as the slab of the
    window along x does, on a tilted frame; a probe of a body on a lattice of 8e36 points (the cube
    at dp = 1e-12) is refused as too large, where the slab's size was a ValueError traceback."""
    from mpisph.errors import InputError
    from mpisph.sources import LatticePoints
    c, s = np.cos(0.3), np.sin(0.3)
    frame = Frame(origin=(0.1, -0.2), axes=((c, -s), (s, c)))
    points = LatticePoints(Lattice((0, 0), (40, 30), 0.05, frame), keep=lambda x: x[:, 0] + x[:, 1] < 1.5)
    rng = np.random.default_rng(3)
    for place in rng.uniform(-0.5, 2.5, (20, 2)):
        index, x = points.near(place, 0.1)
        slab, xs, _ = points.window(0, place[0] - 0.1, place[0] + 0.1)
        within = np.linalg.norm(xs - place, axis=1) <= 0.1
        assert set(slab[within]) <= set(index)
        assert np.all(np.abs(frame.local(x) - frame.local(place[None])) <= 0.1 + 0.05 + 1e-12)
    module = load_case_module("cube_failure_3d")
    with pytest.raises(InputError, match="the case has about 8e\\+36 particles"):
        build_case(module, resolve_params(module, {"dp": "1e-12"}))
