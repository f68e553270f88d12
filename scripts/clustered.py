"""Which particles of a frame are clustered (nearer than dp/2 to another, mpisph/instability.py), and what they are.

    .venv/bin/python scripts/clustered.py FRAME [FRAME ...]

For each frame: how many moving particles are clustered, and how they split by free-surface class
(the frame's ``surface`` field: inner, near-surface, outermost, splashed), how many of the free-surface
ones UTVF leaves unshifted (000_ Eq. 37: div r < 0.6 d), by the sign of their pressure
(p = -tr(sigma)/3 for solids: tension is p < 0), by whether their nearest partner is a wall
particle and, in 3D, by whether 3D UTVF with utvf_edge_neighbours=kept would leave them unshifted; the median distance to that partner and the median height of the clustered particles. This
is the first thing to know when a clustering figure misses: tension inside the body, a free surface,
or a wall. Then, from the run's first frame in the same directory, how close each pair of moving
particles is against its first separation under the deformation fitted around it
(mpisph/pairing.py): a pair the material's own flow brought together, or one that came closer.
"""

import argparse
from pathlib import Path

import numpy as np

from mpisph import pairing, surface
from mpisph.instability import spacing
from mpisph.io.frames import list_frames, read_frame
from mpisph.neighbours import neighbour_lists
from mpisph.particles import MOVING
from mpisph.stabilisers.transport_velocity import NO_SHIFT_DIVERGENCE
from mpisph.tensors import SYM3

CLASSES = ("inner", "near-surface", "outermost", "splashed")


def _moving_first(frame):
    """(dp, the order that puts moving particles first, their count): the neighbour lists are built
    for the first rows."""
    moving = frame["kind"] == MOVING
    return spacing(frame), np.argsort(~moving, kind="stable"), int(moving.sum())


def shifted_on_the_surface(frame):
    """Mask of the free-surface particles (near-surface or outermost) that Eq. 37 shifts: div r >= 0.6 d."""
    return (np.isin(frame["surface"], (surface.NEAR_SURFACE, surface.SURFACE))
            & (frame["div_r"] >= NO_SHIFT_DIVERGENCE * frame["x"].shape[1]))


def beside_an_edge(frame):
    """Mask of the particles of ``shifted_on_the_surface`` that have a material neighbour with
    div r < 0.6 d within h: those 3D UTVF with utvf_edge_neighbours=kept leaves unshifted
    (stabilisers/transport_velocity.py)."""
    dp, order, n_moving = _moving_first(frame)
    kind = frame["kind"][order]
    h = float(frame["params"].get("h_factor", 1.3)) * dp
    start, nbr = neighbour_lists(frame["x"][order], frame["gid"][order], kind, n_moving, h, frame["x"].min(axis=0))
    low = (frame["div_r"][order] < NO_SHIFT_DIVERGENCE * frame["x"].shape[1]) & (kind == MOVING)
    below = np.concatenate([[0], np.cumsum(low[nbr])])  # low neighbours up to each list entry
    mask = np.zeros(len(kind), bool)
    mask[order[:n_moving]] = below[start[1:n_moving + 1]] > below[start[:n_moving]]
    return mask & shifted_on_the_surface(frame)


def pair_stress(frame, i, j):
    """For each pair (``i``, ``j``) of a solid's ``frame``: |cos| of the angle between the pair and
    the most compressive principal axis of the pair's mean stress, and that stress's normal
    component along the pair (tension positive)."""
    dim = frame["x"].shape[1]
    sigma = 0.5 * (frame["stress"][i] + frame["stress"][j])[:, SYM3][:, :dim, :dim]
    e = frame["x"][j] - frame["x"][i]
    e /= np.linalg.norm(e, axis=1)[:, None]
    _, axes = np.linalg.eigh(sigma)  # ascending: the most compressive first
    return np.abs(np.einsum("ka,ka->k", e, axes[:, :, 0])), np.einsum("ka,kab,kb->k", e, sigma, e)


def describe(path):
    frame = read_frame(path, walls=True)
    dim = frame["x"].shape[1]
    dp = spacing(frame)
    i, j = pairing.clustered_pairs(frame, walls=True)
    n = int(np.sum(frame["kind"] == MOVING))
    print(f"{path}: t = {frame['t']:.4g} s, {len(i)} of {n} moving particles clustered ({100 * len(i) / n:.3f} %)")
    if not len(i):
        return
    if "surface" in frame:
        counts = np.bincount(frame["surface"][i], minlength=len(CLASSES))
        print("  by class: " + ", ".join(f"{name} {c}" for name, c in zip(CLASSES, counts)))
    if "p" in frame:
        p = frame["p"][i]
        print(f"  in tension (p < 0): {int(np.sum(p < 0))}, median p {np.median(p):.4g} Pa")
    print(f"  nearest partner a wall particle: {int(np.sum(frame['kind'][j] != MOVING))}")
    if "div_r" in frame and "surface" in frame:
        free = np.isin(frame["surface"][i], (surface.NEAR_SURFACE, surface.SURFACE))
        print(f"  free-surface particles that Eq. 37 leaves unshifted (div r < 0.6 d): "
              f"{int(np.sum(free & ~shifted_on_the_surface(frame)[i]))} of {int(free.sum())}")
    if dim == 3 and "div_r" in frame:
        print(f"  free-surface particles beside an edge (utvf_edge_neighbours=kept leaves them unshifted): "
              f"{int(np.sum(beside_an_edge(frame)[i]))}")
    if "stress" in frame:
        along, normal = pair_stress(frame, i, j)
        print(f"  along the pair, the pair's mean stress: tensile {int(np.sum(normal > 0))}; |cos| with its most "
              f"compressive principal axis: median {np.median(along):.2f} (random directions: 0.5 in 3D, 0.71 in 2D)")
    d = np.linalg.norm(frame["x"][i] - frame["x"][j], axis=1) / dp
    height = frame["x"][i, -1]
    print(f"  distance to it: median {np.median(d):.3f} dp, smallest {d.min():.3f} dp; median height {np.median(height):.3g} m")
    first = list_frames(Path(path).parent)[0]
    if Path(first).resolve() != Path(path).resolve():
        first = read_frame(first, walls=True)
        i, j = pairing.clustered_pairs(frame)  # moving partners only: a wall has no deformation
        deformations = pairing.pair_deformations(frame, first, i, j)
        ratio, separation = pairing.affine_ratio(frame, first, i, j, deformations)
        stretch = np.linalg.svd(deformations[0], compute_uv=False)
        print(f"  first-frame distance: median {np.median(separation) / dp:.2f} dp; the fitted deformation's principal "
              f"stretches: median smallest {np.median(stretch[:, -1]):.2f}, largest {np.median(stretch[:, 0]):.2f}, "
              f"product {np.median(np.prod(stretch, axis=1)):.2f}")
        print(f"  distance over the first frame's separation under the fitted deformation: "
              f"median {np.median(ratio):.2f}, "
              f"10-90 % {np.percentile(ratio, 10):.2f}-{np.percentile(ratio, 90):.2f}; "
              f"within 10 % of it: {int(np.sum(np.abs(ratio - 1.0) < 0.1))}, paired (below "
              f"{pairing.PAIRED_RATIO}): {int(np.sum(ratio < pairing.PAIRED_RATIO))} (mpisph/pairing.py)")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("frames", nargs="+")
    for path in ap.parse_args().frames:
        describe(path)


if __name__ == "__main__":
    main()
