"""The last frames of several runs, one panel each, coloured by a field: docs/REMEDIES.md's pictures.

    .venv/bin/python scripts/remedy_panels.py OUT.png TITLE=RUN_DIR ... [--field plastic_strain]
        [--vmax 1.0] [--xlim 0 5.5]
"""

import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from mpisph.io.frames import list_frames, read_frame  # noqa: E402
from run_check import run_params  # noqa: E402 (this directory)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("runs", nargs="+", metavar="TITLE=RUN_DIR")
    ap.add_argument("--field", default="plastic_strain")
    ap.add_argument("--vmax", type=float, default=1.0)
    ap.add_argument("--xlim", type=float, nargs=2)
    a = ap.parse_args()
    if not a.out.lower().endswith(".png"):
        ap.error(f"{a.out}: the picture is a PNG, its name ends in .png")
    runs = []
    for item in a.runs:
        if "=" not in item:
            ap.error(f"{item!r}: give each run as TITLE=RUN_DIR")
        runs.append(item.split("=", 1))
        run_params(ap, runs[-1][1], (), "run directories")
        if a.field not in read_frame(list_frames(runs[-1][1])[-1]):
            ap.error(f"{runs[-1][1]}: its frames have no field {a.field!r} (--field)")
    fig, axes = plt.subplots(len(runs), 1, figsize=(8, 2.3 * len(runs)), squeeze=False)
    for ax, (title, run) in zip(axes[:, 0], runs):
        frame = read_frame(list_frames(run)[-1])
        x = frame["x"]
        sc = ax.scatter(x[:, 0], x[:, 1], c=np.minimum(frame[a.field], a.vmax), s=0.3, vmin=0.0, vmax=a.vmax)
        ax.set_aspect("equal")
        if a.xlim:
            ax.set_xlim(*a.xlim)
        ax.set_title(f"{title}, t = {frame['t']:.2f} s", fontsize=9)
        fig.colorbar(sc, ax=ax, label=a.field, shrink=0.8)
    fig.tight_layout()
    fig.savefig(a.out, dpi=55)


if __name__ == "__main__":
    main()
