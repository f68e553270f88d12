"""Symmetric tensors stored packed: the component order, and frames of format 1 (3 x 3 stresses)
still restart."""

import numpy as np
from mpi4py import MPI

from mpisph.case import RUN_PARAMS, Case
from mpisph.initial import particles_from_frame
from mpisph.io.frames import write_frame
from mpisph.materials import DruckerPrager
from mpisph.parts import make_parts
from mpisph.tensors import component, packed, unpacked

FULL = np.array([[[1.0, 4.0, 6.0], [4.0, 2.0, 5.0], [6.0, 5.0, 3.0]]])


def test_packed_order_is_vtk_symmetric_tensor_order():
    """xx, yy, zz, xy, yz, xz: what ParaView reads from a 6-component array."""
    np.testing.assert_array_equal(packed(FULL), [[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]])
    np.testing.assert_array_equal(unpacked(packed(FULL), 3), FULL)
    np.testing.assert_array_equal(packed(FULL[:, :2, :2]), [[1.0, 2.0, 4.0]])
    np.testing.assert_array_equal(unpacked(packed(FULL[:, :2, :2]), 2), FULL[:, :2, :2])
    for dim in (2, 3):
        rows = packed(FULL[:, :dim, :dim])[0]
        for a in range(dim):
            for b in range(dim):
                assert rows[component(dim, a, b)] == FULL[0, a, b]


def test_format_1_frame_with_full_tensors_is_packed_on_restart(tmp_path):
    n, dim = 4, 2
    rng = np.random.default_rng(1)
    stress = rng.normal(size=(n, 3, 3))
    stress = stress + stress.transpose(0, 2, 1)
    B = np.broadcast_to(np.array([[1.1, 0.2], [0.2, 0.9]]), (n, 2, 2))
    frame = {"gid": np.arange(n), "kind": np.zeros(n, np.int8), "x": rng.normal(size=(n, dim)),
             "v": np.zeros((n, dim)), "mass": np.ones(n), "rho": np.ones(n), "p": np.zeros(n),
             "normal": np.zeros((n, dim)), "stress": stress, "B": B, "plastic_strain": np.zeros(n)}
    soil = DruckerPrager(rho0=1850.0, E=1.8e6, nu=0.3, cohesion=0.0, phi=30.0, psi=0.0)
    case = Case(dim=dim, domain=((0.0, 0.0), (1.0, 1.0)), dp=0.1, material=soil, scheme="riemann_granular",
                bodies=[], gravity=(0.0, -9.81), stabilisers="utvf")
    parts = make_parts(case, {name: p.default for name, p in RUN_PARAMS.items()})
    path = str(tmp_path / "frame_00001.hdf")
    write_frame(path, MPI.COMM_SELF, frame, time=0.5, step=7, dim=dim, params={})  # tensors stored 3 x 3
    pa, t, step = particles_from_frame(MPI.COMM_SELF, path, parts)
    assert (t, step) == (0.5, 7)
    np.testing.assert_array_equal(unpacked(pa.stress, 3), stress)
    np.testing.assert_array_equal(unpacked(pa.B, 2), B)
