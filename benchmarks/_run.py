"""Run ``python -m mpisph`` under mpirun for a benchmark and parse its closing lines."""

import re
import tempfile
from dataclasses import dataclass

from mpisph.launch import ROOT, command_line, mpirun_mpisph


@dataclass
class Run:
    """What the closing lines of a run say."""

    rate: float  # particle-steps per second per core
    shares: dict  # phase -> percent of the wall time
    particles: int
    steps: int
    configurations: int  # neighbour configurations (advection steps)
    command: str


def run_case(case, ranks, args, root=ROOT):
    """Run a case on ``ranks`` ranks with extra command-line ``args`` (with the code of the tree
    ``root``, by default this one); returns a ``Run``."""
    with tempfile.TemporaryDirectory() as out:
        r = mpirun_mpisph([case, *map(str, args), "--out", out], ranks=ranks, root=root, accept=(0,))
    shown = command_line(["-m", "mpisph", case, *args], ranks)
    m = re.search(r"throughput: (\S+) particle-steps/s/core on \d+ rank\(s\), (\d+) particles, (\d+) steps, "
                  r"(\d+) neighbour configurations", r.stdout)
    shares = {k: float(v) for k, v in re.findall(r"(\w+) ([\d.]+)%", r.stdout.split("timing:")[1])}
    return Run(float(m.group(1)), shares, int(m.group(2)), int(m.group(3)), int(m.group(4)), shown)
