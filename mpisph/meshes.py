"""Geometry from surface meshes (STL, OBJ, VTU and the other formats meshio reads).

A mesh is read as oriented triangles (quads and polygons are split into fans). Two uses:

- ``fill``: the lattice points inside a closed surface, a body's particles. The surface must
  be watertight: every edge shared by exactly two triangles that run along it in opposite
  directions; a point is inside when the generalised winding number of the surface about it
  (the solid angle of the triangles over 4 pi, Van Oosterom & Strackee 1983) exceeds 1/2, which
  needs no ray and no tolerance.
- ``wall_layers``: dummy wall particles behind open (or closed) surfaces. A triangle's normal
  (right-hand rule over its vertices) points to the side the material is on; a lattice point
  is a wall particle of a part when it lies behind that part (on the side its nearest triangle
  faces away from) and nearer than ``layers`` dp to it. The wall normal is the unit vector from
  the particle to the nearest point of its part, as ``geometry.box_walls`` has it.

Both place particles at the cell centres of a lattice in a ``Frame``: origin + axes @ ((i + 1/2)
dp), so that a face lying on a lattice plane of the frame has its particles and its wall
particles dp/2 from it on either side. Walls of several parts (a chute on its slope, a run-out
on the level) each take their own frame. Where parts meet, a point behind more than one of them
belongs to each part it is within dp of being nearest to, so both lattices fill a band about
the joint, and a particle nearer than 3/4 dp to one of an earlier part is left out of that band.
The joint then has no hole wider than a lattice has anyway: cut at the bisector instead, with
the particles nearer than dp/2 to the other lattice left out, it had gaps about a particle wide
through all layers, and in flume_3d soil leaked through them out of the flume.
"""

from dataclasses import dataclass
from pathlib import Path

import meshio
import numpy as np
from numba import njit

from .errors import InputError
from .geometry import _within_memory

# meshio cell types whose cells are planar polygons, split into triangle fans
_POLYGONS = ("triangle", "quad", "polygon")
SEAM = 0.75  # times dp: the closest two wall particles of different parts may come in a joint's band


@dataclass(frozen=True)
class Frame:
    """A lattice frame: ``origin`` and ``axes`` (3 x 3, the columns are the lattice axes, orthonormal)."""

    origin: tuple = (0.0, 0.0, 0.0)
    axes: tuple = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))

    def matrix(self):
        r = np.asarray(self.axes, float)
        if r.shape != (3, 3) or not np.allclose(r.T @ r, np.eye(3), atol=1e-12):
            raise InputError("a lattice frame needs three orthonormal axes")
        return r

    def local(self, x):
        """World points -> coordinates along the frame's axes."""
        return (np.asarray(x, float) - np.asarray(self.origin, float)) @ self.matrix()

    def world(self, u):
        """Frame coordinates -> world points."""
        return np.asarray(self.origin, float) + u @ self.matrix().T


@dataclass
class Surface:
    """Oriented triangles (m, 3, 3) of a mesh, named for messages."""

    name: str
    triangles: np.ndarray

    @property
    def normals(self):
        """Unit normals (m, 3) by the right-hand rule over each triangle's vertices."""
        t = self.triangles
        n = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
        return n / np.linalg.norm(n, axis=1)[:, None]


def read_surface(path, name=None):
    """The triangles of the mesh file ``path`` (any format meshio reads: .stl, .obj, .vtu, ...)."""
    path = Path(path)
    name = name or path.stem
    try:
        with np.errstate(over="ignore"):  # meshio probes an ASCII STL as binary first
            mesh = meshio.read(path)
    except Exception as exc:  # meshio raises several types for unreadable files
        raise InputError(f"cannot read the mesh {path}: {exc}") from None
    points = np.asarray(mesh.points, float)
    if points.shape[1] != 3:
        raise InputError(f"the mesh {path} is not 3D (its points have {points.shape[1]} coordinates)")
    triangles = []
    for block in mesh.cells:
        if block.type not in _POLYGONS:
            continue
        cells = np.asarray(block.data)
        for k in range(1, cells.shape[1] - 1):
            triangles.append(points[cells[:, [0, k, k + 1]]])
    if not triangles:
        raise InputError(f"the mesh {path} has no surface cells (triangles, quads or polygons)")
    triangles = np.concatenate(triangles)
    area = 0.5 * np.linalg.norm(np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0]), axis=1)
    return Surface(name, triangles[area > 0.0])


def open_edges(surface):
    """Directed edges (as vertex coordinates, (k, 2, 3)) that no triangle runs along in the opposite
    direction: none for a watertight, consistently oriented surface. Vertices closer than 1e-9 of
    the surface's extent count as one."""
    points = surface.triangles.reshape(-1, 3)
    weld = 1e-9 * max(float(np.ptp(points, axis=0).max()), 1e-300)  # vertices that differ in rounding are one
    _, first, index = np.unique(np.round(points / weld), axis=0, return_index=True, return_inverse=True)
    vertices = points[first]
    tri = index.reshape(-1, 3)
    edges = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    forward = {tuple(e) for e in edges}
    unmatched = [e for e in edges if (e[1], e[0]) not in forward]
    return vertices[np.array(unmatched, dtype=np.int64).reshape(-1, 2)]


def check_watertight(surface):
    """Raise InputError (one line) unless ``surface`` closes a volume with consistent orientation."""
    edges = open_edges(surface)
    if len(edges):
        at = np.round(0.5 * (edges[0, 0] + edges[0, 1]), 6).tolist()
        raise InputError(f"the surface {surface.name!r} is not watertight: {len(edges)} of its edges "
                         f"have no opposite neighbour (the first at {at}); a body must be a closed, "
                         f"consistently oriented surface")


@njit(inline="always")
def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@njit(cache=True)
def winding_numbers(points, triangles):
    """The generalised winding number of the triangles about each point: 1 inside a closed,
    outward-oriented surface, 0 outside (Van Oosterom & Strackee's solid angle over 4 pi)."""
    out = np.zeros(len(points))
    for i in range(len(points)):
        total = 0.0
        for t in range(len(triangles)):
            a = triangles[t, 0] - points[i]
            b = triangles[t, 1] - points[i]
            c = triangles[t, 2] - points[i]
            la, lb, lc = np.sqrt(_dot(a, a)), np.sqrt(_dot(b, b)), np.sqrt(_dot(c, c))
            det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) \
                + a[2] * (b[0] * c[1] - b[1] * c[0])
            div = la * lb * lc + _dot(a, b) * lc + _dot(a, c) * lb + _dot(b, c) * la
            total += 2.0 * np.arctan2(det, div)
        out[i] = total / (4.0 * np.pi)
    return out


def _lattice(lo, hi, dp, frame, what):
    """Cell-centred lattice points of ``frame`` (in frame coordinates) covering [lo, hi] there."""
    first = np.floor(lo / dp + 1e-9).astype(np.int64)
    last = np.ceil(hi / dp - 1e-9).astype(np.int64)
    _within_memory(last - first, dp, what)
    axes = [(np.arange(f, l) + 0.5) * dp for f, l in zip(first, last)]
    grids = np.meshgrid(*axes, indexing="ij")
    return np.stack([g.ravel() for g in grids], axis=1)


def _lowest_corner(surface):
    """The default frame of a surface: the world axes, origin at the lowest corner of its box."""
    return Frame(origin=tuple(surface.triangles.reshape(-1, 3).min(axis=0)))


def fill(surface, dp, frame=None):
    """Lattice points of ``frame`` (spacing dp; default: the world axes from the surface's lowest
    corner) inside the watertight ``surface``."""
    check_watertight(surface)
    frame = frame or _lowest_corner(surface)
    vertices = frame.local(surface.triangles.reshape(-1, 3))
    u = _lattice(vertices.min(axis=0), vertices.max(axis=0), dp, frame, f"the body {surface.name!r}")
    inside = winding_numbers(u, vertices.reshape(-1, 3, 3)) > 0.5
    if not inside.any():
        raise InputError(f"spacing dp={dp:g} m leaves no particle inside the body {surface.name!r}")
    return frame.world(u[inside])


@njit(cache=True)
def _closest_on_triangle(p, a, b, c):
    """The point of triangle abc nearest to p (Ericson, Real-Time Collision Detection, 5.1.5)."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = _dot(ab, ap), _dot(ac, ap)
    if d1 <= 0.0 and d2 <= 0.0:
        return a
    bp = p - b
    d3, d4 = _dot(ab, bp), _dot(ac, bp)
    if d3 >= 0.0 and d4 <= d3:
        return b
    vc = d1 * d4 - d3 * d2
    if vc <= 0.0 and d1 >= 0.0 and d3 <= 0.0:
        return a + (d1 / (d1 - d3)) * ab
    cp = p - c
    d5, d6 = _dot(ab, cp), _dot(ac, cp)
    if d6 >= 0.0 and d5 <= d6:
        return c
    vb = d5 * d2 - d1 * d6
    if vb <= 0.0 and d2 >= 0.0 and d6 <= 0.0:
        return a + (d2 / (d2 - d6)) * ac
    va = d3 * d6 - d5 * d4
    if va <= 0.0 and d4 - d3 >= 0.0 and d5 - d6 >= 0.0:
        return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b)
    denom = 1.0 / (va + vb + vc)
    return a + ab * (vb * denom) + ac * (vc * denom)


@njit(cache=True)
def nearest_on_parts(points, triangles, normals, part, n_parts):
    """For each point and part: the distance to the part's nearest triangle, that nearest point,
    and whether the point lies behind it ((q - p) . n > 0)."""
    n = len(points)
    dist = np.full((n, n_parts), np.inf)
    near = np.zeros((n, n_parts, 3))
    behind = np.zeros((n, n_parts), np.bool_)
    for i in range(n):
        p = points[i]
        for t in range(len(triangles)):
            q = _closest_on_triangle(p, triangles[t, 0], triangles[t, 1], triangles[t, 2])
            d = np.sqrt(_dot(q - p, q - p))
            k = part[t]
            if d < dist[i, k]:
                dist[i, k] = d
                near[i, k] = q
                behind[i, k] = _dot(q - p, normals[t]) > 0.0
    return dist, near, behind


def wall_layers(parts, dp, layers, frames=None):
    """Dummy wall particles, ``layers`` lattice layers deep, behind each surface of ``parts``.

    ``frames`` gives each part its lattice (default: the world axes with the origin at the part's
    lowest corner). Returns a list over the parts of (positions, inward unit normals)."""
    frames = frames or [_lowest_corner(s) for s in parts]
    triangles = np.concatenate([s.triangles for s in parts])
    normals = np.concatenate([s.normals for s in parts])
    part = np.concatenate([np.full(len(s.triangles), k, np.int64) for k, s in enumerate(parts)])
    depth = layers * dp
    out, kept_dist = [], []  # per part: (positions, normals), and their distances to every part
    for k, (surface, frame) in enumerate(zip(parts, frames)):
        tri = frame.local(surface.triangles.reshape(-1, 3))
        u = _lattice(tri.min(axis=0) - depth, tri.max(axis=0) + depth, dp, frame, f"the walls of {surface.name!r}")
        x = frame.world(u)
        dist, near, behind = nearest_on_parts(x, triangles, normals, part, len(parts))
        claims = behind & (dist < depth)
        mine = claims[:, k].copy()
        for j in range(len(parts)):
            if j != k:  # another part nearer by more than dp takes the point
                mine &= ~(claims[:, j] & (dist[:, j] < dist[:, k] - dp))
        for j, (earlier, _) in enumerate(out):  # in a joint's band the earlier part's particle stays
            joint = mine & (dist[:, j] < depth + 2.0 * dp)
            if joint.any():
                close = kept_dist[j][:, k] < depth + 2.0 * dp
                mine[joint] = _farther_than(x[joint], earlier[close], SEAM * dp)
        if not mine.any():
            raise InputError(f"spacing dp={dp:g} m leaves no wall particle behind {surface.name!r}")
        towards = near[mine, k] - x[mine]
        out.append((x[mine], towards / np.linalg.norm(towards, axis=1)[:, None]))
        kept_dist.append(dist[mine])
    return out


@njit(cache=True)
def _farther_than(points, others, radius):
    """Whether each point lies farther than ``radius`` from every one of ``others`` (by pairs: the
    callers pass the few particles near a joint of two parts)."""
    out = np.ones(len(points), np.bool_)
    r2 = radius * radius
    for i in range(len(points)):
        for j in range(len(others)):
            d = points[i] - others[j]
            if _dot(d, d) < r2:
                out[i] = False
                break
    return out
