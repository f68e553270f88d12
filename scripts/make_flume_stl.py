"""Write the STL files of cases/flume/ that cases/flume_3d.py is built from (000_ Sec. 5.4, Fig. 25a).

The paper gives the flume's dimensions only in its figure; these are ours (docs/FLUME.md has the
sketch). World axes: x downstream on the level, y across, z up; the foot of the slope at the origin.

- chute.stl: the 50-degree slope, 3 m long and 1 m wide, and the wall 1.5 m high (measured normal
  to the floor) that closes its top end; normals point into the flume.
- chute_sides.stl: its two side walls, 1.5 m high normal to the floor.
- runout.stl: the level run-out, 3 m long, and the wall 1.5 m high at its end.
- runout_sides.stl: its side walls, 1.5 m high. Each is split from the chute's along the bisector
  of the angle at the foot of the slope.
- barrier.stl: a wall 0.12 m thick and 0.8 m high across the whole width, its upstream face 0.6 m
  from the foot; an open surface (no bottom face), normals outward.
- soil.stl: the soil mass, a watertight box 1.6 m along the slope, 1 m wide and 1.2 m deep resting
  on the chute floor against its top wall; normals outward.

Run ``python scripts/make_flume_stl.py`` after changing a dimension; tests/test_flume.py checks the
shipped files match. ``python scripts/make_flume_stl.py DIR NAME=VALUE ...`` writes a variant (for
example ``SOIL_DEPTH=1.2``) into DIR, for ``python -m mpisph flume_3d --set geometry=DIR``.
"""

import argparse
from pathlib import Path

import meshio
import numpy as np

THETA = 50.0  # slope angle [deg]
CHUTE_LENGTH = 3.0  # along the slope [m]
RUNOUT_LENGTH = 3.0  # [m]
WIDTH = 1.0  # inside the side walls [m]
SIDE_HEIGHT = 1.5  # side and end walls, normal to the floor they stand on [m]
BARRIER_X, BARRIER_THICKNESS, BARRIER_HEIGHT = 0.6, 0.12, 0.8  # [m]
SOIL_LENGTH, SOIL_DEPTH = 1.6, 1.2  # along the slope and normal to it [m]

OUT = Path(__file__).resolve().parent.parent / "cases" / "flume"


def slope_axes():
    """Down the slope, across, and the chute floor's upward normal (world vectors)."""
    t = np.radians(THETA)
    return np.array([np.cos(t), 0.0, -np.sin(t)]), np.array([0.0, 1.0, 0.0]), np.array([np.sin(t), 0.0, np.cos(t)])


def chute_top():
    """The top end of the chute floor at y = 0."""
    along, _, _ = slope_axes()
    return -CHUTE_LENGTH * along


def quad(a, b, c, d, towards):
    """The planar quad abcd as two triangles whose normals point along ``towards``."""
    tri = np.array([[a, b, c], [a, c, d]], float)
    n = np.cross(tri[0, 1] - tri[0, 0], tri[0, 2] - tri[0, 0])
    return tri if n @ towards > 0 else tri[:, ::-1]


def side_outlines():
    """(chute, run-out) side-wall outlines in the x-z plane: the chute's floor, the foot, the corner
    above the foot on the bisector of the angle there, and the chute's top end at wall height."""
    _, _, up = slope_axes()
    top = chute_top()
    corner = np.array([SIDE_HEIGHT * np.tan(np.radians(THETA) / 2.0), 0.0, SIDE_HEIGHT])
    chute = [top, np.zeros(3), corner, top + SIDE_HEIGHT * up]
    runout = [np.zeros(3), np.array([RUNOUT_LENGTH, 0.0, 0.0]), np.array([RUNOUT_LENGTH, 0.0, SIDE_HEIGHT]), corner]
    return chute, runout


Y = np.array([0.0, 1.0, 0.0])


def floor_and_end(floor_start, floor_end, end, end_normal):
    """The floor of one stretch of the flume and the wall across its end (normals inward)."""
    floor_normal = np.cross(floor_end - floor_start, Y)
    across = WIDTH * Y
    return np.concatenate([quad(floor_start, floor_end, floor_end + across, floor_start + across, floor_normal),
                           quad(end[0], end[1], end[1] + across, end[0] + across, end_normal)])


def sides(outline):
    """The two side walls of one stretch, with the x-z ``outline`` (normals inward)."""
    return np.concatenate([quad(*outline, Y), quad(*[p + WIDTH * Y for p in outline], -Y)])


def chute():
    along, _, up = slope_axes()
    top = chute_top()
    return floor_and_end(top, np.zeros(3), (top, top + SIDE_HEIGHT * up), along)


def runout():
    end = np.array([RUNOUT_LENGTH, 0.0, 0.0])
    return floor_and_end(np.zeros(3), end, (end, end + [0.0, 0.0, SIDE_HEIGHT]), np.array([-1.0, 0.0, 0.0]))


def box_faces(corner, edges, skip_bottom=False):
    """The box corner + [0, 1]^3 . edges (rows: three edge vectors, right-handed) as quads, outward."""
    e0, e1, e2 = (np.asarray(e, float) for e in edges)
    c = np.asarray(corner, float)
    centre = c + 0.5 * (e0 + e1 + e2)
    faces = []
    for a, b, n in ((e0, e1, e2), (e1, e2, e0), (e2, e0, e1)):
        for offset in (np.zeros(3), n):
            if skip_bottom and np.allclose(n, e2) and not offset.any():
                continue
            p = c + offset
            face = quad(p, p + a, p + a + b, p + b, p + 0.5 * (a + b) - centre)
            faces.append(face)
    return np.concatenate(faces)


def barrier():
    return box_faces((BARRIER_X, 0.0, 0.0), ([BARRIER_THICKNESS, 0, 0], [0, WIDTH, 0], [0, 0, BARRIER_HEIGHT]),
                     skip_bottom=True)


def soil():
    along, across, up = slope_axes()
    return box_faces(chute_top(), (SOIL_LENGTH * along, WIDTH * across, SOIL_DEPTH * up))


SURFACES = {"chute": chute, "chute_sides": lambda: sides(side_outlines()[0]), "runout": runout,
            "runout_sides": lambda: sides(side_outlines()[1]), "barrier": barrier, "soil": soil}


def write(out=OUT):
    out.mkdir(parents=True, exist_ok=True)
    for name, make in SURFACES.items():
        tri = make()
        meshio.write(out / f"{name}.stl", meshio.Mesh(tri.reshape(-1, 3), [("triangle", np.arange(3 * len(tri)).reshape(-1, 3))]),
                     binary=False)
    return out


def sketch(png):
    """Side view (the centre line) and plan of the flume with its dimensions, for docs/FLUME.md."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    along, _, up = slope_axes()
    top = chute_top()
    fig, (side, plan) = plt.subplots(1, 2, figsize=(13, 4.8), gridspec_kw={"width_ratios": [1.6, 1]})
    chute_outline, runout_outline = side_outlines()
    for outline in (chute_outline, runout_outline):
        ring = np.array(outline + outline[:1])
        side.fill(ring[:, 0], ring[:, 2], color="0.92", zorder=0)
    floor = np.array([top + SIDE_HEIGHT * up, top, np.zeros(3), [RUNOUT_LENGTH, 0, 0], [RUNOUT_LENGTH, 0, SIDE_HEIGHT]])
    side.plot(floor[:, 0], floor[:, 2], "k-", lw=2)
    b = np.array([[BARRIER_X, 0], [BARRIER_X, BARRIER_HEIGHT], [BARRIER_X + BARRIER_THICKNESS, BARRIER_HEIGHT],
                  [BARRIER_X + BARRIER_THICKNESS, 0]])
    side.fill(b[:, 0], b[:, 1], color="tab:red")
    corners = [top, top + SOIL_LENGTH * along, top + SOIL_LENGTH * along + SOIL_DEPTH * up, top + SOIL_DEPTH * up]
    c = np.array(corners)
    side.fill(c[:, 0], c[:, 2], color="tab:brown", alpha=0.8)
    notes = [(0.5 * top + [0.25, 0, 0.25], f"chute {CHUTE_LENGTH:g} m at {THETA:g} deg"),
             ([0.3 * RUNOUT_LENGTH, 0, -0.25], f"run-out {RUNOUT_LENGTH:g} m"),
             ([BARRIER_X - 0.2, 0, BARRIER_HEIGHT + 0.12], f"barrier {BARRIER_THICKNESS:g} x {BARRIER_HEIGHT:g} m, "
                                                           f"face {BARRIER_X:g} m from the foot"),
             (top + 0.5 * SOIL_LENGTH * along + 1.1 * SOIL_DEPTH * up + [0.2, 0, 0],
              f"soil {SOIL_LENGTH:g} m along, {SOIL_DEPTH:g} m deep"),
             ([RUNOUT_LENGTH - 0.9, 0, SIDE_HEIGHT + 0.12], f"side walls {SIDE_HEIGHT:g} m high (free-slip)")]
    for at, text in notes:
        side.annotate(text, (at[0], at[2]), fontsize=9)
    side.set_aspect("equal")
    side.set_xlabel("x [m] (0: foot of the slope)")
    side.set_ylabel("z [m]")
    side.set_title("side view (sides shaded)")
    x0 = top[0]
    plan.add_patch(plt.Rectangle((x0, 0), RUNOUT_LENGTH - x0, WIDTH, color="0.92"))
    plan.add_patch(plt.Rectangle((BARRIER_X, 0), BARRIER_THICKNESS, WIDTH, color="tab:red"))
    plan.add_patch(plt.Rectangle((x0, 0), SOIL_LENGTH * along[0], WIDTH, color="tab:brown", alpha=0.8))
    plan.plot([x0, RUNOUT_LENGTH], [0, 0], "k-", [x0, RUNOUT_LENGTH], [WIDTH, WIDTH], "k-", lw=2)
    plan.axvline(0.0, color="k", ls=":", lw=1)
    plan.annotate(f"width {WIDTH:g} m", (0.2, 0.5 * WIDTH), fontsize=9)
    plan.set_xlim(x0 - 0.2, RUNOUT_LENGTH + 0.2)
    plan.set_ylim(-0.3, WIDTH + 0.3)
    plan.set_aspect("equal")
    plan.set_xlabel("x [m]")
    plan.set_ylabel("y [m]")
    plan.set_title("plan (dotted: foot of the slope)")
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    return png


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir", nargs="?", type=Path, default=OUT, help="where to write them (default: cases/flume/)")
    ap.add_argument("dimensions", nargs="*", metavar="NAME=VALUE",
                    help="a dimension of this file in metres or degrees, e.g. SOIL_DEPTH=1.2")
    a = ap.parse_args()
    if "=" in str(a.dir):
        ap.error(f"{a.dir} reads as a dimension: a variant needs its directory first, DIR NAME=VALUE ...")
    if a.dimensions and a.dir.resolve() == OUT.resolve():
        ap.error(f"a variant would write over the shipped surfaces in {OUT}: give it a directory of its own")
    for arg in a.dimensions:
        name, _, value = arg.partition("=")
        if name not in globals() or not isinstance(globals()[name], float):
            ap.error(f"unknown dimension {name!r}")
        try:
            globals()[name] = float(value)
        except ValueError:
            ap.error(f"{name} takes a number, not {value!r}")
    out = write(a.dir)
    print(f"wrote the flume's surfaces to {out}")
    if out == OUT:
        print(f"drew {sketch(Path(__file__).resolve().parent.parent / 'docs' / 'img' / 'flume_3d_sketch.png')}")
