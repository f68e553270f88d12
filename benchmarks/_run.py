"""Run ``python -m mpisph`` under mpirun for a benchmark and parse its closing lines."""

import re
import tempfile

from mpisph.launch import mpirun_mpisph


def run_case(case, ranks, args):
    """Run a case; returns (throughput per core, phase shares {name: percent}, command line)."""
    with tempfile.TemporaryDirectory() as out:
        r = mpirun_mpisph([case, *args, "--out", out], ranks=ranks)
    shown = f"mpirun -n {ranks} python -m mpisph {case} {' '.join(map(str, args))}"
    if r.returncode != 0:
        raise SystemExit(f"benchmark run failed: {shown}\n{r.stderr}")
    rate = float(re.search(r"throughput: (\S+) particle-steps/s/core", r.stdout).group(1))
    shares = {k: float(v) for k, v in re.findall(r"(\w+) ([\d.]+)%", r.stdout.split("timing:")[1])}
    return rate, shares, shown
