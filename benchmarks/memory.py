"""Resident bytes per particle of a 2D fluid run (dam break) and a 3D granular run (cube failure), one rank.

    .venv/bin/python benchmarks/memory.py

Each case runs at two resolutions in a fresh process; the growth of the peak
resident set size divided by the growth of the particle count removes the
fixed cost of Python, numba and MPI. Particles are counted with the wall
particles (they are stored like the others) and, in brackets, per moving
particle.

The peak includes the C allocator's slack: freed blocks that glibc keeps
resident and reuses in an order that varies from run to run (about 30 B per
particle of scatter). The second figure, "live", is the same growth of the
resident set at the end of the step loop, every array still alive, after
``malloc_trim`` has returned the free heap to the system: what the arrays
themselves take.
"""

import argparse
import subprocess
import sys
import tempfile

from mpisph import case as cases
from mpisph.launch import ROOT

PROBE = """
import ctypes, resource, sys
from mpisph import solver
from mpisph.__main__ import main

def resident():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * resource.getpagesize()

step_loop = solver.Simulation.run
live = []
def measured(sim):
    out = step_loop(sim)
    ctypes.CDLL(None).malloc_trim(0)
    live.append(resident())
    return out
solver.Simulation.run = measured
code = main([sys.argv[1], "--set", "dp=" + sys.argv[2], "--t-end", sys.argv[3],
             "--output-interval", sys.argv[3], "--out", sys.argv[4], "--quiet"])
print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024, live[0])
sys.exit(code)
"""

# case: (small spacing, large spacing, simulated time)
CASES = {
    "dam_break_2d": (0.01, 0.0035, 0.004),
    "cube_failure_3d": (0.1, 0.05, 0.004),
}


def resident_set(case, dp, t_end, out):
    """(peak, live at the end of the step loop) resident bytes of a one-rank run."""
    r = subprocess.run([sys.executable, "-c", PROBE, case, str(dp), str(t_end), out], capture_output=True,
                       text=True, cwd=ROOT, check=True)
    peak, live = r.stdout.strip().splitlines()[-1].split()
    return int(peak), int(live)


def particles(case, dp):
    """(all particles, moving particles) of ``case`` at spacing ``dp``."""
    module = cases.load_case_module(case)
    c = cases.build_case(module, cases.resolve_params(module, {"dp": str(dp)}))
    counts = [len(source.everything()[0]) for source in c.sources]
    return sum(counts), sum(counts[:len(c.bodies)])


def main():
    for case, (small, large, t_end) in CASES.items():
        with tempfile.TemporaryDirectory() as out:
            (m_small, l_small), (m_large, l_large) = (resident_set(case, small, t_end, out),
                                                      resident_set(case, large, t_end, out))
        (n_small, mv_small), (n_large, mv_large) = particles(case, small), particles(case, large)
        growth = m_large - m_small
        print(f"{case}: {growth / (n_large - n_small):.0f} resident bytes per particle at the peak "
              f"({growth / (mv_large - mv_small):.0f} per moving particle; peak RSS "
              f"{m_small / 2**20:.0f} MiB at {n_small} particles, {m_large / 2**20:.0f} MiB at {n_large}); "
              f"{(l_large - l_small) / (n_large - n_small):.0f} live  [.venv/bin/python benchmarks/memory.py]",
              flush=True)


if __name__ == "__main__":
    argparse.ArgumentParser(description=__doc__.splitlines()[0]).parse_args()  # --help, and no other argument
    main()
