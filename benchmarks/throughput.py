"""Particle-steps per second per core at >= 100k particles, 1 and 2 ranks, and the 2-rank efficiency.

    .venv/bin/python benchmarks/throughput.py [--cases dam_break_2d column_collapse_2d]

Cases: the 2D dam break (fluid, dual time stepping) and the 2D column
collapse (Drucker-Prager with UTVF, single time stepping as in 000_ Sec. 3.4).
Each run is timed by the solver itself (wall time of the step loop, numba
compilation excluded by a warm-up run); the 2-rank parallel efficiency is the
2-rank rate per core over the 1-rank rate.
"""

import argparse

from _run import run_case

# case: (spacing giving >= 100k moving particles, simulated time per run, a small warm-up run)
BENCHMARKS = {
    "dam_break_2d": ("dp=0.0044", 0.02, ["--set", "dp=0.05", "--t-end", "0.01"]),  # 103k particles
    "column_collapse_2d": ("dp=0.00044", 0.0005, ["--set", "dp=0.01", "--t-end", "0.005"]),  # 103k particles
}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", nargs="*", choices=list(BENCHMARKS), default=list(BENCHMARKS))
    a = ap.parse_args()
    for case in a.cases:
        spacing, t_end, warm_up = BENCHMARKS[case]
        run_case(case, 1, warm_up)  # compile the numba kernels once
        args = ["--set", spacing, "--t-end", t_end, "--output-interval", t_end]
        rates = {}
        for ranks in (1, 2):
            rate, shares, cmd = run_case(case, ranks, args)
            rates[ranks] = rate
            phases = ", ".join(f"{k} {v:.0f}%" for k, v in shares.items())
            print(f"{case} {spacing} ranks={ranks}: {rate:.4g} particle-steps/s/core  ({phases})  [{cmd}]",
                  flush=True)
        print(f"{case} 2-rank parallel efficiency: {100 * rates[2] / rates[1]:.1f}%", flush=True)


if __name__ == "__main__":
    main()
