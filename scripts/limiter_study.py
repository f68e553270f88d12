"""Which pairs should the Riemann dissipation limiter damp? Both choices on four cases.

    .venv/bin/python scripts/limiter_study.py [--ranks 2] [--only CASE ...]

Runs the elliptical drop, the dam break, the granular column collapse and the
cohesive cut with ``--set limiter=approaching`` and ``limiter=separating``
(the scheme option of riemann_fluid and riemann_granular, fluid.LIMITED_PAIRS)
into runs/limiter_study/, and prints a Markdown table of each case's measures
beside its reference and the change of kinetic plus gravitational energy
(docs/REMEDIES.md keeps the table and the decision).
"""

import argparse
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from mpisph import measure, references  # noqa: E402
from mpisph.instability import tensile_instability  # noqa: E402
from mpisph.io.diagnostics import read_diagnostics  # noqa: E402
from mpisph.io.frames import list_frames, read_frame  # noqa: E402
from mpisph.launch import mpirun_mpisph  # noqa: E402

RUNS = ROOT / "runs" / "limiter_study"
LIMITERS = ("approaching", "separating")


def run(case, limiter, args, ranks):
    """The frames (walls included) and diagnostics of one run."""
    out = RUNS / f"{case}_{limiter}"
    mpirun_mpisph([case, "--set", f"limiter={limiter}", *args, "--out", out, "--quiet"], ranks=ranks, accept=(0,))
    frames = [read_frame(f, walls=True) for f in list_frames(out)]
    return frames, read_diagnostics(out / "diagnostics.csv")


def energy_change(diag):
    """(E_end - E_0) / E_0 of kinetic plus gravitational energy (E_0 > 0 for the drop: no gravity),
    or over the largest kinetic energy when the start is at rest."""
    e = diag["kinetic_energy"] + diag["potential_energy"]
    scale = e[0] if diag["potential_energy"][0] == 0.0 else diag["kinetic_energy"].max()
    return (e[-1] - e[0]) / scale


def moving(frame):
    return {k: (v[frame["kind"] == 0] if isinstance(v, np.ndarray) and len(v) == len(frame["kind"]) else v)
            for k, v in frame.items()}


def drop(limiter, ranks):
    frames, diag = run("elliptical_drop", limiter, ["--t-end", "0.0076", "--output-interval", "0.0038"], ranks)
    a, b = measure.semi_axes(frames[-1], 0.02)
    ref = references.elliptical_drop_axes(frames[-1]["t"])[0]
    return [("x / y semi-axis at 0.0076 s", f"{100 * (a / ref[0] - 1):+.2f} % / {100 * (b / ref[1] - 1):+.2f} %",
             "Monaghan's ODE"), ("kinetic energy change", f"{100 * energy_change(diag):+.2f} %", "-")]


def dam_break(limiter, ranks):
    frames, diag = run("dam_break_2d", limiter, ["--t-end", "0.72", "--output-interval", "0.02"], ranks)
    T, z = measure.dam_break_fronts(frames)
    early = references.KOSHIZUKA_T[1:][references.KOSHIZUKA_T[1:] <= 1.6]
    err = max(abs(np.interp(Tk, T, z) / references.koshizuka_oka_front(Tk) - 1) for Tk in early)
    speed = measure.front_speed(T, z, *references.MARTIN_MOYCE_SPAN)
    reference = references.martin_moyce_speed()
    return [("front, largest error for T <= 1.6", f"{100 * err:.1f} %", "Koshizuka & Oka"),
            ("front speed dZ/dT, T = {:g}-{:g}".format(*references.MARTIN_MOYCE_SPAN),
             f"{speed:.3f} ({100 * (speed / reference - 1):+.1f} %)",
             f"Martin & Moyce {reference:.3f}"),
            ("energy change / max kinetic", f"{100 * energy_change(diag):+.1f} %", "-")]


def column(limiter, ranks):
    frames, diag = run("column_collapse_2d", limiter, [], ranks)
    last = moving(frames[-1])
    e = diag["kinetic_energy"] + diag["potential_energy"]
    return [("runout at 1 s [m]", f"{measure.runout(last, 0.002):.3f}", "0.32-0.38"),
            ("final / peak max speed", f"{measure.final_over_peak_speed(frames):.4f}", "0"),
            ("final / initial mechanical energy", f"{e[-1] / e[0]:.3f}", "0.69 +- 0.03")]


def cohesive(limiter, ranks):
    frames, diag = run("cohesive_failure_2d", limiter, [], ranks)
    first, last = moving(frames[0]), moving(frames[-1])
    m = tensile_instability(frames[-1])
    return [("crest crack behind the face [m]", f"{measure.crest_crack(first, last, 0.04, 4.0, 0.1):.2f}", "1.2-1.5"),
            ("clustering / inner voids at 2 s", f"{100 * m['clustering']:.2f} % / {100 * m['inner_voids']:.2f} %",
             "0 / 0"),
            ("final / peak max speed", f"{measure.final_over_peak_speed(frames):.3f}", "0"),
            ("energy change / max kinetic", f"{100 * energy_change(diag):+.1f} %", "-")]


CASES = {"elliptical_drop": drop, "dam_break_2d": dam_break, "column_collapse_2d": column,
         "cohesive_failure_2d": cohesive}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--only", nargs="*", choices=list(CASES))
    a = ap.parse_args()
    print("| case | measure | approaching | separating | reference |\n|---|---|---|---|---|")
    for name in a.only or CASES:
        rows = {limiter: CASES[name](limiter, a.ranks) for limiter in LIMITERS}
        for k, (what, value, ref) in enumerate(rows["approaching"]):
            print(f"| {name if k == 0 else ''} | {what} | {value} | {rows['separating'][k][1]} | {ref} |", flush=True)


if __name__ == "__main__":
    main()
