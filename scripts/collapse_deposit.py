"""The final deposit of a mu(I) column collapse against Lube's laws.

    .venv/bin/python scripts/collapse_deposit.py RUN [RUN ...]

For each run of ``lube_collapse_3d`` (the cylinder) or ``lube_collapse_2d``, from its first and last
frames: r_0 / dp and the layers the column was filled with, the runout ratio (r_inf - r_0) / r_0 as
scripts/validate.py measures it (measure.radial_runout, measure.runout) beside Lube's law
(references.axisymmetric_runout, planar_runout), the height of the deposit's centre (its top grain
within 0.3 r_0 of the axis or the back wall, plus dp / 2) over the column's, which Lube et al. found
undisturbed below a = 0.74 (axisymmetric) and 1.15 (planar), the deposit's surface height over
r_0 at 0.5, 0.75, 1, 1.25 and 1.5 r_0, the speed of the deposit's edge between the last two
frames over the front's peak speed (measure.edge_rest_ratio, at most 1e-3 at rest), the onset
(measure.collapse_onset: when the front, the farthest grain of diagnostics.csv, has first moved
0.05 r_0 from its start), and the grains beyond the connected deposit's edge
(measure.beyond_the_edge): how many, and how far the farthest lies beyond r_0, over r_0, and how
far beyond r_0, over r_0, 90, 95 and 99 % of the mass lie (measure.mass_extent).

With ``--at T [T ...]`` it measures each run at the frame nearest each time T instead of at its last
frame (the edge speed between that frame and the one before; nan at the first frame), so that one
run gives the deposit against time: whether the runout and the centre's height still change once
the collapse is over. A run restarted into a directory of its own, whose first frame is not the
column at t = 0, is refused.

With ``--ensemble`` it also prints, for the runs of each shape, a and r_0 / dp (for example the same
column run with frames at other times, hence other sequences of time steps), the mean runout
ratio and 95 and 99 % mass extents with their least and greatest, and how many of the runs' edges
move faster than 1e-3 of the peak front speed at the end; and, for the planar runs of each length /
dp that include columns a <= 1 and two a >= 4, Lube et al.'s (2005) fits of those means
(measure.planar_runout_fits: the low-a slope through the origin, 1.2 for their sand, and the
high-a exponent, 2/3).

With ``--profile STEP`` it also prints, for all the runs side by side, the deposit's surface height over
r_0 at every STEP r_0 from STEP to the farthest grain (0 where no grain lies within dp of the station),
so that runs at different spacings can be compared along the whole deposit; ``--plot PNG`` draws the
surfaces (the top of each dp-wide bin plus dp / 2) of all the runs in one picture.
"""

import argparse
from pathlib import Path

import numpy as np

from mpisph import measure, references
from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import frame_time, list_frames, read_frame
from run_check import run_params  # (this directory)

STATIONS = (0.5, 0.75, 1.0, 1.25, 1.5)  # radii / r_0 of the surface profile
FRACTIONS = (0.9, 0.95, 0.99)  # of the mass, for measure.mass_extent


def surface_at(frame, dp, radial, length, stations):
    """The deposit's surface height over ``length`` at each of ``stations`` (distances over
    ``length`` from the axis or the back wall): the top grain within dp of the station plus dp / 2,
    0 where there is none."""
    x = frame["x"]
    distance = measure.outward_distance(x, radial) / length
    out = []
    for station in stations:
        near = np.abs(distance - station) < dp / length
        out.append((x[near, -1].max() + 0.5 * dp) / length if near.any() else 0.0)
    return out


def surface_line(frame, dp, radial, length):
    """The deposit's surface over ``length`` against the distance over ``length`` (bin centres),
    from measure.surface_profile on (distance from the axis or the back wall, height)."""
    x = frame["x"]
    distance = measure.outward_distance(x, radial)
    centres, top = measure.surface_profile({"x": np.column_stack([distance, x[:, -1]])}, dp)
    return centres / length, top / length


def deposit(run, at=None):
    """The figures of the module docstring for one run, as a dict: at its last frame, or at the
    frame nearest the time ``at``."""
    frames = list_frames(run)
    if not frames:
        raise SystemExit(f"{run}: no frames (a run's output directory is expected)")
    k = len(frames) - 1 if at is None else int(np.argmin([abs(frame_time(f) - at) for f in frames]))
    first, before, last = (read_frame(frames[i]) for i in (0, max(k - 1, 0), k))
    diag = read_diagnostics(Path(run) / "diagnostics.csv")
    p = last["params"]
    dp, a = float(p["dp"]), float(p["a"])
    in_3d = p["case"] == "lube_collapse_3d"
    radial = in_3d and p.get("shape", "cylinder") == "cylinder"  # shape=slab: the planar column in 3D
    length = float(p["r_0"] if in_3d else p["L_0"])
    top0 = first["x"][:, -1].max() + 0.5 * dp
    extent = measure.radial_runout(last, dp) if radial else measure.runout(last, dp)
    beyond = measure.beyond_the_edge(last, dp, radial=radial)
    law = references.axisymmetric_runout(a) if radial else references.planar_runout(a)
    surface = surface_at(last, dp, radial, length, STATIONS)
    return {"a": a, "radial": radial, "resolution": length / dp, "layers": int(round(top0 / dp)),
            "t": float(last["t"]), "ratio": (extent - length) / length, "law": float(law),
            "centre": measure.deposit_height(last, dp, 0.3 * length, radial=radial) / top0, "surface": surface,
            "rest": (measure.edge_rest_ratio(before, last, diag["t"], diag["front"], dp, radial=radial) if k > 0
                     else float("nan")),  # the first frame has none before it
            "onset": measure.collapse_onset(diag["t"], diag["front"], length),
            "beyond": int(beyond.sum()), "farthest": measure.farthest_edge(last, dp, radial) / length - 1.0,
            "extents": [(measure.mass_extent(last, q, radial=radial) - length) / length for q in FRACTIONS],
            "frame": last, "dp": dp, "length": length}


def profile_table(deposits, step):
    """Lines of the surface heights of ``deposits`` (dicts of ``deposit``) side by side, at every
    ``step`` from ``step`` to the farthest grain of any of them."""
    end = max(1.0 + d["farthest"] for d in deposits)
    stations = np.arange(1, int(end / step) + 1) * step
    columns = [surface_at(d["frame"], d["dp"], d["radial"], d["length"], stations) for d in deposits]
    lines = ["distance " + " ".join(f"{d['resolution']:>7.1f}" for d in deposits) + "  (surface / length at "
             "distance / length; columns: the runs' length / dp)"]
    for k, station in enumerate(stations):
        lines.append(f"{station:8.2f} " + " ".join(f"{c[k]:7.3f}" for c in columns))
    return lines


def ensemble_table(deposits):
    """Lines of the ``--ensemble`` summary (module docstring) of ``deposits`` (dicts of ``deposit``),
    a line for each shape (planar first), a and r_0 / dp, sorted by the three, then the planar fits of
    each spacing that allows them."""
    groups, means = {}, {}
    for d in deposits:
        groups.setdefault((d["radial"], d["a"], round(d["resolution"], 1)), []).append(d)
    lines = ["shape a length/dp runs: runout ratio, 95 % and 99 % of the mass within, as mean (least-greatest); "
             "runs whose edge moves at the end"]
    for (radial, a, resolution), runs in sorted(groups.items()):
        columns = [[d["ratio"] for d in runs]]
        columns += [[d["extents"][FRACTIONS.index(q)] for d in runs] for q in (0.95, 0.99)]
        moving = sum(d["rest"] > measure.AT_REST for d in runs)
        lines.append(f"{'axisymmetric' if radial else 'planar'} {a:g} {resolution:g} {len(runs)}: "
                     + "; ".join(f"{np.mean(c):.3f} ({min(c):.3f}-{max(c):.3f})" for c in columns)
                     + f"; {moving} of {len(runs)}")
        means.setdefault((radial, resolution), {})[a] = [np.mean(c) for c in columns]
    for (radial, resolution), by_a in sorted(means.items()):
        a = np.array(sorted(by_a))
        if radial or not (np.any(a <= 1.0) and np.sum(a >= 4.0) >= 2):
            continue
        fits = [measure.planar_runout_fits(a, [by_a[x][k] for x in a]) for k in range(3)]
        lines.append(f"planar fits at L_0 / dp = {resolution:g} (a = " + ", ".join(f"{x:g}" for x in a)
                     + "): low-a slope and high-a exponent of the runout ratio"
                     + "; of 95 % and of 99 % of the mass: " + "; ".join(f"{s:.3f} {e:.3f}" for s, e in fits))
    return lines


def plot_surfaces(deposits, png):
    """The surfaces of ``deposits`` against the distance, both over the column's length, into ``png``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 3.5))
    symbol = "r_0" if deposits[0]["radial"] else "L_0"
    for d in deposits:
        x, top = surface_line(d["frame"], d["dp"], d["radial"], d["length"])
        ax.step(x, top, where="mid", label=f"a = {d['a']:g}, {symbol} / dp = {d['resolution']:.0f}, t = {d['t']:.3g} s")
    ax.set_xlabel(f"distance / {symbol}")
    ax.set_ylabel(f"surface / {symbol}")
    ax.set_aspect("equal")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", help="lube_collapse_2d and lube_collapse_3d run directories")
    ap.add_argument("--at", type=float, nargs="+", metavar="T", help="measure at the frames nearest these times")
    ap.add_argument("--ensemble", action="store_true", help="print the mean over the runs of each spacing")
    ap.add_argument("--profile", type=float, metavar="STEP",
                    help="print the surfaces side by side every STEP (in L_0 or r_0) out to the farthest grain")
    ap.add_argument("--plot", metavar="PNG", help="draw the surfaces of all the runs into PNG")
    args = ap.parse_args()
    for run in args.runs:
        run_params(ap, run, ("a",), "the mu(I) column collapses (lube_collapse_2d, lube_collapse_3d)")
        start = frame_time(list_frames(run)[0])
        if start > 0:  # a run restarted into a directory of its own: the column is not here
            ap.error(f"{run}'s first frame is at t = {start:g} s, not 0: the column before its collapse is not in "
                     "this directory (a restart written elsewhere); give the directory of the run from t = 0")
    deposits = []
    for run, at in ((run, at) for run in args.runs for at in (args.at or [None])):
        d = deposit(run, at)
        deposits.append(d)
        symbol = "r_0" if d["radial"] else "L_0"
        shape = "axisymmetric" if d["radial"] else "planar"
        print(f"{run}: {shape} a = {d['a']:g}, {symbol} / dp = {d['resolution']:.1f} "
              f"({d['layers']} layers), t = {d['t']:.3g} s: runout ratio {d['ratio']:.3f} against Lube's "
              f"{d['law']:.3f} ({100 * (d['ratio'] / d['law'] - 1):+.1f} %); centre height / H_0 "
              f"{d['centre']:.3f}; surface / {symbol} at " + ", ".join(f"{s:g}" for s in STATIONS) + f" {symbol}: "
              + " ".join(f"{s:.3f}" for s in d["surface"]) + f"; edge speed / peak front speed {d['rest']:.1e}; "
              f"onset at {d['onset']:.3g} s; {d['beyond']} grains beyond the edge, the farthest grain's edge at "
              f"{d['farthest']:.3f}; "
              + ", ".join(f"{100 * q:g}" for q in FRACTIONS) + " % of the mass within "
              + " ".join(f"{e:.3f}" for e in d["extents"]))
    if args.ensemble:
        print("\n".join(ensemble_table(deposits)))
    if args.profile:
        print("\n".join(profile_table(deposits, args.profile)))
    if args.plot:
        plot_surfaces(deposits, args.plot)

if __name__ == "__main__":
    main()
