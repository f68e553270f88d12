"""How hard the walls of flume_3d push back where they are built from several parts.

    .venv/bin/python scripts/flume_walls.py [--dp 0.04]

Builds the case's wall particles and prints, for probes dp/2 in front of the side walls (chute
and run-out up to the barrier, 1 m deep in the flow) and of the floors within 0.5 m of the foot
of the slope, the wall particles' push over that of the continuous wall they stand for
(mpisph/wall_push.py): below 1 the wall has a hole there, above 1 more particles than its region
holds; a flat wall gives 1.02 to 1.05. The lowest and highest probes are named. The probes
stand where the walls' surfaces are: with a dp that does not divide the flume's width (1 m) the
lattices place the walls off them, so the figures are for such a dp as 0.04 or 0.05.
"""

import argparse
import sys
from pathlib import Path

import numpy as np

import make_flume_stl as flume  # this directory: the flume's dimensions

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from mpisph.case import build_case, load_case_module, resolve_params  # noqa: E402
from mpisph.geometry import support_layers  # noqa: E402
from mpisph.kernels import Kernel  # noqa: E402
from mpisph.meshes import read_surface  # noqa: E402
from mpisph.wall_push import push_over_continuous  # noqa: E402

FLOW_DEPTH = 1.0  # how far from the floor the side walls are probed [m]
ABOUT_THE_FOOT = 0.5  # how far along the floors from the foot they are probed [m]


def side_probes(dp):
    """(probes, normals) dp/2 in front of both side walls, over the chute and the run-out up to
    the barrier's face, up to FLOW_DEPTH from the floor."""
    along, across, up = flume.slope_axes()
    top = flume.chute_top()
    steps = np.arange(0.5 * dp, FLOW_DEPTH, dp)
    plane = [top + u * along + h * up for u in np.arange(0.5 * dp, flume.CHUTE_LENGTH, dp) for h in steps]
    plane += [np.array([x, 0.0, h]) for x in np.arange(0.0, flume.BARRIER_X - 0.5 * dp, dp) for h in steps]
    plane = np.array(plane)
    plane = plane[plane[:, 0] < flume.BARRIER_X - 0.5 * dp]  # the chute's probes high above the foot reach over the run-out
    probes = np.concatenate([plane + 0.5 * dp * across, plane + (flume.WIDTH - 0.5 * dp) * across])
    normals = np.concatenate([np.tile(across, (len(plane), 1)), np.tile(-across, (len(plane), 1))])
    return probes, normals


def floor_probes(dp):
    """(probes, normals) dp/2 above the chute's and the run-out's floors within ABOUT_THE_FOOT of
    the foot, across the whole width."""
    along, across, up = flume.slope_axes()
    probes, normals = [], []
    for s in np.arange(-ABOUT_THE_FOOT, ABOUT_THE_FOOT, dp / 2):
        for y in np.arange(0.5 * dp, flume.WIDTH, dp / 2):
            if s < 0:  # on the chute, |s| up the slope from the foot
                probes.append(s * along + 0.5 * dp * up + y * across), normals.append(up)
            else:
                probes.append(np.array([s, y, 0.5 * dp])), normals.append(np.array([0.0, 0.0, 1.0]))
    return np.array(probes), np.array(normals)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dp", type=float, default=0.04)
    dp = ap.parse_args().dp
    module = load_case_module("flume_3d")
    p = resolve_params(module, {"dp": str(dp)})
    case = build_case(module, p)
    walls = np.concatenate([w.points.everything()[0] for w in case.walls])
    surfaces = [read_surface(module.GEOMETRY / f"{name}.stl") for name in module.WALLS]
    kernel = Kernel(p["kernel"], p["h_factor"] * dp, 3)
    depth = support_layers(p["h_factor"]) * dp
    print(f"flume_3d at dp = {dp} m: wall push over the continuous wall's, dp/2 in front of the walls")
    for name, (probes, normals) in (("side walls", side_probes(dp)), ("floors about the foot", floor_probes(dp))):
        ratio = push_over_continuous(surfaces, walls, dp, depth, probes, normals, kernel)
        lo, hi = probes[ratio.argmin()], probes[ratio.argmax()]
        print(f"  {name}: {len(probes)} probes, lowest {ratio.min():.3f} at {np.round(lo, 3)}, "
              f"highest {ratio.max():.3f} at {np.round(hi, 3)}, below 0.9: {int((ratio < 0.9).sum())}")


if __name__ == "__main__":
    main()
