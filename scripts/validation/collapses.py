"""What the mu(I) column collapses share (004_ Sec. 5.2): one run and its measures (runout, rest, onset,
the share of the dissipation where the law is ill-posed), and the rows and panels built from them."""

import numpy as np

from mpisph import measure
from mpisph.case import case_of_frame
from mpisph.well_posedness import ill_posed_energy_share, well_posed_window

from .runs import run


def collapse(case, a, length, dp, ranks, radial, variant=(), t_end=None, n_frames=20):
    """One mu(I) collapse of aspect ratio ``a`` (column length or radius ``length``) to ``t_end``,
    by default 6 sqrt(H_0/g) (at least 0.6 s), with ``n_frames`` frames: its diagnostics, last frame,
    command, runout ratio, how far from rest it is between its last two frames
    (measure.edge_rest_ratio), and its onset (measure.collapse_onset)."""
    H0 = a * length
    default_end = max(0.6, 6.0 * np.sqrt(H0 / 9.81))
    settings = [f"a={a}", f"dp={dp:.12g}", *variant]
    name = f"{case}_" + "_".join(s.replace("=", "") for s in settings)
    if t_end is None:
        t_end = default_end
    else:
        name += f"_to{t_end:g}"
    if n_frames != 20:
        name += f"_frames{n_frames}"
    frames, diag, shown = run(name, case, ["--set", *settings, "--t-end", f"{t_end:.3g}", "--output-interval",
                                           f"{t_end / n_frames:.3g}"], ranks)
    last = frames[-1]
    extent = measure.radial_runout(last, dp) if radial else measure.runout(last, dp)
    rest = measure.edge_rest_ratio(frames[-2], last, diag["t"], diag["front"], dp, radial=radial)
    window = well_posed_window(case_of_frame(last["params"]).material.params)
    return {"a": a, "H0": H0, "dp": dp, "length": length, "radial": radial, "diag": diag, "last": last,
            "cmd": shown, "ratio": (extent - length) / length, "rest": rest, "t_end": last["t"],
            "onset": measure.collapse_onset(diag["t"], diag["front"], length), "window": window,
            "ill_posed": ill_posed_energy_share(frames, window)}


def ill_posed_row(runs, label):
    """The share of each run's dissipated energy at inertial numbers where its mu(I) is ill-posed
    (mpisph/well_posedness.py; docs/COLLAPSES.md)."""
    window = runs[0]["window"]
    where = f"outside {window[0]:.3g} < I < {window[1]:.3g}" if window else "at every I"
    return (f"share of the energy dissipated where the law is ill-posed ({where}; Barker et al. 2015) at {label}",
            " / ".join(f"{r['ill_posed']:.3f}" for r in runs), "-", "-", "-")


def centre(r):
    """The deposit's top within 0.3 of the column's length (radius) from its back wall (axis), over
    H_0: 1 where the top stays undisturbed (scripts/collapse_deposit.py's centre)."""
    return measure.deposit_height(r["last"], r["dp"], 0.3 * r["length"], radial=r["radial"]) / r["H0"]


def farthest(r):
    """The farthest grain's edge beyond the column, over its length (radius)."""
    return measure.farthest_edge(r["last"], r["dp"], r["radial"]) / r["length"] - 1.0


def front_panel(ax, runs, length, symbol):
    for r in runs:
        scale = np.sqrt(r["H0"] / 9.81)
        ax.plot(r["diag"]["t"] / scale, (r["diag"]["front"] - r["diag"]["front"][0]) / length, label=f"a = {r['a']:g}")
    ax.set_xlabel("t / sqrt(H_0 / g)")
    ax.set_ylabel(f"front advance / {symbol}_0")
    ax.legend(fontsize=7)


def rest_row(r, what):
    return (f"a = {r['a']:g}: speed of {what} over the last frame interval / peak front speed", f"{r['rest']:.1e}",
            f"<= {measure.AT_REST:g}", "-", f"{measure.AT_REST:g}", r["rest"] <= measure.AT_REST)
