"""How the clustered pairs of a run's last frame came together: by their velocities, or by a shift.

    .venv/bin/python scripts/pair_closing.py RUN_DIR [--from T]

For each particle of the last frame nearer than dp/2 to another (pairing.clustered_pairs), the change
of its distance to that partner since the frame at T (default: the run's first frame) is split into
the part the pair's relative velocity along the pair explains, the trapezoidal integral of
(v_i - v_j) . e_ij over the frames, and the rest, which a position shift (the transport-velocity
corrections, particle shifting) did without a velocity. With frames a few steps apart the split is
exact up to the trapezoid's error; docs/REMEDIES.md ('Remedies combined') reads artificial stress
beside UTVF this way.
"""

import argparse

import numpy as np

from mpisph import pairing
from mpisph.instability import spacing
from mpisph.io.frames import list_frames, read_frame


def closing(frames):
    """(distance change, the relative velocity's part) in units of the spacing, per clustered pair of
    the last of ``frames`` (moving particles in the same gid order in every frame)."""
    last = frames[-1]
    i, j = pairing.clustered_pairs(last)
    for f in frames:
        if not np.array_equal(f["gid"], last["gid"]):
            raise SystemExit("pair_closing: the frames hold different particles")
    t = np.array([f["t"] for f in frames])
    d = np.array([f["x"][i] - f["x"][j] for f in frames])  # frames x pairs x dim
    r = np.linalg.norm(d, axis=2)
    along = np.array([np.sum((f["v"][i] - f["v"][j]) * dk, axis=1) for f, dk in zip(frames, d)]) / r
    dp = spacing(last)
    return (r[-1] - r[0]) / dp, np.trapezoid(along, t, axis=0) / dp


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run")
    ap.add_argument("--from", dest="start", type=float, default=None, help="first frame's time [s]")
    a = ap.parse_args()
    frames = [read_frame(p) for p in list_frames(a.run)]
    if a.start is not None:
        frames = [f for f in frames if f["t"] >= a.start - 1e-12]
    change, by_velocity = closing(frames)
    print(f"{a.run}: {len(change)} clustered particles at t = {frames[-1]['t']:g} s, their pairs followed from "
          f"t = {frames[0]['t']:g} s over {len(frames)} frames")
    if len(change):
        print(f"  distance change: median {np.median(change):+.3f} dp")
        print(f"  by the relative velocity along the pair: median {np.median(by_velocity):+.3f} dp")
        print(f"  the rest, a shift without a velocity: median {np.median(change - by_velocity):+.3f} dp")


if __name__ == "__main__":
    main()
