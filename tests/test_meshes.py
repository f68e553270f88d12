"""Geometry from meshes (mpisph/meshes.py): fills of closed STL/OBJ/VTU surfaces, the refusal of a
surface that is not watertight, and wall layers behind open surfaces."""

import meshio
import numpy as np
import pytest

from mpisph.errors import InputError
from mpisph.geometry import box, box_walls, depth_outside
from mpisph.kernels import Kernel
from mpisph.lattice import Frame
from mpisph.meshes import Surface, depth_behind, fill, read_surface, wall_layers
from mpisph.wall_push import push_over_continuous

# The six faces of the unit cube as quads, each listed counter-clockwise seen from outside.
CUBE_POINTS = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                        [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
CUBE_QUADS = np.array([[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [1, 2, 6, 5], [0, 4, 7, 3]])


def cube_triangles(lo, hi, drop=()):
    """The box [lo, hi] as outward-oriented triangles, without the quads listed in ``drop``."""
    points = np.asarray(lo) + CUBE_POINTS * (np.asarray(hi) - np.asarray(lo))
    quads = [q for k, q in enumerate(CUBE_QUADS) if k not in drop]
    return np.concatenate([points[np.array(quads)[:, [0, 1, 2]]], points[np.array(quads)[:, [0, 2, 3]]]])


def write(path, triangles):
    points = triangles.reshape(-1, 3)
    meshio.write(path, meshio.Mesh(points, [("triangle", np.arange(len(points)).reshape(-1, 3))]))
    return path


def test_a_watertight_stl_box_fills_as_the_lattice_box(tmp_path):
    lo, hi, dp = (0.2, -0.1, 0.0), (0.6, 0.2, 0.25), 0.05
    x, _ = fill(read_surface(write(tmp_path / "box.stl", cube_triangles(lo, hi))), dp).everything()
    expected = box(lo, hi, dp)
    assert len(x) == len(expected) == 8 * 6 * 5
    assert np.allclose(np.sort(x, axis=0), np.sort(expected, axis=0))
    # the same box with its faces turned inwards (winding number -1 inside) fills alike, where it
    # had no particles at all
    inwards = fill(read_surface(write(tmp_path / "inwards.stl", cube_triangles(lo, hi)[:, ::-1])), dp)
    assert np.array_equal(inwards.everything()[0], fill(read_surface(tmp_path / "box.stl"), dp).everything()[0])
    assert abs(inwards.estimate - len(x)) <= 1  # the enclosed volume over dp^3, rounded down


def test_an_obj_sphere_fills_its_volume(tmp_path):
    """A closed polyhedral sphere written as OBJ with quads and triangles: the fill holds the
    lattice points of the ball (up to the facets' chords) and nothing outside it."""
    n_theta, n_phi, r = 24, 48, 0.5
    theta = np.linspace(0.0, np.pi, n_theta + 1)[1:-1]
    phi = np.linspace(0.0, 2 * np.pi, n_phi, endpoint=False)
    ring = np.array([[np.sin(t) * np.cos(f), np.sin(t) * np.sin(f), np.cos(t)] for t in theta for f in phi]) * r
    points = np.concatenate([[[0, 0, r]], ring, [[0, 0, -r]]])
    south = len(points) - 1
    idx = lambda a, b: 1 + a * n_phi + b % n_phi  # noqa: E731
    caps = [[0, idx(0, b), idx(0, b + 1)] for b in range(n_phi)]
    caps += [[south, idx(n_theta - 2, b + 1), idx(n_theta - 2, b)] for b in range(n_phi)]
    quads = [[idx(a, b), idx(a + 1, b), idx(a + 1, b + 1), idx(a, b + 1)]
             for a in range(n_theta - 2) for b in range(n_phi)]
    meshio.write(tmp_path / "ball.obj", meshio.Mesh(points, [("triangle", np.array(caps)), ("quad", np.array(quads))]))
    dp = 0.05
    x, _ = fill(read_surface(tmp_path / "ball.obj"), dp, Frame(origin=(-0.5, -0.5, -0.5))).everything()
    radius = np.linalg.norm(x, axis=1)
    assert radius.max() < r
    lattice = box((-0.5,) * 3, (0.5,) * 3, dp)
    deep = np.linalg.norm(lattice, axis=1) < r * np.cos(np.pi / n_theta)  # inside every facet
    assert np.all(np.isin(lattice[deep].round(9), x.round(9)).all(axis=1))
    volume = len(x) * dp**3
    assert abs(volume / (4 / 3 * np.pi * r**3) - 1.0) < 0.03


def test_a_vtu_surface_reads_like_the_stl(tmp_path):
    tri = cube_triangles((0, 0, 0), (0.3, 0.3, 0.3))
    write(tmp_path / "box.vtu", tri)
    assert len(fill(read_surface(tmp_path / "box.vtu"), 0.05).everything()[0]) == 216


def test_a_box_with_a_missing_face_is_refused_in_one_line(tmp_path):
    surface = read_surface(write(tmp_path / "broken.stl", cube_triangles((0, 0, 0), (1, 1, 1), drop=(1,))))
    with pytest.raises(InputError) as err:
        fill(surface, 0.1)
    message = str(err.value)
    assert "'broken' is not watertight" in message and "4 of its edges" in message and "\n" not in message


def test_a_box_with_one_face_turned_inside_out_is_refused(tmp_path):
    tri = cube_triangles((0, 0, 0), (1, 1, 1))
    tri[2] = tri[2][::-1]  # one triangle against the others' orientation
    with pytest.raises(InputError, match="not watertight"):
        fill(Surface("flipped", tri), 0.1)


def test_an_unreadable_mesh_is_a_one_line_error(tmp_path):
    (tmp_path / "junk.stl").write_text("not a mesh")
    with pytest.raises(InputError, match="cannot read the mesh"):
        read_surface(tmp_path / "junk.stl")


def layers_of(parts, dp, layers, frames=None):
    """wall_layers' particles as arrays: (positions, normals) per part."""
    return [points.everything() for points in wall_layers(parts, dp, layers, frames)]


def open_box(lo, hi):
    """The floor and four sides of the box [lo, hi], normals pointing into it (the material side)."""
    return cube_triangles(lo, hi, drop=(1,))[:, ::-1]


def test_wall_layers_behind_an_open_box_are_box_walls_with_rounded_corners():
    """Below the rim, the layers are box_walls' within layers dp of the box (the corners rounded);
    above it, behind the sides' open edges, they are the rounded caps of those edges."""
    lo, hi, dp, layers = (0.0, 0.0, 0.0), (0.4, 0.3, 0.2), 0.02, 3
    [(x, n)] = layers_of([Surface("tank", open_box(lo, hi))], dp, layers)
    cap = x[:, 2] > hi[2]
    rim = np.clip(x[cap], lo, hi) - x[cap]
    assert np.all(np.linalg.norm(rim, axis=1) < layers * dp) and np.all(np.abs(x[cap, 2] - hi[2]) < layers * dp)
    x, n = x[~cap], n[~cap]
    ref_x, ref_n = box_walls(lo, hi, dp, layers, open_sides=("+z",))
    ref_x, ref_n = ref_x[ref_x[:, 2] < hi[2]], ref_n[ref_x[:, 2] < hi[2]]
    depth = np.linalg.norm(np.clip(ref_x, lo, hi) - ref_x, axis=1)
    within = depth < layers * dp
    assert len(x) == within.sum()
    order, ref_order = np.lexsort(x.T), np.lexsort(ref_x[within].T)
    assert np.allclose(x[order], ref_x[within][ref_order])
    assert np.allclose(n[order], ref_n[within][ref_order])
    # their depth behind the surface (Wall.distance for the Morris walls) is the box's, as for box_walls
    np.testing.assert_allclose(depth_behind(Surface("tank", open_box(lo, hi)))(x), depth_outside(lo, hi)(x),
                               atol=1e-12)


def test_a_side_through_lattice_points_keeps_all_its_layers():
    """A side an odd number of half spacings from the frame's origin passes through a plane of
    lattice points: those on it are not wall particles, and its layers are the ``layers`` planes
    at dp, 2 dp, ... layers dp behind it (rounding must not lose the last: flume_3d's end and side
    walls at dp = 0.08 m had two)."""
    lo, hi, dp, layers = (0.0, 0.0, 0.0), (0.41, 0.3, 0.2), 0.02, 3
    [(x, n)] = layers_of([Surface("tank", open_box(lo, hi))], dp, layers)
    middle = (x[:, 1] > 0.1) & (x[:, 1] < 0.2) & (x[:, 2] > 0.05) & (x[:, 2] < 0.15)
    beyond = middle & (x[:, 0] > 0.3)
    np.testing.assert_allclose(np.unique(x[beyond, 0].round(12)), hi[0] + dp * np.arange(1, layers + 1))
    assert np.allclose(n[beyond], (-1.0, 0.0, 0.0))
    behind_lo = middle & (x[:, 0] < 0.1)  # the side on a lattice plane: dp/2, 3 dp/2, ... behind it
    np.testing.assert_allclose(np.unique(x[behind_lo, 0].round(12)), -dp * (np.arange(layers)[::-1] + 0.5))


def test_parts_share_the_layers_behind_their_joints_without_overlap():
    """The same open box as two parts (floor; sides) gives the same particles as one part."""
    lo, hi, dp, layers = (0.0, 0.0, 0.0), (0.4, 0.3, 0.2), 0.02, 3
    tri = open_box(lo, hi)
    floor = np.abs(Surface("", tri).normals[:, 2] - 1.0) < 1e-12
    [(whole, _)] = layers_of([Surface("tank", tri)], dp, layers)
    frame = Frame(origin=lo)
    parts = layers_of([Surface("floor", tri[floor]), Surface("sides", tri[~floor])], dp, layers, [frame, frame])
    joined = np.concatenate([x for x, _ in parts])
    assert len(joined) == len(whole)
    assert len(np.unique(joined.round(9), axis=0)) == len(joined)


def test_wall_layers_follow_a_tilted_floor_in_its_own_frame():
    """A 50-degree floor: its layers lie in its frame at depths (k + 1/2) dp, normals along the floor's."""
    theta, dp, layers = np.radians(50.0), 0.05, 3
    along, across, up = np.array([np.cos(theta), 0, -np.sin(theta)]), np.array([0, 1.0, 0]), np.array([np.sin(theta), 0, np.cos(theta)])
    corners = np.array([[0, 0], [1, 0], [1, 0.5], [0, 0.5]]) @ np.array([along, across])
    tri = np.array([corners[[0, 1, 2]], corners[[0, 2, 3]]])  # normal: along x across = up
    frame = Frame(origin=(0, 0, 0), axes=tuple(map(tuple, np.column_stack([along, across, up]))))
    [(x, n)] = layers_of([Surface("chute", tri)], dp, layers, [frame])
    u = frame.local(x)
    under = np.all((u[:, :2] > 0) & (u[:, :2] < (1.0, 0.5)), axis=1)
    assert under.sum() == 20 * 10 * layers
    assert np.allclose(np.unique(u[under, 2].round(12)), -(np.arange(layers)[::-1] + 0.5) * dp)
    assert np.allclose(n[under], up)


def _closest_pair(x):
    d = np.linalg.norm(x[:, None] - x[None], axis=2)
    np.fill_diagonal(d, np.inf)
    return d.min()


def test_where_two_frames_meet_no_hole_opens_and_no_particles_double():
    """A 50-degree slope meeting a level floor, each part in its own frame: a particle dp/2 in
    front of either floor, across the joint, is pushed by the wall particles within 15 % below to
    30 % above the push of the continuous wall: no hole (the previous rule, 3/4 dp between parts,
    left one that pushed 31 % short, and soil leaked there in flume_3d), and where the later
    lattice's first layer in the joint is kept, an overfill of a quarter (1.25), not a doubling.
    No two wall particles are nearer than dp/2."""
    theta, dp, layers = np.radians(50.0), 0.05, 3
    along, up = np.array([np.cos(theta), 0, -np.sin(theta)]), np.array([np.sin(theta), 0, np.cos(theta)])
    across = np.array([0, 0.5, 0])
    top = -1.0 * along
    slope = np.array([[top, (0, 0, 0), across], [top, across, top + across]], float)
    level = np.array([[(0, 0, 0), (1, 0, 0), (1, 0.5, 0)], [(0, 0, 0), (1, 0.5, 0), (0, 0.5, 0)]], float)
    frames = [Frame(origin=tuple(top), axes=tuple(map(tuple, np.column_stack([along, (0, 1, 0), up])))), Frame()]
    surfaces = [Surface("slope", slope), Surface("level", level)]
    x = np.concatenate([p for p, _ in layers_of(surfaces, dp, layers, frames)])
    assert _closest_pair(x) >= 0.5 * dp
    probes, normals = [], []
    for s in np.arange(-6, 6, 0.25) * dp:  # along the floors from the joint, slope side negative
        for y in np.arange(0.15, 0.35, dp / 3):
            if s >= 0:
                probes.append((s, y, 0.5 * dp)), normals.append((0, 0, 1))
            else:
                probes.append(-s * top / np.linalg.norm(top) + 0.5 * dp * up + (0, y, 0)), normals.append(up)
    push = push_over_continuous(surfaces, x, dp, layers * dp, np.array(probes, float), np.array(normals, float),
                                Kernel("wendland_c2", 1.3 * dp, 3))
    assert 0.85 < push.min() and push.max() < 1.3


def test_coplanar_walls_in_two_frames_leave_no_hole_at_their_seam():
    """Two side walls in one plane (y = 0), one on a lattice along a 50-degree slope, one level,
    meeting along a line (the chute's and run-out's side walls of flume_3d): a particle dp/2 in
    front of the seam is pushed by the wall particles within 15 % of the continuous wall's push
    (the previous rule pushed 22 % short)."""
    theta, dp, layers = np.radians(50.0), 0.05, 3
    along, up = np.array([np.cos(theta), 0, -np.sin(theta)]), np.array([np.sin(theta), 0, np.cos(theta)])
    seam = np.array([np.tan(theta / 2), 0, 1.0]) * 0.5  # the bisector of the angle at the foot
    foot, top, top_up = np.zeros(3), -0.4 * along, -0.4 * along + 0.5 * up
    left = np.array([[foot, seam, top_up], [foot, top_up, top]])
    right = np.array([[(0, 0, 0), (0.4, 0, 0), (0.4, 0, 0.5)], [(0, 0, 0), (0.4, 0, 0.5), seam]])
    y = np.array([0, 1.0, 0])
    orient = lambda t: t if np.cross(t[0, 1] - t[0, 0], t[0, 2] - t[0, 0]) @ y > 0 else t[:, ::-1]  # noqa: E731
    frames = [Frame(origin=(0, 0, 0), axes=tuple(map(tuple, np.column_stack([along, y, up])))), Frame()]
    surfaces = [Surface("chute_side", orient(left)), Surface("runout_side", orient(right))]
    x = np.concatenate([p for p, _ in layers_of(surfaces, dp, layers, frames)])
    assert _closest_pair(x) >= 0.5 * dp
    across_seam = np.array([1.0, 0, -np.tan(theta / 2)]) / np.hypot(1, np.tan(theta / 2))
    probes = np.array([s * seam / np.linalg.norm(seam) + t * across_seam + (0, 0.5 * dp, 0)
                       for s in np.arange(0.12, 0.38, dp / 4) for t in np.arange(-3, 3, 0.25) * dp])
    push = push_over_continuous(surfaces, x, dp, layers * dp, probes, np.tile(y, (len(probes), 1)),
                                Kernel("wendland_c2", 1.3 * dp, 3))
    assert 0.85 < push.min() and push.max() < 1.15
