"""Run the cases of RUNS (every case but lube_collapse_3d, sliding_sheet and
soil_cylinder_impact) with the code of a base commit and with the current code, and compare
the final frames field by field: a refactoring that claims to leave the physics alone must end
with the same bits. With ``--throughput``, compare their speed instead.

    .venv/bin/python scripts/compare_commits.py [--base REF] [--ranks N] [--only RUN ...] [--current-set K=V ...]
    .venv/bin/python scripts/compare_commits.py --throughput [--base REF] [--repeat 3] [--cases CASE ...]

The base commit's tree is exported with ``git archive`` into ``runs/compare/<sha>/`` (kept,
so numba's cache is reused next time) and run with that tree first on ``PYTHONPATH``; the
current code is the working tree. Each row is one run (a case, sometimes a variant that
reaches another code path) at a small size; the table gives, per field of the final frame
(walls included, sorted by global id), ``same`` for equal bits or the largest absolute
difference, and the step count of both runs. Exits 1 if any field differs or is missing.
``--current-set K=V`` runs the current code with ``--set K=V`` on every case that has the
parameter K: a deliberate change of a default since the base (the Riemann limiter's, issue 13)
is set back so that the rest of the code is compared bit for bit.

``--throughput`` runs the cases of benchmarks/throughput.py (same sizes, same warm-up) on 1
and 2 ranks with both trees, alternating base and current run by run, so that a drift in the
speed of a shared machine hits both alike; it prints the best of ``--repeat`` runs of each and
their ratio.
"""

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

sys.path.insert(0, str(ROOT / "benchmarks"))

from _run import run_case  # noqa: E402
from mpisph.case import load_case_module  # noqa: E402
from mpisph.io.frames import list_frames, read_frame  # noqa: E402
from mpisph.launch import mpirun_mpisph  # noqa: E402
from throughput import BENCHMARKS  # noqa: E402

BASE = "2d40723"  # the last commit before issue 12 (the composable step)

# name: (case, arguments); the cases at least once but the three above, variants for the remaining code paths
RUNS = {
    "elliptical_drop": ("elliptical_drop", ["--set", "dp=0.05", "--t-end", "0.004"]),
    "rotating_square_patch": ("rotating_square_patch", ["--set", "dp=0.05", "--t-end", "0.1"]),
    "taylor_green": ("taylor_green", ["--set", "nx=30", "--t-end", "0.3"]),
    "lid_driven_cavity": ("lid_driven_cavity", ["--set", "nx=20", "--t-end", "0.5"]),
    "dam_break_2d": ("dam_break_2d", ["--set", "dp=0.05", "--t-end", "0.1"]),
    "dam_break_2d free_slip": ("dam_break_2d", ["--set", "dp=0.05", "wall=free_slip", "--t-end", "0.1"]),
    "hydrostatic_tank": ("hydrostatic_tank", ["--set", "dp=0.05", "--t-end", "0.1"]),
    "oscillating_beam": ("oscillating_beam", ["--set", "H_over_dp=5", "--t-end", "0.01"]),
    "oscillating_beam none": ("oscillating_beam", ["--set", "H_over_dp=5", "stabiliser=none", "--t-end", "0.01"]),
    "oscillating_beam classic": ("oscillating_beam", ["--set", "H_over_dp=5", "scheme=classic_elastic",
                                                      "stabiliser=artificial_stress", "--t-end", "0.01"]),
    "column_collapse_2d": ("column_collapse_2d", ["--set", "dp=0.01", "--t-end", "0.03"]),
    "column_collapse_2d tvf dual": ("column_collapse_2d", ["--set", "dp=0.01", "stabiliser=tvf",
                                                           "time_stepping=dual", "--t-end", "0.03"]),
    "cohesive_failure_2d": ("cohesive_failure_2d", ["--set", "dp=0.2", "--t-end", "0.2"]),
    "cube_failure_3d": ("cube_failure_3d", ["--set", "dp=0.25", "--t-end", "0.2"]),
    "dam_break_3d": ("dam_break_3d", ["--set", "dp=0.15", "--t-end", "0.1"]),
    "flume_3d": ("flume_3d", ["--set", "dp=0.1", "--t-end", "0.2"]),  # free-slip side walls
    "vertical_cut classic": ("vertical_cut", ["--set", "dp=0.1", "scheme=classic_granular",
                                              "stabiliser=artificial_stress", "--t-end", "0.1"]),
    "inclined_plane": ("inclined_plane", ["--set", "H=0.02", "dp=0.002", "columns=16", "m_0=0.2",
                                          "--t-end", "0.01"]),
    # the law's kernel means of the deviatoric strain rate and of the carried pressure (law_viscosity);
    # against a base before e5600f5 its law_pressure differs on the walls, which held unset memory there
    "inclined_plane law_means": ("inclined_plane", ["--set", "H=0.02", "dp=0.002", "columns=16", "m_0=0.2",
                                                    "pressure_form=isotropic", "law_pressure=carried_mean",
                                                    "law_strain_rate=deviatoric_kernel_mean", "--t-end", "0.01"]),
    "lube_collapse_2d": ("lube_collapse_2d", ["--set", "dp=0.005", "--t-end", "0.06"]),  # the implicit viscous kick
    "lube_collapse_2d deviatoric": ("lube_collapse_2d", ["--set", "dp=0.005", "viscous_form=corrected_stress",
                                                         "viscous_stress=deviatoric", "m_0=40", "--t-end", "0.06"]),
}


def export(ref):
    """The tree of commit ``ref`` in runs/compare/<sha>/ (exported once)."""
    sha = subprocess.run(["git", "rev-parse", "--short", ref], cwd=ROOT, check=True,
                         capture_output=True, text=True).stdout.strip()
    tree = ROOT / "runs" / "compare" / sha
    if not (tree / "mpisph").is_dir():
        tree.mkdir(parents=True, exist_ok=True)
        archive = subprocess.run(["git", "archive", sha], cwd=ROOT, check=True, capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", str(tree)], input=archive, check=True)
    return sha, tree


def run(tree, case, args, ranks, out):
    """``mpirun -n ranks python -m mpisph`` with the code of ``tree``; the final frame."""
    mpirun_mpisph([case, *args, "--output-interval", "1e9", "--out", out, "--quiet"], ranks=ranks,
                  timeout=1800, root=tree, accept=(0,))
    return read_frame(list_frames(out)[-1], walls=True)


def current_args(case, args, sets):
    """``args`` plus ``--set K=V`` for each K=V of ``sets`` that ``case`` takes."""
    params = load_case_module(case).PARAMS
    return [*args, *(w for kv in sets if kv.split("=", 1)[0] in params for w in ("--set", kv))]


def compare(a, b):
    """{field: 'same' | largest absolute difference | 'missing in base/current'}."""
    out = {}
    for name in sorted(set(a) | set(b)):
        if name in ("params", "dim"):
            continue
        if name not in a or name not in b:
            out[name] = "missing in " + ("base" if name not in a else "current")
            continue
        x, y = np.asarray(a[name]), np.asarray(b[name])
        if x.shape != y.shape:
            out[name] = f"shape {x.shape} vs {y.shape}"
        elif np.array_equal(x, y, equal_nan=True) and np.array_equal(np.signbit(x), np.signbit(y)):
            out[name] = "same"
        else:
            out[name] = f"{np.nanmax(np.abs(x.astype(float) - y.astype(float))):.3g}"
    return out


def throughput(sha, tree, repeat, cases):
    """Best-of-``repeat`` particle-steps/s/core of both trees, runs interleaved."""
    print(f"throughput at {sha} and of the working tree, best of {repeat}, runs alternating\n")
    print("| case | ranks | before | after | after / before |")
    print("|---|---|---|---|---|")
    for case in cases:
        name = case.split()[0]  # a key such as "cube_failure_3d geostatic" is the case with other settings
        if not (tree / "cases" / f"{name}.py").exists():
            print(f"| {case} | - | not at {sha} | - | - |", flush=True)
            continue
        settings, t_end, warm_up, *_ = BENCHMARKS[case]
        for root in (tree, ROOT):
            run_case(name, 1, warm_up, root=root)  # numba compilation
        args = [*(w for s in settings for w in ("--set", s)), "--t-end", t_end, "--output-interval", t_end]
        for ranks in (1, 2):
            best = {tree: 0.0, ROOT: 0.0}
            for _ in range(repeat):
                for root in (tree, ROOT):
                    best[root] = max(best[root], run_case(name, ranks, args, root=root).rate)
            print(f"| {name} {' '.join(settings)} | {ranks} | {best[tree]:.4g} | {best[ROOT]:.4g} | "
                  f"{best[ROOT] / best[tree]:.3f} |", flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--base", default=BASE, help=f"commit to compare against (default {BASE})")
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--only", nargs="*", choices=list(RUNS), default=list(RUNS))
    ap.add_argument("--current-set", nargs="*", default=[], metavar="K=V",
                    help="parameters for the current code's runs, on the cases that take them")
    ap.add_argument("--throughput", action="store_true", help="compare speed, not bits")
    ap.add_argument("--repeat", type=int, default=3, help="with --throughput: runs per tree and rank count")
    ap.add_argument("--cases", nargs="*", choices=list(BENCHMARKS), default=list(BENCHMARKS),
                    help="with --throughput: the cases of benchmarks/throughput.py to run")
    a = ap.parse_args()
    sha, tree = export(a.base)
    if a.throughput:
        throughput(sha, tree, a.repeat, a.cases)
        return
    shown = f", the working tree with {' '.join(a.current_set)}" if a.current_set else ""
    print(f"final frames at {sha} against the working tree, {a.ranks} ranks, walls included{shown}\n")
    print("| run | steps | fields with the same bits | fields that differ |")
    print("|---|---|---|---|")
    failed = False
    for name in a.only:
        case, args = RUNS[name]
        with tempfile.TemporaryDirectory() as d:
            base = run(tree, case, args, a.ranks, Path(d) / "base")
            current = run(ROOT, case, current_args(case, args, a.current_set), a.ranks, Path(d) / "current")
        result = compare(base, current)
        same = [k for k, v in result.items() if v == "same"]
        differ = [f"{k} ({v})" for k, v in result.items() if v != "same"]
        failed |= bool(differ)
        print(f"| {name} | {base['step']} / {current['step']} | {len(same)}: {' '.join(same)} | "
              f"{', '.join(differ) or 'none'} |", flush=True)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
