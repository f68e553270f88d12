"""Pictures of 3D runs, drawn off-screen with matplotlib: particles seen in perspective coloured by
speed at chosen times, and a field on a plane cut through the body.

``snapshots_png`` draws one panel per time: the moving particles of the frame nearest that time,
coloured by speed, drawn over every wall particle in light grey (so the walls between the eye and
the body do not hide it). ``slice_png`` draws the particles within
half a spacing of a plane, in the plane's own coordinates, coloured by a field; ``slice_grid_png``
draws several runs so, a row each.
"""

import os

import numpy as np

from .errors import InputError
from .instability import spacing
from .io.frames import frame_time, list_frames, read_frame
from .particles import MOVING

SPEED_LABEL = "speed |v| [m/s]"


def frames_at(out_dir, times):
    """The frames of the run in ``out_dir`` nearest each of ``times`` (walls included)."""
    paths = list_frames(os.fspath(out_dir))
    if not paths:
        raise InputError(f"no complete frames (frame_*.hdf) in {out_dir}")
    stamps = np.array([frame_time(p) for p in paths])
    return [read_frame(paths[int(np.argmin(np.abs(stamps - t)))], walls=True) for t in times]


def _figure(panels, width=5.0, height=4.2):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(width * panels + 1.0, height), dpi=120)
    FigureCanvasAgg(fig)
    return fig


def snapshots_png(out_dir, times, png_path, view=(25.0, -60.0), title=""):
    """Perspective views of the run in ``out_dir`` at ``times``, coloured by speed up to the 99.5th
    percentile of any of them; returns the path."""
    frames = frames_at(out_dir, times)
    speeds = [np.linalg.norm(f["v"][f["kind"] == MOVING], axis=1) for f in frames]
    top = max(float(np.percentile(s, 99.5)) for s in speeds if len(s)) or 1.0
    fig = _figure(len(frames))
    everything = np.concatenate([f["x"] for f in frames])
    lo, hi = everything.min(axis=0), everything.max(axis=0)
    for k, (f, s) in enumerate(zip(frames, speeds)):
        ax = fig.add_subplot(1, len(frames), k + 1, projection="3d")
        ax.computed_zorder = False  # the walls stay behind the body from every side
        moving = f["kind"] == MOVING
        walls = f["x"][~moving]
        ax.scatter(walls[:, 0], walls[:, 1], walls[:, 2], s=0.3, c="0.85", depthshade=False, rasterized=True,
                   zorder=1)
        x = f["x"][moving]
        sc = ax.scatter(x[:, 0], x[:, 1], x[:, 2], s=1.0, c=s, cmap="viridis", vmin=0.0, vmax=top,
                        depthshade=False, rasterized=True, zorder=2)
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
        ax.set_zlim(lo[2], hi[2])
        ax.set_box_aspect(hi - lo)
        ax.view_init(*view)
        ax.set_title(f"t = {f['t']:.2f} s", fontsize=10)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_zlabel("z [m]")
    bar = fig.colorbar(sc, ax=fig.axes, shrink=0.7, pad=0.02)
    bar.set_label(SPEED_LABEL)
    if title:
        fig.suptitle(title)
    fig.savefig(png_path, dpi=120, bbox_inches="tight", facecolor="white")
    return png_path


def plane_coordinates(x, origin, u, v):
    """Coordinates of points ``x`` in the plane origin + a u + b v (u, v orthonormal), and their
    distance from it."""
    u, v = np.asarray(u, float), np.asarray(v, float)
    d = np.asarray(x) - np.asarray(origin, float)
    n = np.cross(u, v)
    return d @ u, d @ v, np.abs(d @ n)


def slice_png(out_dir, times, png_path, origin, u, v, field="plastic_strain", label="", title=""):
    """The moving particles within dp/2 of the plane origin + a u + b v at ``times``, in the plane's
    coordinates (a along u, b along v), coloured by ``field`` up to its largest value in any of them;
    returns the path."""
    return slice_grid_png({"": out_dir}, times, png_path, origin, u, v, field, label, title)


def _colour_top(values, each):
    """The top of a panel's colour scale: the 99th percentile of ``values`` with ``each``, else their
    largest; 0 for no values."""
    if not len(values):
        return 0.0
    return float(np.percentile(values, 99)) if each else float(values.max())


def slice_grid_png(runs, times, png_path, origin, u, v, field="plastic_strain", label="", title="",
                   each=False):
    """``slice_png`` of several runs, a row per run ({row title: run directory}) and a panel per time,
    on shared axes. Coloured up to the field's largest value in any panel, or with ``each`` up to
    each panel's own 99th percentile (printed in its title), which shows where a field that grows
    by orders of magnitude over the times starts."""
    cuts = []
    for out_dir in runs.values():
        for f in frames_at(out_dir, times):
            moving = f["kind"] == MOVING
            if field not in f:
                raise InputError(f"the frames in {out_dir} have no field {field!r}")
            a, b, dist = plane_coordinates(f["x"][moving], origin, u, v)
            near = dist < 0.5 * spacing(f)
            cuts.append((f["t"], a[near], b[near], np.asarray(f[field][moving])[near]))
    tops = [_colour_top(value, each) for *_, value in cuts]
    shared = max(tops) or 1.0
    a_all = np.concatenate([c[1] for c in cuts])
    b_all = np.concatenate([c[2] for c in cuts])
    (a_lo, a_hi), (b_lo, b_hi) = (a_all.min(), a_all.max()), (min(0.0, b_all.min()), b_all.max())
    names, columns, rows = list(runs), len(times), len(runs)
    fig = _figure(columns, width=4.5, height=rows * (3.6 * max(0.3, (b_hi - b_lo) / max(a_hi - a_lo, 1e-12)) + 1.0))
    for k, ((t, a, b, value), top) in enumerate(zip(cuts, tops)):
        ax = fig.add_subplot(rows, columns, k + 1)
        vmax = (top or 1.0) if each else shared
        sc = ax.scatter(a, b, c=value, s=4.0, cmap="magma_r", vmin=0.0, vmax=vmax, linewidths=0, rasterized=True)
        ax.set_xlim(a_lo, a_hi)
        ax.set_ylim(b_lo, b_hi)
        ax.set_aspect("equal")
        name = names[k // columns]
        scale = f", colours to {vmax:.2g}" if each else ""
        ax.set_title(f"{name + ': ' if name else ''}t = {t:.2f} s{scale}", fontsize=9)
        ax.set_xlabel("along the cut [m]")
        ax.set_ylabel("height [m]")
        if each:
            fig.colorbar(sc, ax=ax, shrink=0.6, pad=0.02, ticks=[0.0, vmax], format="%.2g")
    if not each:
        bar = fig.colorbar(sc, ax=fig.axes, shrink=0.8, pad=0.02)
        bar.set_label(label or field)
    if title:
        fig.suptitle(title)
    fig.savefig(png_path, dpi=120, bbox_inches="tight", facecolor="white")
    return png_path
