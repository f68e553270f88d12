"""Particle-steps per second per core of the 2D dam break at >= 100k particles, 1 and 2 ranks.

    .venv/bin/python benchmarks/throughput.py [--dp 0.0044] [--t-end 0.02]

Each run is timed by the solver itself (wall time of the step loop, numba
compilation excluded by a warm-up run); the 2-rank parallel efficiency is the
2-rank rate per core over the 1-rank rate.
"""

import argparse

from _run import run_case


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dp", type=float, default=0.0044, help="dam break spacing (0.0044 m: 103k particles)")
    ap.add_argument("--t-end", type=float, default=0.02, help="simulated time per run [s]")
    a = ap.parse_args()
    args = ["--set", f"dp={a.dp}", "--t-end", a.t_end, "--output-interval", a.t_end]
    run_case("dam_break_2d", 1, ["--set", "dp=0.05", "--t-end", "0.01"])  # compile numba kernels once
    rates = {}
    for ranks in (1, 2):
        rate, shares, cmd = run_case("dam_break_2d", ranks, args)
        rates[ranks] = rate
        phases = ", ".join(f"{k} {v:.0f}%" for k, v in shares.items())
        print(f"dam_break_2d dp={a.dp} ranks={ranks}: {rate:.4g} particle-steps/s/core  ({phases})  [{cmd}]")
    print(f"dam_break_2d 2-rank parallel efficiency: {100 * rates[2] / rates[1]:.1f}%")


if __name__ == "__main__":
    main()
