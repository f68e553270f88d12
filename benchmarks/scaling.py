"""Throughput against particle count, 10k to 1M particles in 2D, on 1 and 2 ranks, with a plot.

    .venv/bin/python benchmarks/scaling.py [--png docs/img/throughput.png] [--ranks 1 2]

The 2D dam break (fluid) and the 2D column collapse (Drucker-Prager with
UTVF) at five resolutions each; every run covers about 30 steps (the
simulated time scales with dp, like the time step) and is timed by the
solver, numba compilation excluded by a warm-up run.
"""

import argparse
import math

from _run import run_case

COUNTS = (10_000, 30_000, 100_000, 300_000, 1_000_000)

# case: (dp for N moving particles, simulated time per unit dp for ~30 steps, warm-up arguments)
CASES = {
    "dam_break_2d": (lambda n: math.sqrt(2.0 / n), 0.4, ["--set", "dp=0.05", "--t-end", "0.01"]),
    "column_collapse_2d": (lambda n: math.sqrt(0.02 / n), 0.32, ["--set", "dp=0.01", "--t-end", "0.005"]),
}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--png", default="docs/img/throughput.png")
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    a = ap.parse_args()
    results = {}
    for case, (spacing, time_per_dp, warm_up) in CASES.items():
        run_case(case, 1, warm_up)
        for ranks in a.ranks:
            for n in COUNTS:
                dp = spacing(n)
                t_end = time_per_dp * dp
                r = run_case(case, ranks, ["--set", f"dp={dp:.6g}", "--t-end", f"{t_end:.6g}",
                                           "--output-interval", f"{t_end:.6g}"])
                results[case, ranks, r.particles] = r.rate
                print(f"{case} {r.particles} particles ranks={ranks}: {r.rate:.4g} particle-steps/s/core "
                      f"({r.steps} steps)  [{r.command}]", flush=True)
    plot(results, a.png)
    print(f"plot: {a.png}")


def plot(results, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for (case, ranks) in sorted({(c, r) for c, r, _ in results}):
        pts = sorted((n, rate) for (c, r, n), rate in results.items() if (c, r) == (case, ranks))
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-" if ranks == 1 else "s--",
                label=f"{case}, {ranks} rank{'s' if ranks > 1 else ''}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("moving particles")
    ax.set_ylabel("particle-steps per second per core")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=120)


if __name__ == "__main__":
    main()
