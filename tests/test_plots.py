"""Serial tests of the deposit picture (mpisph.plots) and of ``python -m mpisph plot``."""

import numpy as np
import pytest
from mpi4py import MPI

from mpirun import mpisph, stderr_lines
from mpisph.errors import InputError
from mpisph.io.frames import frame_path, write_frame
from mpisph.plots import SPEED_LABEL, STRAIN_LABEL, colour_field, deposit_png

DP = 0.01
PARAMS = {"case": "fake_collapse", "dp": DP}


def fields(t, strain=True):
    """A 20 x 10 column on a two-layer floor; at t > 0 it has slumped to the right."""
    i, j = np.meshgrid(np.arange(20), np.arange(10), indexing="ij")
    x = (np.c_[i.ravel(), j.ravel()] + 0.5) * DP
    x[:, 0] += t * x[:, 1] * 3.0
    x[:, 1] *= 1.0 - 0.5 * t
    wi, wj = np.meshgrid(np.arange(-3, 60), np.arange(-2, 0), indexing="ij")
    walls = (np.c_[wi.ravel(), wj.ravel()] + 0.5) * DP
    n, nw = len(x), len(walls)
    out = {
        "x": np.r_[x, walls],
        "gid": np.arange(n + nw, dtype=np.int64),
        "kind": np.r_[np.zeros(n, np.int8), np.ones(nw, np.int8)],
        "mass": np.full(n + nw, 2000.0 * DP**2),
        "rho": np.full(n + nw, 2000.0),
        "v": np.r_[np.c_[t * x[:, 1], -t * np.ones(n)], np.zeros((nw, 2))],
    }
    if strain:
        out["plastic_strain"] = np.r_[t * x[:, 0] / DP, np.zeros(nw)]
    return out


def fake_run(directory, strain=True):
    directory.mkdir(exist_ok=True)
    for index, t in enumerate((0.0, 0.5)):
        write_frame(frame_path(str(directory), index), MPI.COMM_SELF, fields(t, strain), time=t,
                    step=10 * index, dim=2, params=PARAMS)
    return directory


def assert_png(path):
    with open(path, "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"


def test_deposit_png_default_path(tmp_path):
    run = fake_run(tmp_path / "run")
    path = deposit_png(run)
    assert path == str(run / "deposit.png")
    assert_png(path)


@pytest.mark.parametrize("strain", [True, False])
def test_deposit_png_given_path(tmp_path, strain):
    run = fake_run(tmp_path / "run", strain)
    path = deposit_png(run, tmp_path / "picture.png")
    assert path == str(tmp_path / "picture.png")
    assert_png(path)


@pytest.mark.parametrize("strain", [True, False])
def test_moving_particles_coloured_by_plastic_strain_else_by_speed(strain):
    """A frame with plastic_strain (the Drucker-Prager schemes) is coloured by it; without (fluids,
    elastic solids, mu(I) grains) by the speed; the walls are left out."""
    frame = fields(0.5, strain)
    moving = frame["kind"] == 0
    value, label, _ = colour_field(frame, moving)
    assert len(value) == 200
    if strain:
        np.testing.assert_array_equal(value, frame["plastic_strain"][:200])
        assert label == STRAIN_LABEL
    else:
        np.testing.assert_allclose(value, np.hypot(frame["v"][:200, 0], frame["v"][:200, 1]), rtol=1e-15)
        assert label == SPEED_LABEL


def test_no_frames(tmp_path):
    (tmp_path / "frame_00000.hdf.part").write_bytes(b"partial")
    with pytest.raises(InputError, match="no complete frames") as err:
        deposit_png(tmp_path)
    assert "\n" not in str(err.value)
    with pytest.raises(InputError, match="no such directory"):
        deposit_png(tmp_path / "missing")
    with pytest.raises(InputError, match="frame_00000.hdf.part is a file: plot takes the directory of a run"):
        deposit_png(tmp_path / "frame_00000.hdf.part")
    with pytest.raises(InputError, match="plot writes a PNG, its name ends in .png"):
        deposit_png(tmp_path, tmp_path / "deposit.txt")


def test_cli_plot(tmp_path):
    run = fake_run(tmp_path / "run")
    result = mpisph(["plot", run], timeout=120)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == f"wrote {run / 'deposit.png'}"
    assert_png(run / "deposit.png")
    result = mpisph(["plot", run, tmp_path / "other.png"], timeout=120)
    assert result.returncode == 0, result.stderr
    assert "wrote" in result.stdout
    assert_png(tmp_path / "other.png")


def test_cli_plot_names_a_frame_file_it_left_out(tmp_path):
    """A last frame cut short (a run killed while writing it) is not drawn, and plot says so."""
    run = fake_run(tmp_path / "run")
    cut = frame_path(str(run), 2)
    with open(frame_path(str(run), 1), "rb") as f, open(cut, "wb") as g:
        g.write(f.read(3000))
    result = mpisph(["plot", run], timeout=120)
    assert result.returncode == 0, result.stderr
    lines = stderr_lines(result.stderr)
    assert len(lines) == 1 and lines[0].startswith(f"mpisph: warning: left out {cut} (") and "truncated" in lines[0]


@pytest.mark.parametrize("args, fragment", [
    (["plot"], "usage: python -m mpisph plot OUT_DIR [PNG]"),
    (["plot", "a", "b", "c"], "usage: python -m mpisph plot OUT_DIR [PNG]"),
    (["plot", "EMPTY"], "no complete frames"),
])
def test_cli_plot_errors(tmp_path, args, fragment):
    args = [str(tmp_path) if a == "EMPTY" else a for a in args]
    result = mpisph(args, timeout=120)
    lines = stderr_lines(result.stderr)
    assert result.returncode == 2 and "Traceback" not in result.stderr
    assert len(lines) == 1 and lines[0].startswith("mpisph: error: "), result.stderr
    assert fragment in lines[0], lines[0]
    assert not list(tmp_path.iterdir())
