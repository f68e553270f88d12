"""Resident bytes per particle of a 2D fluid run (dam break), on one rank.

    .venv/bin/python benchmarks/memory.py

Runs the case at two resolutions in-process and reports the growth of the
peak resident set size divided by the growth of the particle count, which
removes the fixed cost of Python, numba and MPI.
"""

import subprocess
import sys
import tempfile

import numpy as np

from mpisph.launch import ROOT

PROBE = """
import resource, sys
from mpisph.__main__ import main
code = main(["dam_break_2d", "--set", "dp=" + sys.argv[1], "--t-end", "0.004",
             "--output-interval", "0.004", "--out", sys.argv[2], "--quiet"])
print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024)
sys.exit(code)
"""


def peak_rss(dp, out):
    r = subprocess.run([sys.executable, "-c", PROBE, str(dp), out], capture_output=True, text=True,
                       cwd=ROOT, check=True)
    return int(r.stdout.strip().splitlines()[-1])


def particles(dp):
    """Water particles of the L x 2L column (L = 1 m), as geometry.box fills it."""
    return int(np.floor(1.0 / dp + 1e-9)) * int(np.floor(2.0 / dp + 1e-9))


def main():
    with tempfile.TemporaryDirectory() as out:
        small, large = 0.01, 0.0035
        m_small, m_large = peak_rss(small, out), peak_rss(large, out)
    n_small, n_large = particles(small), particles(large)
    per = (m_large - m_small) / (n_large - n_small)
    print(f"dam_break_2d: {per:.0f} resident bytes per particle "
          f"(peak RSS {m_small / 2**20:.0f} MiB at {n_small} particles, {m_large / 2**20:.0f} MiB at {n_large})")


if __name__ == "__main__":
    main()
