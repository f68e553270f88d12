"""Pictures of a run: ``deposit_png`` draws the last frame of a run as a PNG.

matplotlib is imported inside the functions (Agg canvas, no pyplot), so
``import mpisph`` and ``import mpisph.plots`` stay light.
"""

import os

import numpy as np

from mpisph.errors import InputError
from mpisph.io import list_frames, read_frame

STRAIN_LABEL = "accumulated deviatoric plastic strain [-]"
SPEED_LABEL = "speed |v| [m/s]"
REFINE = 4  # sub-cells per particle spacing when tracing the initial outline


def _spacing(frame, dim):
    """Particle spacing dp: median of (mass/rho)^(1/dim), else params['dp'], else area / n."""
    if "mass" in frame and "rho" in frame and len(frame["mass"]):
        volume = frame["mass"] / frame["rho"]
        volume = volume[np.isfinite(volume) & (volume > 0)]
        if len(volume):
            return float(np.median(volume) ** (1.0 / dim))
    dp = frame["params"].get("dp")
    if isinstance(dp, (int, float)) and dp > 0:
        return float(dp)
    x = frame["x"]
    extent = np.ptp(x, axis=0) if len(x) else np.ones(dim)
    return float(np.prod(np.maximum(extent, 1e-12)) / max(len(x), 1)) ** (1.0 / dim)


def _occupancy(points, dp):
    """Cells of size dp holding a particle, holes of one cell closed; (grid, origin)."""
    origin = points.min(axis=0) - 2 * dp
    idx = np.rint((points - origin) / dp).astype(np.int64)
    grid = np.zeros(tuple(idx.max(axis=0) + 3), dtype=bool)
    grid[idx[:, 0], idx[:, 1]] = True

    def shifted(g, op):
        out = g.copy()
        for i in (-1, 0, 1):
            for j in (-1, 0, 1):
                out = op(out, np.roll(np.roll(g, i, axis=0), j, axis=1))
        return out

    closed = shifted(shifted(grid, np.logical_or), np.logical_and)  # dilate, then erode
    return closed, origin


def _outline(ax, points, dp):
    """Dashed black line around the particle cloud ``points``, dp/2 outside the outer centres."""
    if len(points) == 0:
        return
    grid, origin = _occupancy(points, dp)
    fine = np.kron(grid, np.ones((REFINE, REFINE))).astype(float)
    centres = [origin[a] - dp / 2 + (np.arange(fine.shape[a]) + 0.5) * dp / REFINE for a in (0, 1)]
    ax.contour(centres[0], centres[1], fine.T, levels=[0.5], colors="k",
               linestyles="--", linewidths=1.0, zorder=3)


def _view(moving, walls, dp):
    """Axis limits: the moving particles of the first and last frame, padded.

    Walls just beyond them along an axis (the floor under them, a back wall beside them, within
    three paddings) are shown whole along it; walls further out (an open tank's far end, tall
    side walls, a wide floor's ends) are cut off at the padding.
    """
    lo, hi = moving.min(axis=0), moving.max(axis=0)
    pad = max(0.05 * float(np.max(hi - lo)), 4 * dp)
    view_lo, view_hi = lo - pad, hi + pad
    for a in range(len(lo)):
        others = [b for b in range(len(lo)) if b != a]
        beside = np.all((walls[:, others] >= lo[others]) & (walls[:, others] <= hi[others]), axis=1)
        below = beside & (walls[:, a] >= view_lo[a] - 2 * pad) & (walls[:, a] < lo[a])
        above = beside & (walls[:, a] <= view_hi[a] + 2 * pad) & (walls[:, a] > hi[a])
        if below.any():
            view_lo[a] = min(view_lo[a], walls[below, a].min() - dp / 2)
        if above.any():
            view_hi[a] = max(view_hi[a], walls[above, a].max() + dp / 2)
    return view_lo, view_hi


def colour_field(frame, moving):
    """(value per moving particle, colour-bar label, colour map) of the picture: the accumulated
    deviatoric plastic strain where the frame has it (the Drucker-Prager schemes), else the speed."""
    if "plastic_strain" in frame:
        return frame["plastic_strain"][moving], STRAIN_LABEL, "magma_r"
    if "v" in frame:
        return np.linalg.norm(frame["v"][moving], axis=1), SPEED_LABEL, "viridis"
    return np.zeros(int(np.count_nonzero(moving))), "", "viridis"


def deposit_png(out_dir, png_path=None):
    """Draw the last frame of the run in ``out_dir`` as a PNG and return its path.

    Moving particles are coloured by the accumulated deviatoric plastic strain
    (by speed when the frames have no ``plastic_strain``), wall particles are
    light grey, and a dashed line is the outline of the body in the first frame.
    Default ``png_path``: ``<out_dir>/deposit.png``. 3D runs are seen along
    y (x horizontal, z vertical).
    """
    out_dir = os.fspath(out_dir)
    if os.path.isfile(out_dir):
        raise InputError(f"{out_dir} is a file: plot takes the directory of a run")
    if not os.path.isdir(out_dir):
        raise InputError(f"{out_dir}: no such directory")
    if png_path is not None and not os.fspath(png_path).lower().endswith(".png"):
        raise InputError(f"{png_path}: plot writes a PNG, its name ends in .png")
    frames = list_frames(out_dir)
    if not frames:
        raise InputError(f"no complete frames (frame_*.hdf) in {out_dir}")
    png_path = os.fspath(png_path) if png_path is not None else os.path.join(out_dir, "deposit.png")

    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    first = read_frame(frames[0])
    last = read_frame(frames[-1], walls=True)
    dim = last["dim"]
    axes = (0, dim - 1)  # horizontal, vertical
    names = ("x", "y" if dim == 2 else "z")
    wall = last["kind"] != 0
    x = last["x"][~wall][:, axes]
    walls = last["x"][wall][:, axes]
    x0 = first["x"][:, axes]
    dp = _spacing(first if len(first["x"]) else last, dim)

    value, label, cmap = colour_field(last, ~wall)
    # colour scale up to the 99.5th percentile, so that a few runaway particles do not wash it out
    finite = value[np.isfinite(value)]
    top = float(finite.max()) if len(finite) else 0.0
    vmax = float(np.percentile(finite, 99.5)) if len(finite) else 0.0
    if top <= 1.1 * vmax or vmax <= 0.0:
        vmax = top if top > 0.0 else 1.0
    clipped = top > vmax

    cloud = np.concatenate([p for p in (x, x0) if len(p)]) if len(x) or len(x0) else walls
    if len(cloud) == 0:
        cloud = np.zeros((1, 2))
    lo, hi = _view(cloud, walls, dp)
    span = hi - lo
    width = 10.0
    height = float(np.clip(width * span[1] / span[0], 2.5, 12.0)) + 1.2

    fig = Figure(figsize=(width + 1.8, height), dpi=150)
    FigureCanvasAgg(fig)
    ax = fig.add_axes([0.08, 0.12, 0.78, 0.78])
    cax = fig.add_axes([0.88, 0.12, 0.02, 0.78])
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal", adjustable="box")
    ax.apply_aspect()
    # the colour bar follows the axes' height once the aspect has shrunk it
    box = ax.get_position()
    cax.set_position([box.x1 + 0.015, box.y0, 0.02, box.height])

    # marker diameter = dp in points, so that neighbouring particles just touch
    (x_a, _), (x_b, _) = ax.transData.transform([(0.0, 0.0), (1.0, 0.0)])
    points_per_m = (x_b - x_a) * 72.0 / fig.dpi
    size = max((dp * points_per_m) ** 2, 0.05)

    if len(walls):
        ax.scatter(walls[:, 0], walls[:, 1], s=size, c="0.82", marker="o", linewidths=0,
                   zorder=1, rasterized=True)
    order = np.argsort(value, kind="stable")  # strained particles on top
    sc = ax.scatter(x[order, 0], x[order, 1], s=size, c=value[order], cmap=cmap, vmin=0.0, vmax=vmax,
                    marker="o", linewidths=0, zorder=2, rasterized=True)
    _outline(ax, x0, dp)
    bar = fig.colorbar(sc, cax=cax, extend="max" if clipped else "neither")
    bar.set_label(label)

    ax.set_xlabel(f"{names[0]} [m]")
    ax.set_ylabel(f"{names[1]} [m]")
    case = last["params"].get("case", os.path.basename(os.path.normpath(out_dir)))
    ax.set_title(f"{case}: t = {last['t']:.3g} s, {len(x)} particles "
                 f"(dashed: body at t = {first['t']:.3g} s)")
    try:
        fig.savefig(png_path, dpi=150, bbox_inches="tight", facecolor="white")
    except OSError as e:
        raise InputError(f"cannot write {png_path}: {e.strerror or e}") from None
    return png_path
