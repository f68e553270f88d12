"""Factor of safety of a Drucker-Prager case by strength reduction: stages that divide c and tan phi by F.

    .venv/bin/python scripts/strength_reduction.py CASE [--set NAME=VALUE ...] --factors 0.8 0.9 1.0 \
        [--settle 2] [--stage 1] [-n 2] --out DIR [--report]

The first stage runs the case (its parameters with ``--set``) from the start for ``--settle`` seconds
with its cohesion and friction reduced by the first factor F, c / F and atan(tan phi / F) (the
dilatancy angle likewise); each further stage restarts from the last frame with the next factor, for
``--stage`` seconds, into DIR. Then a row per stage: F, the reduced c and phi, the kinetic-energy
peak and when in the stage it came, the kinetic energy at the stage's end, and the 99th percentile of
the particles' displacements over the stage and since the start over the body's height
(measure.cut_height). The first stage, the case's release, settles; a later stage whose displacement
passes SLIDE H slid (a cut at rest creeps by a few thousandths of H a second, docs/CUTS.md), and the
first F that slid brackets the factor of safety with the one before (a slide changes the body's shape,
so the stages after it no longer test the same body). For a vertical cut the first line also gives
the factors at which limit analysis puts the cut's height critical
(references.vertical_cut_safety_factor). ``--report`` reads the stages already in DIR.
"""

import argparse
import math
import os
from pathlib import Path

import numpy as np

from mpisph.arguments import parse_sets
from mpisph.case import load_case_module, resolve_params
from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import list_frames, read_frame
from mpisph.launch import mpirun_mpisph
from mpisph.measure import cut_height, displacement_percentile
from mpisph.references import vertical_cut_safety_factor

SLIDE = 0.015  # share of the height a stage's 99 % displacement passes when the body slid


def reduced(params, factor):
    """(c, phi, psi) of ``params`` with c and the tangents of the angles divided by ``factor``."""
    def angle(name):
        return math.degrees(math.atan(math.tan(math.radians(float(params[name]))) / factor))
    return float(params["cohesion"]) / factor, angle("phi"), angle("psi")


def stage_times(factors, settle, stage):
    """(factor, start, end) of each stage: the first ``settle`` long, the others ``stage``."""
    ends = np.cumsum([settle] + [stage] * (len(factors) - 1))
    return [(f, float(t0), float(t1)) for f, t0, t1 in zip(factors, np.concatenate([[0.0], ends[:-1]]), ends)]


def run_stages(case, sets, soil, stages, stage, ranks, out):
    """Run ``stages`` (``stage_times``; see the module's docstring) into ``out``: ``sets`` are the
    --set items, ``soil`` the case's parameters and ``stage`` the frames' spacing in time, a quarter
    of it."""
    case = str(Path(case).resolve()) if case.endswith(".py") else case  # the runs start in the repository's root
    for k, (factor, t0, t1) in enumerate(stages):
        c, phi, psi = reduced(soil, factor)
        strength = [f"cohesion={c!r}", f"phi={phi!r}", f"psi={psi!r}"]
        start = ["--set", *sets, *strength] if k == 0 else ["--restart", list_frames(out)[-1], "--set", *strength]
        mpirun_mpisph([case, *start, "--t-end", repr(t1), "--output-interval", repr(stage / 4), "--out", out,
                       "--quiet"], ranks=ranks, accept=(0,))


def stage_rows(out, params, stages):
    """The table's rows (see the module's docstring) from the frames and diagnostics in ``out``."""
    frames = {round(f["t"], 9): f for f in map(read_frame, list_frames(out))}
    diag = read_diagnostics(os.path.join(out, "diagnostics.csv"))
    first = frames[round(stages[0][1], 9)]
    height = cut_height(first)
    rows = []
    for index, (factor, t0, t1) in enumerate(stages):
        a, b = frames[round(t0, 9)], frames[round(t1, 9)]
        inside = (diag["t"] > t0 + 1e-9) & (diag["t"] <= t1 + 1e-9)
        energy, times = diag["kinetic_energy"][inside], diag["t"][inside]
        k = int(np.argmax(energy))
        moved = displacement_percentile(a, b) / height
        c, phi, _ = reduced(params, factor)
        rows.append(f"| {factor:g} | {c / 1e3:.3f} | {phi:.2f} | {energy[k]:.3g} at +{times[k] - t0:.2f} | "
                    f"{energy[-1]:.3g} | {moved:.4f} | {displacement_percentile(first, b) / height:.3f} | "
                    f"{'settling' if index == 0 else 'slid' if moved > SLIDE else 'stood'} |")
    return height, rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case")
    ap.add_argument("--set", dest="sets", nargs="+", action="extend", default=[], metavar="NAME=VALUE")
    ap.add_argument("--factors", type=float, nargs="+", required=True, help="F of each stage, in order")
    ap.add_argument("--settle", type=float, default=2.0, help="simulated time of the first stage [s]")
    ap.add_argument("--stage", type=float, default=1.0, help="simulated time of each further stage [s]")
    ap.add_argument("-n", "--ranks", type=int, default=1)
    ap.add_argument("--out", required=True, help="directory of the stages' frames")
    ap.add_argument("--report", action="store_true", help="read the stages already in --out, run none")
    a = ap.parse_args()
    a.out = os.path.abspath(a.out)  # the runs start in the repository's root (launch.mpirun_mpisph)
    soil = resolve_params(load_case_module(a.case), parse_sets(a.sets))
    stages = stage_times(a.factors, a.settle, a.stage)
    if not a.report:
        run_stages(a.case, a.sets, soil, stages, a.stage, a.ranks, a.out)
    height, rows = stage_rows(a.out, soil, stages)
    gamma = soil["rho0"] * soil["g"]
    limit = vertical_cut_safety_factor(soil["cohesion"], soil["phi"], gamma, height, soil["psi"])
    print(f"{a.case}: H = {height:.3f} m, c = {soil['cohesion'] / 1e3:g} kPa, phi = {soil['phi']:g} deg; limit "
          f"analysis puts it critical at F = {limit[0]:.3f} (associated) and {limit[1]:.3f} (psi = {soil['psi']:g}, "
          "Drescher & Detournay)")
    print("| F | c [kPa] | phi [deg] | peak kinetic energy [J] at [s into the stage] | kinetic energy at the end [J] "
          f"| 99 % displacement over the stage / H | since the start / H | over {SLIDE:g} H |")
    print("|---|---|---|---|---|---|---|---|")
    print("\n".join(rows))


if __name__ == "__main__":
    main()
