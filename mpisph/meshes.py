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
  faces away from) and no farther than ``layers`` dp from it (to a rounding tolerance,
  ``ON_SURFACE`` dp); a point on the surface is not. The wall normal is the unit vector from
  the particle to the nearest point of its part, as ``geometry.box_walls`` has it.

Both place particles at the cell centres of a lattice in a ``Frame``: origin + axes @ ((i + 1/2)
dp), so that a face lying on a lattice plane of the frame has its particles and its wall
particles dp/2 from it on either side. A face through a plane of cell centres (a wall an odd
number of half spacings from its frame's origin) has its wall particles at dp, 2 dp, ...
``layers`` dp behind it: ``layers`` layers either way.

Walls of several parts (a chute on its slope, a run-out on the level) each take their own frame.
Where parts meet, a point behind more than one of them belongs to each part it is within dp of
being nearest to, so both lattices fill a band about the joint. In that band a later part's
particle is left out where the earlier parts' particles already fill its place: where their
kernel sum about it (Wendland C2, h = dp) is at least half a full lattice's, or one of them is
nearer than dp/2. Half is the sum at the edge of a filled half-space, so across a flat edge the
later lattice starts, on average over the offsets of the two lattices, one spacing beyond the
earlier one's last layer. Two earlier rules left holes: cut at the bisector, gaps about a
particle wide through all layers, through which soil leaked out of flume_3d; particles nearer
than 3/4 dp to an earlier part's left out, a band about a third of a particle too thin along
every seam: a particle dp/2 in front of the side walls' seam was pushed back 33 % less than by
the continuous wall, one over the floors' joint at the foot 31 % less (scripts/flume_walls.py,
wall_push.py), and soil still leaked.
"""

from dataclasses import dataclass
from pathlib import Path

import meshio
import numpy as np
from numba import njit

from .errors import InputError
from .kernels import Kernel, w
from .lattice import Frame, Lattice
from .sources import LatticePoints, Points

# meshio cell types whose cells are planar polygons, split into triangle fans
_POLYGONS = ("triangle", "quad", "polygon")
COVERED = 0.5  # a joint's point is filled where earlier parts' kernel sum is this fraction of a full lattice's
ON_SURFACE = 1e-9  # distances within this many dp of 0 or of the layers' depth are taken as equal to it


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


def _lowest_corner(surface):
    """The default frame of a surface: the world axes, origin at the lowest corner of its box."""
    return Frame(origin=tuple(surface.triangles.reshape(-1, 3).min(axis=0)))


def volume(surface):
    """The volume a closed, outward-oriented surface encloses (divergence theorem)."""
    t = surface.triangles
    return float(np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum() / 6.0)


def fill(surface, dp, frame=None):
    """The lattice points of ``frame`` (spacing dp; default: the world axes from the surface's
    lowest corner) inside the watertight ``surface``, however its faces are oriented, as a source
    (sources.py)."""
    check_watertight(surface)
    frame = frame or _lowest_corner(surface)
    vertices = frame.local(surface.triangles.reshape(-1, 3))
    lattice = Lattice.covering(vertices.min(axis=0), vertices.max(axis=0), dp, frame)
    triangles = surface.triangles

    def inside(x):  # |winding number| 1: a surface oriented inwards (-1) fills its inside too
        return np.abs(winding_numbers(x, triangles)) > 0.5

    return LatticePoints(lattice, keep=inside, estimate=abs(volume(surface)) / dp**3)


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


def joined(parts):
    """The triangles, normals and part index of every triangle of the surfaces ``parts``, one array
    each, as ``nearest_on_parts`` takes them."""
    triangles = np.concatenate([s.triangles for s in parts])
    normals = np.concatenate([s.normals for s in parts])
    part = np.concatenate([np.full(len(s.triangles), k, np.int64) for k, s in enumerate(parts)])
    return triangles, normals, part


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
    lowest corner). Returns a source (sources.py) per part, whose normals point inwards."""
    walls = _WallLayers(parts, dp, layers, frames or [_lowest_corner(s) for s in parts])
    return [_PartLayers(walls, k) for k in range(len(parts))]


class _WallLayers:
    """The wall layers of all parts, a slab at a time. A part's particle near a joint depends on
    the particles earlier parts keep within a kernel support (2 dp) of it, so a slab is computed
    with a margin of 2 dp per part and then cut back. The lattice points a part can claim lie
    within ``layers`` dp of one of its triangles: only the boxes about its triangles are searched."""

    def __init__(self, parts, dp, layers, frames):
        self.parts, self.dp = parts, dp
        self.depth = layers * dp
        self.triangles, self.normals, self.part = joined(parts)
        self.lattices, self.boxes = [], []  # per part: its lattice, and the sub-lattice about each triangle
        for surface, frame in zip(parts, frames):
            tri = frame.local(surface.triangles.reshape(-1, 3)).reshape(-1, 3, 3)
            lattice = Lattice.covering(tri.reshape(-1, 3).min(axis=0) - self.depth,
                                       tri.reshape(-1, 3).max(axis=0) + self.depth, dp, frame)
            self.lattices.append(lattice)
            self.boxes.append([Lattice.covering(t.min(axis=0) - self.depth, t.max(axis=0) + self.depth, dp, frame)
                               for t in tri])
        self._last = None  # (window, result): the parts ask for the same slab one after the other

    def estimate(self, k):
        """About how many particles part k has: ``layers`` deep behind its area, and a quarter
        cylinder of that radius about each open edge where the layers wrap round it."""
        t = self.parts[k].triangles
        area = 0.5 * np.linalg.norm(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), axis=1).sum()
        edges = open_edges(self.parts[k])
        perimeter = np.linalg.norm(edges[:, 1] - edges[:, 0], axis=1).sum()
        return int((area * self.depth + perimeter * np.pi * self.depth**2 / 4) / self.dp**3)

    def _candidates(self, k, axis, lo, hi):
        """Indices (in part k's lattice, ascending) of the points in the boxes about its triangles
        whose coordinate along ``axis`` lies in [lo, hi)."""
        lattice, found = self.lattices[k], []
        for box in self.boxes[k]:
            first = np.maximum(box.first, lattice.first)
            last = np.minimum(box.last, lattice.last)
            if np.any(last <= first):
                continue
            sub = Lattice(tuple(first), tuple(last), self.dp, lattice.frame)
            tuples = np.unravel_index(sub.window(axis, lo, hi), sub.shape)
            found.append(np.ravel_multi_index([t + f - g for t, f, g in zip(tuples, first, lattice.first)],
                                              lattice.shape))
        return np.unique(np.concatenate(found)) if found else np.zeros(0, np.int64)

    def window(self, axis, lo, hi):
        """Per part: (indices, positions, inward normals) of its particles in [lo, hi) along ``axis``."""
        if self._last is not None and self._last[0] == (axis, lo, hi):
            return self._last[1]
        dp, depth, n_parts = self.dp, self.depth, len(self.parts)
        margin = n_parts * 2.0 * dp
        out, kept_dist = [], []  # per part: (indices, positions, normals), and their distances to every part
        for k in range(n_parts):
            index = self._candidates(k, axis, lo - margin, hi + margin)
            x = self.lattices[k].points(index)
            dist, near, behind = nearest_on_parts(x, self.triangles, self.normals, self.part, n_parts)
            claims = behind & (dist > ON_SURFACE * dp) & (dist <= depth + ON_SURFACE * dp)
            mine = claims[:, k].copy()
            for j in range(n_parts):
                if j != k:  # another part nearer by more than dp takes the point
                    mine &= ~(claims[:, j] & (dist[:, j] < dist[:, k] - dp))
            band = depth + 2.0 * dp  # a joint's band: within this of an earlier part
            joint = mine & np.any(dist[:, :k] < band, axis=1)
            if joint.any():  # the earlier parts' particles fill the place, or this part's do
                earlier = np.concatenate([p[d[:, k] < band] for (_, p, _), d in zip(out, kept_dist)])
                coverage, nearest = _coverage(x[joint], earlier, dp)
                mine[joint] = (coverage < COVERED) & (nearest >= 0.5 * dp)
            towards = near[mine, k] - x[mine]
            out.append((index[mine], x[mine], towards / np.linalg.norm(towards, axis=1)[:, None]))
            kept_dist.append(dist[mine])
        result = []
        for index, x, normal in out:
            inside = (x[:, axis] >= lo) & (x[:, axis] < hi)
            result.append((index[inside], x[inside], normal[inside]))
        self._last = ((axis, lo, hi), result)
        return result


class _PartLayers(Points):
    """The wall layers of one part of a ``_WallLayers``."""

    def __init__(self, walls, k):
        self.walls, self.k = walls, k
        self.size = walls.lattices[k].size
        self.estimate = min(self.size, sum(box.size for box in walls.boxes[k]), walls.estimate(k))

    def window(self, axis, lo, hi):
        return self.walls.window(axis, lo, hi)[self.k]

    def position(self, index):
        return self.walls.lattices[self.k].points(np.array([index]))[0]


def depth_behind(surface):
    """The function of positions giving their distance to the nearest point of ``surface``: the depth
    of its wall layers' particles behind it (``Wall.distance``, which the Morris walls of mu_i and
    classic_granular read), as ``geometry.depth_outside`` gives it for a box."""
    triangles, normals, part = joined([surface])
    return lambda x: nearest_on_parts(np.ascontiguousarray(x, dtype=float), triangles, normals, part, 1)[0][:, 0]


def _coverage(points, others, dp):
    """sum_o dp^3 W(|p - o|) over ``others`` about each of ``points`` (Wendland C2, h = dp) as a
    fraction of a full cubic lattice's sum, and the distance to the nearest of them (inf where
    none lies in the 27 cells about the point). ``others`` are sorted into cells a support wide and each
    point looks in the 27 cells about its own; each point's terms are summed in ascending order, so
    the sum does not depend on which others a slab holds beyond the support."""
    kernel = Kernel("wendland_c2", dp, 3)
    out, nearest = np.zeros(len(points)), np.full(len(points), np.inf)
    if len(others) == 0:
        return out, nearest
    radius = kernel.support
    lo = others.min(axis=0)
    cells = np.floor((others - lo) / radius).astype(np.int64) + 1  # a ring of empty cells about them
    dims = cells.max(axis=0) + 2
    keys = (cells[:, 0] * dims[1] + cells[:, 1]) * dims[2] + cells[:, 2]
    order = np.argsort(keys, kind="stable")
    _kernel_sums(points, others[order], keys[order], lo, radius, dims, kernel.params, out, nearest)
    return out * dp**3 / kernel.lattice_sum(dp), nearest


@njit(cache=True)
def _kernel_sums(points, others, keys, lo, radius, dims, kernel, out, nearest):
    terms = np.empty(len(others))
    for i in range(len(points)):
        c = np.floor((points[i] - lo) / radius).astype(np.int64) + 1
        if np.any(c < 0) or np.any(c > dims - 1):
            continue  # beyond the ring of empty cells: no other within the support
        m = 0
        for a in range(c[0] - 1, c[0] + 2):
            for b in range(c[1] - 1, c[1] + 2):
                key = (a * dims[1] + b) * dims[2] + c[2] - 1
                k = np.searchsorted(keys, key)
                while k < len(keys) and keys[k] <= key + 2:
                    d = points[i] - others[k]
                    r = np.sqrt(_dot(d, d))
                    nearest[i] = min(nearest[i], r)
                    value = w(r, kernel)
                    if value > 0.0:
                        terms[m] = value
                        m += 1
                    k += 1
        out[i] = np.sort(terms[:m]).sum()
