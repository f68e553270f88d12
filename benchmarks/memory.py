"""Resident bytes per particle of a 2D fluid run (dam break) and a 3D granular run (cube failure), one rank.

    .venv/bin/python benchmarks/memory.py

Each case runs at two resolutions in a fresh process; the growth of the peak
resident set size divided by the growth of the particle count removes the
fixed cost of Python, numba and MPI. Particles are counted with the wall
particles (they are stored like the others) and, in brackets, per moving
particle.
"""

import subprocess
import sys
import tempfile

from mpisph import case as cases
from mpisph.launch import ROOT

PROBE = """
import resource, sys
from mpisph.__main__ import main
code = main([sys.argv[1], "--set", "dp=" + sys.argv[2], "--t-end", sys.argv[3],
             "--output-interval", sys.argv[3], "--out", sys.argv[4], "--quiet"])
print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024)
sys.exit(code)
"""

# case: (small spacing, large spacing, simulated time)
CASES = {
    "dam_break_2d": (0.01, 0.0035, 0.004),
    "cube_failure_3d": (0.1, 0.05, 0.004),
}


def peak_rss(case, dp, t_end, out):
    r = subprocess.run([sys.executable, "-c", PROBE, case, str(dp), str(t_end), out], capture_output=True,
                       text=True, cwd=ROOT, check=True)
    return int(r.stdout.strip().splitlines()[-1])


def particles(case, dp):
    """(all particles, moving particles) of ``case`` at spacing ``dp``."""
    module = cases.load_case_module(case)
    c = cases.build_case(module, cases.resolve_params(module, {"dp": str(dp)}))
    moving = sum(len(b.x) for b in c.bodies)
    return moving + sum(len(w.x) for w in c.walls), moving


def main():
    for case, (small, large, t_end) in CASES.items():
        with tempfile.TemporaryDirectory() as out:
            m_small, m_large = peak_rss(case, small, t_end, out), peak_rss(case, large, t_end, out)
        (n_small, mv_small), (n_large, mv_large) = particles(case, small), particles(case, large)
        growth = m_large - m_small
        print(f"{case}: {growth / (n_large - n_small):.0f} resident bytes per particle "
              f"({growth / (mv_large - mv_small):.0f} per moving particle; peak RSS "
              f"{m_small / 2**20:.0f} MiB at {n_small} particles, {m_large / 2**20:.0f} MiB at {n_large})  "
              f"[.venv/bin/python benchmarks/memory.py]", flush=True)


if __name__ == "__main__":
    main()
