"""Where a block's clustered particles started: on its free edges, on its free faces or inside.

    .venv/bin/python scripts/block_edges.py RUN [FRAME_INDEX ...]

For a case that starts as a rectangular lattice block standing on a floor (cube_failure_3d, the 2D
cuts and columns), each moving particle of the run's first frame is placed by how many of the
block's free bounding planes it lies on (the sides and the top; the bottom stands on the floor):
0 inside, 1 a face, 2 an edge, 3 a corner (in 2D a block's corner is its "edge"). For each frame
(all but the first by default) it prints the clustered particles (nearer than dp/2 to another,
pairing.clustered_pairs) by where they and their nearest partners started, and the gaps between
each edge particle and its face neighbours of the first frame (1 dp apart then): median, 10 %
quantile and the share below dp/2, beside the median pressure of the edge and face particles.
000_ Eq. 37 leaves an edge particle unshifted (div r < 0.6 d) and moves the face particles beside
it towards it (docs/REMEDIES.md); these gaps show that crowding.
"""

import argparse

import numpy as np

from mpisph.instability import spacing
from mpisph.io.frames import list_frames, read_frame
from mpisph.neighbours import neighbour_lists
from mpisph.pairing import clustered_pairs

PLACES = ("inside", "face", "edge", "corner")


def starting_places(first):
    """Per moving particle of ``first`` (read_frame, moving only): the number of the block's free
    bounding planes it lies on, within dp/4 (the bottom plane, on the floor, is not free)."""
    x, dp = first["x"], spacing(first)
    lo, hi = x.min(axis=0), x.max(axis=0)
    on = (np.abs(x - lo) < 0.25 * dp) | (np.abs(x - hi) < 0.25 * dp)
    vertical = x.shape[1] - 1
    on[:, vertical] = np.abs(x[:, vertical] - hi[vertical]) < 0.25 * dp
    return on.sum(axis=1)


def edge_face_pairs(first, places):
    """(i, j): each edge particle of ``first`` and a face particle 1 dp from it there."""
    x, dp = first["x"], spacing(first)
    start, nbr = neighbour_lists(x, first["gid"], np.zeros(len(x), np.int8), len(x), 1.01 * dp, x.min(axis=0))
    i = np.repeat(np.arange(len(x)), np.diff(start))
    keep = (places[i] == 2) & (places[nbr] == 1)
    return i[keep], nbr[keep]


def describe(frame, first, places, pairs):
    """The lines this script prints for ``frame`` (read_frame of the same run, moving only)."""
    assert np.array_equal(frame["gid"], first["gid"]), "the frames hold other particles than the first"
    dp = spacing(first)
    i, j = clustered_pairs(frame)
    lines = [f"t = {frame['t']:.3g} s: {len(i)} of {len(frame['x'])} clustered ({100 * len(i) / len(frame['x']):.3f} %)"]
    count = np.zeros((4, 4), int)
    np.add.at(count, (places[i], places[j]), 1)
    lines.append("  started on (particle / nearest partner): " + ", ".join(
        f"{PLACES[a]}/{PLACES[b]} {count[a, b]}" for a in range(4) for b in range(4) if count[a, b]))
    a, b = pairs
    gap = np.linalg.norm(frame["x"][a] - frame["x"][b], axis=1) / dp
    lines.append(f"  edge-face gaps of the first frame ({len(gap)}) over dp: median {np.median(gap):.3f}, 10 % "
                 f"{np.quantile(gap, 0.1):.3f}, below 0.5: {100 * np.mean(gap < 0.5):.1f} %; median pressure: edges "
                 f"{np.median(frame['p'][places == 2]):.0f} Pa, faces {np.median(frame['p'][places == 1]):.0f} Pa")
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run")
    ap.add_argument("frames", nargs="*", type=int, help="frame indices (default: all but the first)")
    a = ap.parse_args()
    paths = list_frames(a.run)
    first = read_frame(paths[0])
    places = starting_places(first)
    pairs = edge_face_pairs(first, places)
    print(f"{a.run}: " + ", ".join(f"{np.sum(places == k)} {PLACES[k]}" for k in range(4)))
    for k in a.frames or range(1, len(paths)):
        print("\n".join(describe(read_frame(paths[k]), first, places, pairs)))


if __name__ == "__main__":
    main()
