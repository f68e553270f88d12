"""Factor of safety of a Drucker-Prager case by strength reduction: stages dividing c and tan phi by F.

    .venv/bin/python scripts/strength_reduction.py CASE [--set NAME=VALUE ...] --factors 0.8 0.9 1.0 \
        [--bisect 2] [--settle 2] [--stage 1] [--hold 1] [--height H] [-n 2] --out DIR
    .venv/bin/python scripts/strength_reduction.py CASE [--set NAME=VALUE ...] --out DIR --hold 1
    .venv/bin/python scripts/strength_reduction.py CASE [--set NAME=VALUE ...] --out DIR --report

The release runs the case (its parameters with ``--set``) for ``--settle`` seconds with c and tan
phi (and tan psi) divided by the first factor; each further factor restarts the last stage that
stood for ``--stage`` seconds, up to the first that slides; ``--bisect K`` then halves the bracket K
times (mpisph/strength_reduction.py says how a stage is judged: by displacements over the height H,
which is the body's top above the floor y = 0 unless ``--height`` gives it, as a slope on a
foundation needs: the slope's own height). Each stage runs in a directory of its own under DIR
(``stage03_F0.725``, say). Then a row per stage and the bracket; the first line also gives the
factors at which limit analysis puts a vertical cut of height H critical
(references.vertical_cut_safety_factor), a reference for a vertical cut only. ``--hold S`` runs the
last factor that stood on for S seconds more, after the search or, without ``--factors``, on the
search recorded in DIR: a factor whose stage gives way there counts as slid. ``--report`` prints the
stages already recorded in DIR. Both read the record with the case and --set items of its search,
which they check against its release. A warning follows the table when the release still crept at
its end as fast as the slide's share per second (strength_reduction.release_creep): a longer
--settle is then needed.
"""

import argparse
import os
from pathlib import Path

from mpisph import strength_reduction
from mpisph.arguments import parse_sets
from mpisph.case import case_key, load_case_module, resolve_params
from mpisph.launch import mpirun_mpisph
from mpisph.measure import cut_height


def launcher(out, ranks):
    """A ``launch`` for strength_reduction.search: each stage by mpirun into OUT/NAME."""
    def launch(name, case, arguments):
        directory = os.path.join(out, name)
        mpirun_mpisph([case, *arguments, "--out", directory, "--quiet"], ranks=ranks, accept=(0,))
        return directory
    return launch


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                 formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    ap.add_argument("case")
    ap.add_argument("--set", dest="sets", nargs="+", action="extend", default=[], metavar="NAME=VALUE")
    ap.add_argument("--factors", type=float, nargs="+", default=[], help="F of each stage, rising (not with --report)")
    ap.add_argument("--bisect", type=int, default=0, help="stages halving the bracket once a factor slid")
    ap.add_argument("--settle", type=float, default=2.0, help="simulated time of the release [s]")
    ap.add_argument("--stage", type=float, default=1.0, help="simulated time of each further stage [s]")
    ap.add_argument("--height", type=float, default=None, metavar="H",
                    help="the height [m] the displacements are judged over (default: the body's top above y = 0; "
                         "a slope on a foundation: the slope's own)")
    ap.add_argument("-n", "--ranks", type=int, default=1)
    ap.add_argument("--out", required=True, help="directory of the stages")
    ap.add_argument("--report", action="store_true", help="print the stages recorded in --out, run none")
    ap.add_argument("--hold", type=float, default=0.0, metavar="SECONDS",
                    help="run the last factor that stood on for SECONDS more: after the search, or without "
                         "--factors on the search recorded in --out")
    a = ap.parse_args()
    if a.hold < 0:
        ap.error(f"--hold takes seconds, not {a.hold:g}")
    if a.height is not None and not a.height > 0:
        ap.error(f"--height takes metres, more than 0, not {a.height:g}")
    if a.report and (a.factors or a.hold):
        ap.error("--report runs no stage: leave out --factors and --hold")
    if not (a.report or a.hold or a.factors) or sorted(a.factors) != a.factors:
        ap.error("--factors must be given, rising")
    out = os.path.abspath(a.out)  # the runs start in the repository's root (launch.mpirun_mpisph)
    case = str(Path(a.case).resolve()) if a.case.endswith(".py") else a.case
    soil = resolve_params(load_case_module(case), parse_sets(a.sets))
    if not {"cohesion", "phi", "psi"} <= soil.keys():
        ap.error(f"{a.case} has no Drucker-Prager strength (cohesion, phi, psi) to reduce: choose a soil case")
    if a.factors:
        os.makedirs(out, exist_ok=True)
        stages = strength_reduction.search(launcher(out, a.ranks), case, a.sets, soil, a.factors, a.settle,
                                              a.stage, a.bisect, a.height)
    elif not os.path.exists(os.path.join(out, strength_reduction.RECORD)):
        ap.error(f"{out} holds no {strength_reduction.RECORD}: no search ran there")
    else:
        stages = strength_reduction.read_record(out)
        try:
            strength_reduction.check_record(stages, case_key(case), soil)
        except ValueError as e:
            ap.error(f"{out}: {e}")
        if a.height is not None and abs(a.height - stages[0].height) > 1e-9 * a.height:
            ap.error(f"{out}: its search judged the stages over H = {stages[0].height:g} m, not --height "
                     f"{a.height:g}: leave --height out, or search again")
    if a.hold:
        try:
            strength_reduction.hold(launcher(out, a.ranks), case, stages, soil, a.hold)
        except ValueError as e:
            ap.error(str(e))
    if not a.report:
        strength_reduction.write_record(out, stages)
    height = stages[0].height
    associated, dilatant = strength_reduction.limit_factors(height, soil)
    top = cut_height(strength_reduction.release_frame(stages))
    which = ("--height" if abs(height - top) > 1e-9 * top else
             "the body's top above y = 0; a slope's own height: --height")
    print(f"{a.case}: H = {height:.3f} m ({which}), c = {soil['cohesion'] / 1e3:g} kPa, phi = {soil['phi']:g} deg; "
          f"limit analysis puts a vertical cut of this height critical at F = {associated:.3f} (associated) and "
          f"{dilatant:.3f} (psi = {soil['psi']:g}, Drescher & Detournay); a slope of another angle has its own")
    print("\n".join(strength_reduction.table(stages, soil)))
    creep = strength_reduction.release_creep(stages)
    if creep >= strength_reduction.SLIDE:
        print(f"warning: the release still moved {creep:.3g} H/s at its end, past the slide's "
              f"{strength_reduction.SLIDE:g} H per second: it had not settled, so the stages after it "
              "may read its own motion as a slide; give a longer --settle")
    stood, slid = strength_reduction.bracket(stages)
    print(f"factor of safety: {stood:g} to {slid:g}" if stood is not None and slid is not None else
          f"no stage slid: the factor of safety is above {stood:g}" if slid is None else
          f"the first factor slid: the factor of safety is below {slid:g}")


if __name__ == "__main__":
    main()
