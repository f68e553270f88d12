"""Read the logs of the runs made by benchmarks/peers/pysph.sh and print the figures.

    python benchmarks/peers/compare.py RUNS.tsv [--mpi-missing REASON] [--busy-check]

RUNS.tsv has one row per run, tab-separated:
    case  code(pysph|mpisph)  ranks  stdout-file  output-dir  process-seconds  cpu-seconds  command
Prints one figure per line, each with the command that produced it. Exits
non-zero if a log lacks the lines it needs.
"""

import argparse
import glob
import os
import re
import sys


BUSY_SHARE = 0.9  # below this CPU time / (wall x ranks) a run was sharing its cores


class Missing(Exception):
    pass


def grab(pattern, text, what, last=False):
    found = re.findall(pattern, text, flags=re.M)
    if not found:
        raise Missing(what)
    return found[-1] if last else found[0]


def is_busy(r):
    """During the solver loop every rank computes or spins in MPI (Open MPI polls, also with
    yield_when_idle), so a run alone on its cores spends at least loop x ranks of CPU time
    (start-up adds more). Less means it shared its cores with other work."""
    return r["cpu"] < BUSY_SHARE * r["loop"] * r["ranks"]


def parse_mpisph(stdout):
    """Solver-loop wall time, steps, particles and rate from mpisph's closing lines."""
    wall = float(grab(r"^timing: wall ([\d.eE+-]+) s", stdout, "mpisph 'timing: wall' line"))
    rate, particles, steps = grab(  # the rank count comes from the runs' table
        r"^throughput: ([\d.eE+-]+) particle-steps/s/core on \d+ rank\(s\), (\d+) particles, (\d+) steps",
        stdout, "mpisph 'throughput:' line")
    t_end = float(grab(r"^mpisph: done at t = ([\d.eE+-]+) s", stdout, "mpisph 'done at t' line"))
    return dict(loop=wall, steps=int(steps), fluid=int(particles), total=None,
                rate=float(rate), t_end=t_end)


def parse_pysph(stdout, out_dir):
    """Solver-loop wall time ("Run took", slowest rank), steps and end time from PySPH's log."""
    loops = [float(x) for x in re.findall(r"Run took: ([\d.eE+-]+) secs", stdout)]
    if not loops:
        raise Missing("PySPH 'Run took:' line")
    logs = glob.glob(os.path.join(out_dir, "*.log"))
    if not logs:
        raise Missing(f"PySPH log file in {out_dir}")
    with open(logs[0]) as f:
        log = f.read()
    t_end, steps = grab(r"Writing output at time ([\d.eE+-]+), iteration (\d+)", log,
                        "PySPH 'Writing output ... iteration' log line", last=True)
    counts = dict(re.findall(r"^\s+(\w+): (\d+)$", stdout.split("No of particles:", 1)[-1], flags=re.M))
    return dict(loop=max(loops), steps=int(steps), counts=counts, t_end=float(t_end))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("runs")
    ap.add_argument("--mpi-missing", default="")
    ap.add_argument("--busy-check", action="store_true",
                    help="only check the runs' CPU time: exit 3 if one shared its cores")
    a = ap.parse_args()

    runs = []
    with open(a.runs) as f:
        for line in f:
            if not line.strip():
                continue
            case, code, ranks, stdout_file, out_dir, proc, cpu, cmd = line.rstrip("\n").split("\t")
            with open(stdout_file, errors="replace") as g:
                stdout = g.read()
            try:
                r = parse_mpisph(stdout) if code == "mpisph" else parse_pysph(stdout, out_dir)
            except Missing as e:
                sys.exit(f"compare.py: no {e} in {stdout_file} (run: {cmd})")
            r.update(case=case, code=code, ranks=int(ranks), proc=float(proc), cpu=float(cpu), cmd=cmd)
            runs.append(r)

    if a.busy_check:
        busy = [r for r in runs if is_busy(r)]
        for r in busy:
            print(f"CPU time {r['cpu']:.1f} s < {100 * BUSY_SHARE:.0f}% of solver loop x ranks "
                  f"({r['loop'] * r['ranks']:.1f} s)")
        sys.exit(3 if busy else 0)

    # PySPH's per-rank counts in a 2-rank run include ghosts: take the counts of its 1-core run.
    for r in runs:
        if r["code"] == "pysph":
            serial = next(s for s in runs if s["code"] == "pysph" and s["case"] == r["case"] and s["ranks"] == 1)
            c = serial["counts"]
            r["fluid"] = int(c["fluid"])
            r["total"] = int(c.get("Total", c["fluid"]))
            r["rate"] = r["fluid"] * r["steps"] / r["loop"] / r["ranks"]
            r["rate_all"] = r["total"] * r["steps"] / r["loop"] / r["ranks"]

    def out(case, label, value, cmd):
        print(f"{case:16s} {label:62s} {value:>14s}   <- {cmd}")

    def name(r):
        return f"{r['code']} {r['ranks']} {'core' if r['ranks'] == 1 else 'ranks'}"

    print("=== summary: one figure per line, then the command that produced it ===")
    print("(solver loop = PySPH's 'Run took' (slowest rank) / mpisph's 'timing: wall', both without "
          "start-up and code generation; process = whole command, start-up included)")
    for case in dict.fromkeys(r["case"] for r in runs):
        mine = [r for r in runs if r["case"] == case]
        for r in mine:
            n = name(r)
            walls = f" (+{r['total'] - r['fluid']} wall particles)" if r["total"] and r["total"] > r["fluid"] else ""
            out(case, f"{n}: fluid particles{walls}", f"{r['fluid']}", r["cmd"])
            out(case, f"{n}: time steps to t = {r['t_end']:g} s", f"{r['steps']}", r["cmd"])
            out(case, f"{n}: solver-loop wall time [s]", f"{r['loop']:.2f}", r["cmd"])
            out(case, f"{n}: whole-process wall time [s]", f"{r['proc']:.2f}", r["cmd"])
            out(case, f"{n}: fluid particle-steps/s/core (solver loop)", f"{r['rate']:.4g}", r["cmd"])
            if r.get("rate_all") and r["total"] > r["fluid"]:
                out(case, f"{n}: all particle-steps/s/core incl. walls (solver loop)",
                    f"{r['rate_all']:.4g}", r["cmd"])
        by = {(r["code"], r["ranks"]): r for r in mine}
        for ranks in (1, 2):
            p, m = by.get(("pysph", ranks)), by.get(("mpisph", ranks))
            what = "1 core" if ranks == 1 else "2 ranks"
            if p is None or m is None:
                print(f"{case:16s} ratio PySPH/mpisph time to solution, {what}: MISSING"
                      f" ({a.mpi_missing or 'run not made'})")
                continue
            both = f"{p['cmd']}  VS  {m['cmd']}"
            out(case, f"ratio PySPH/mpisph solver-loop time, {what}", f"{p['loop'] / m['loop']:.2f}", both)
            out(case, f"ratio PySPH/mpisph whole-process time, {what}", f"{p['proc'] / m['proc']:.2f}", both)
        for code in ("pysph", "mpisph"):
            one, two = by.get((code, 1)), by.get((code, 2))
            if one and two:
                out(case, f"{code} 2-rank speed-up of the solver loop (x of 1 core)",
                    f"{one['loop'] / two['loop']:.2f}", f"{one['cmd']}  VS  {two['cmd']}")
    busy = [r for r in runs if is_busy(r)]
    for r in busy:
        print(f"WARNING: {r['case']} {name(r)}: CPU time {r['cpu']:.1f} s < {100 * BUSY_SHARE:.0f}% of "
              f"solver loop x ranks ({r['loop'] * r['ranks']:.1f} s): the machine was busy with something "
              f"else, its figures are not reliable  <- {r['cmd']}")
    if not busy:
        print(f"every run's CPU time >= {100 * BUSY_SHARE:.0f}% of its solver-loop time x ranks: "
              "no sign of other load on the machine")
    if a.mpi_missing:
        print(f"PySPH MPI comparison missing: {a.mpi_missing}")


if __name__ == "__main__":
    main()
