"""The final deposit of a mu(I) column collapse against Lube's laws.

    .venv/bin/python scripts/collapse_deposit.py RUN [RUN ...]

For each run of ``lube_collapse_3d`` (the cylinder) or ``lube_collapse_2d``, from its first and last
frames: r_0 / dp and the layers the column was filled with, the runout ratio (r_inf - r_0) / r_0 as
scripts/validate.py measures it (measure.radial_runout, measure.runout) beside Lube's law
(references.axisymmetric_runout, planar_runout), the height of the deposit's centre (its top grain
within 0.3 r_0 of the axis or the back wall, plus dp / 2) over the column's, which Lube et al. found
undisturbed below a = 0.74 (axisymmetric) and 1.15 (planar), the deposit's surface height over
r_0 at 0.5, 0.75, 1, 1.25 and 1.5 r_0, the speed of the deposit's edge between the last two
frames over the front's peak speed (measure.edge_rest_ratio, at most 1e-3 at rest), and the grains
beyond the connected deposit's edge (measure.beyond_the_edge): how many, and how far the farthest
lies beyond r_0, over r_0.
"""

import argparse
from pathlib import Path

import numpy as np

from mpisph import measure, references
from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import list_frames, read_frame

STATIONS = (0.5, 0.75, 1.0, 1.25, 1.5)  # radii / r_0 of the surface profile


def deposit(run):
    """The figures of the module docstring for one run, as a dict."""
    frames = list_frames(run)
    first, before, last = (read_frame(frames[k]) for k in (0, -2, -1))
    diag = read_diagnostics(Path(run) / "diagnostics.csv")
    p = last["params"]
    dp, a = float(p["dp"]), float(p["a"])
    radial = p["case"] == "lube_collapse_3d"
    length = float(p["r_0"] if radial else p["L_0"])
    x = last["x"]
    distance = np.hypot(x[:, 0], x[:, 1]) if radial else x[:, 0]
    height = x[:, -1]
    top0 = first["x"][:, -1].max() + 0.5 * dp
    extent = measure.radial_runout(last, dp) if radial else measure.runout(last, dp)
    beyond = measure.beyond_the_edge(last, dp, radial=radial)
    law = references.axisymmetric_runout(a) if radial else references.planar_runout(a)
    surface = []
    for station in STATIONS:
        near = np.abs(distance - station * length) < dp
        surface.append((height[near].max() + 0.5 * dp) / length if near.any() else 0.0)
    return {"a": a, "radial": radial, "resolution": length / dp, "layers": int(round(top0 / dp)),
            "t": float(last["t"]), "ratio": (extent - length) / length, "law": float(law),
            "centre": (height[distance < 0.3 * length].max() + 0.5 * dp) / top0, "surface": surface,
            "rest": measure.edge_rest_ratio(before, last, diag["t"], diag["front"], dp, radial=radial),
            "beyond": int(beyond.sum()), "farthest": (distance.max() + 0.5 * dp - length) / length}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+")
    for run in ap.parse_args().runs:
        d = deposit(run)
        symbol = "r_0" if d["radial"] else "L_0"
        print(f"{run}: {'axisymmetric' if d['radial'] else 'planar'} a = {d['a']:g}, {symbol} / dp = {d['resolution']:.1f} "
              f"({d['layers']} layers), t = {d['t']:.3g} s: runout ratio {d['ratio']:.3f} against Lube's "
              f"{d['law']:.3f} ({100 * (d['ratio'] / d['law'] - 1):+.1f} %); centre height / H_0 "
              f"{d['centre']:.3f}; surface / {symbol} at " + ", ".join(f"{s:g}" for s in STATIONS) + f" {symbol}: "
              + " ".join(f"{s:.3f}" for s in d["surface"]) + f"; edge speed / peak front speed {d['rest']:.1e}; "
              f"{d['beyond']} grains beyond the edge, the farthest grain's edge at {d['farthest']:.3f}")


if __name__ == "__main__":
    main()
