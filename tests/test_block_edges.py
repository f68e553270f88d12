"""scripts/block_edges.py on a hand-built block: where its particles start, and a face particle moved
against the edge beside it."""

import numpy as np

from repo_script import load_script

block_edges = load_script("block_edges")


def block(nx, dim):
    """A lattice block of nx^dim moving particles, dp = 1, as read_frame gives a frame."""
    x = np.stack(np.meshgrid(*[np.arange(nx, dtype=float)] * dim, indexing="ij"), -1).reshape(-1, dim)
    n = len(x)
    return {"x": x, "gid": np.arange(n), "kind": np.zeros(n, np.int8), "mass": np.ones(n), "rho": np.ones(n),
            "p": np.zeros(n), "t": 0.0}


def test_places_of_a_3d_block():
    """A 6^3 block on a floor: its 4 top corners, 36 free edge particles (5 on each vertical edge
    below its corner, 4 on each top edge between two), 96 on the free faces (16 on the top, 20 on
    each side) and 80 inside or on the bottom."""
    places = block_edges.starting_places(block(6, 3))
    assert np.bincount(places, minlength=4).tolist() == [80, 96, 36, 4]


def test_a_face_particle_against_its_edge():
    """Moved to 0.4 dp from the edge particle beside it, a face particle and that edge particle are
    the only clustered ones, each the other's nearest partner, and theirs is the one gap below dp/2."""
    first = block(6, 3)
    places = block_edges.starting_places(first)
    pairs = block_edges.edge_face_pairs(first, places)
    assert len(pairs[0]) == 2 * 16 + 2 * 20  # a top-edge particle has two face neighbours, a vertical one two
    edge = np.flatnonzero((first["x"] == [0, 0, 2]).all(axis=1))[0]  # on a vertical edge, below the top
    face = np.flatnonzero((first["x"] == [1, 0, 2]).all(axis=1))[0]  # beside it on the side face y = 0
    assert places[edge] == 2 and places[face] == 1
    frame = block(6, 3)
    frame["x"][face, 0] = 0.4
    lines = block_edges.describe(frame, first, places, pairs)
    assert lines[0].startswith("t = 0 s: 2 of 216 clustered")
    assert lines[1].endswith("face/edge 1, edge/face 1")
    assert f"below 0.5: {100 / len(pairs[0]):.1f} %" in lines[2]
