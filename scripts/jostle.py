"""How much of the pressure the particles' jostle carries in a run, frame by frame (docs/INCLINE.md).

    .venv/bin/python scripts/jostle.py RUN_DIR ... [--every 1]

For the particles moving at more than a fifth of the frame's largest speed, with a positive pressure:
the sum of their jostle pressure rho |v - <v>|^2 / D (measure.jostle_pressure, the velocity's departure
from its kernel mean) over the sum of their pressure p, and the pressure-weighted mean of the law's
inertial number I times dp / d where the frames hold it (mu(I) runs), whose square the jostle's share
follows (physics/mu_i.JOSTLE_STRESS). The kernel mean shares part of a particle's jostle with it, so
this share is below the momentum flux across a plane that scripts/incline_layers.py measures on an
incline (about 0.6 of it there).
"""

import argparse

import numpy as np

from mpisph.case import case_of_frame
from mpisph.io.frames import list_frames, read_frame
from mpisph.kernels import Kernel
from mpisph.materials import MuIGranular
from mpisph.measure import jostle_pressure


def frame_row(frame, kernel, dp, grain):
    """(t, flowing particles, jostle over pressure, pressure-weighted I dp / d or nan) of one frame."""
    speed = np.linalg.norm(frame["v"], axis=1)
    flowing = (speed > 0.2 * speed.max()) & (frame["p"] > 0.0)
    p = frame["p"][flowing]
    share = jostle_pressure(frame, kernel)[flowing].sum() / p.sum()
    I = frame.get("inertial_number")
    scaled = np.nan if I is None or grain is None else float(np.sum(I[flowing] * p) / p.sum() * dp / grain)
    return frame["t"], int(flowing.sum()), float(share), scaled


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--every", type=int, default=1, help="read every n-th frame")
    a = ap.parse_args()
    for run in a.runs:
        paths = list_frames(run)
        first = read_frame(paths[0])
        case = case_of_frame(first["params"])
        p = first["params"]
        grain = case.material.params.d0 if isinstance(case.material, MuIGranular) else None
        kernel = Kernel(p["kernel"], p["h_factor"] * p["dp"], case.dim)
        print(f"{run}: dp = {p['dp']:g} m" + (f", dp / d = {p['dp'] / grain:.3g}" if grain else ""))
        print(f"{'t [s]':>8} {'flowing':>8} {'jostle/p':>9} {'I dp/d':>7}")
        for path in paths[1::a.every]:
            t, count, share, scaled = frame_row(read_frame(path), kernel, p["dp"], grain)
            print(f"{t:8.3f} {count:8d} {share:9.5f} {scaled:7.3f}")


if __name__ == "__main__":
    main()
