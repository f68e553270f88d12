"""Command line: python -m mpisph CASE [options] | list | info CASE [--set ...] | info FRAME | OUT_DIR
| report FRAME... | plot OUT_DIR [PNG]
| compare CASE --stabiliser A,B,... (compare.py)

Identical under ``mpirun -n N``; rank 0 prints. Bad input ends with one line
``mpisph: error: ...`` on stderr and status 2 before anything is written; a
blow-up writes a last frame and ends with status 3. SIGTERM or SIGUSR1 (parallel/stop.py) ends
a run after the current step with a frame, a line that says how to restart, and status 0.
"""

import os
import shlex
import sys
import tempfile
import time
import traceback
from pathlib import Path

from .arguments import COMPARE_USAGE, Parser, add_set, add_times, parse_sets, with_times
from .errors import BlowUp, InputError, Stopped

WORD_COMMANDS = {  # the commands that take plain words: their usage and what they do, which --help prints
    "list": ("python -m mpisph list", "Lists the cases, each with the first paragraph of its description."),
    "report": ("python -m mpisph report FRAME|OUT_DIR [...]",
               "Prints each frame's tensile-instability measures (clustering, inner voids, fragments, closest "
               "pair); for a solid or a soil also the share of paired particles since its run's first frame. "
               "An OUT_DIR stands for each of its frames, in time order."),
    "plot": ("python -m mpisph plot OUT_DIR [PNG]",
             "Draws the last frame of the run in OUT_DIR (particles by plastic strain, or by speed, the walls "
             "and the initial outline) into PNG (default OUT_DIR/deposit.png) and prints its path, and a "
             "warning for each frame file it left out as incomplete."),
}

USAGE = ("python -m mpisph CASE [--set NAME=VALUE ...] [--t-end T] [--output-interval DT] "
         "[--out DIR] [--restart FRAME] [--quiet]\n"
         "       python -m mpisph --restart FRAME [--set NAME=VALUE ...] [--t-end T] [--out DIR] [--quiet]\n"
         f"       {WORD_COMMANDS['list'][0]}\n"
         "       python -m mpisph info CASE [--set NAME=VALUE ...] | FRAME | OUT_DIR\n"
         f"       {WORD_COMMANDS['report'][0]}\n"
         f"       {WORD_COMMANDS['plot'][0]}\n"
         f"       {COMPARE_USAGE}")


def _parser():
    p = Parser(prog="mpisph", usage=USAGE, description="MPI-parallel SPH for fluids and geomaterials.")
    p.add_argument("case", nargs="?", help="the case (a name of cases/ or a case file); a restart's default: "
                   "its frame's")
    add_set(p)
    add_times(p)
    p.add_argument("--out", help="output directory (default runs/CASE, or for a restart the frame's directory); "
                   "a run replaces the frames an earlier run wrote there after its start (with a warning when they "
                   "are another case's), but a restart into its frame's directory that no --out names refuses to "
                   "replace frames after its time")
    p.add_argument("--restart", metavar="FRAME", help="continue from this frame file")
    p.add_argument("--quiet", action="store_true",
                   help="print neither the opening, progress nor closing lines (warnings and errors still print)")
    return p


def _overrides(args):
    for option, value in (("--out", args.out), ("--restart", args.restart)):
        if value == "":
            raise InputError(f"{option} needs a path, not an empty one")
    return with_times(parse_sets(args.overrides), args)


def cmd_list():
    from .case import case_names, describe, load_case_module
    names = case_names()
    width = max(map(len, names), default=0)
    for name in names:
        print(f"{name:<{width}}  {describe(load_case_module(name))}")


def cmd_info(name, overrides):
    """The case's description, parts, parameters (default, unit, meaning) and the arrays its frames
    hold with its default parameters but ``overrides`` ({name: text} of --set)."""
    import numpy as np

    from .case import all_params, build_case, describe, load_case_module, resolve_params
    from .gauges import Gauge
    from .observables import column_docs
    from .parts import make_parts
    module = load_case_module(name)
    values = resolve_params(module, overrides)
    case = build_case(module, values)
    parts = make_parts(case, values)  # before any line: parameters that cannot go together stop here
    fields = parts.frame_fields
    print(f"{name}: {describe(module)}")
    forces = ", ".join(type(f).__name__ for f in case.forces)
    print(f"scheme {case.scheme}, integrator {parts.integrator.name}, "
          f"stabilisers {', '.join(case.stabilisers) or 'none'}" + (f", forces {forces}" if forces else ""))
    print(size_line(case, fields, values, parts.kernel.support))
    print()
    params = all_params(module)
    width, default_width = max(map(len, params)), max(len(repr(p.default)) for p in params.values())
    for key, p in params.items():
        extra = (f" (one of {', '.join(p.choices)})" if p.choices else
                 f" (in [{p.bounds[0]:g}, {p.bounds[1]:g}))" if p.bounds else "")
        print(f"  {key:<{width}}  {p.default!r:>{default_width}} {p.unit:<6} {p.doc}{extra}")
    print()
    print("frames hold for each particle, with these parameters (ParaView's point arrays; x gives the points):")
    width = max(len(f.name) for f in fields)
    for f in fields:
        shape = "x".join(map(str, f.shape_in(case.dim))) or "scalar"
        print(f"  {f.name:<{width}}  {np.dtype(f.dtype).name:<7} {shape:<6} {f.doc}")
    print()
    print("diagnostics.csv's columns" + (" (2D: per metre of depth)" if case.dim == 2 else "") + ":")
    docs = column_docs(case, parts.scheme)
    width = max(map(len, docs))
    for column, doc in docs.items():
        print(f"  {column:<{width}}  {doc}")
    for g in case.gauges:
        print(f"gauge_{g.name}.csv: " + (f"t, then for each of its {len(g.points)} points (gauge_{g.name}_points.csv) "
                                          f"its kernel sum and {', '.join(g.fields)} (their units as above)"
                                          if isinstance(g, Gauge) else
                                          f"t, then the material's top over its {len(g.stations)} station"
                                          f"{'s' * (len(g.stations) != 1)} (gauge_{g.name}_points.csv) [m]"))


def size_line(case, fields, values, support):
    """What a run of ``case`` holds, from its sources' estimates before any particle is made: the
    particles, the memory to run them (memory.RUN_BYTES_PER_PARTICLE), the frames' size, and the
    most ranks its slabs of the kernel's ``support`` allow."""
    import math

    import numpy as np

    from .memory import RUN_BYTES_PER_PARTICLE
    from .parallel.decomposition import slab_count
    count = case.particle_estimate
    per_frame = count * sum(np.dtype(f.dtype).itemsize * math.prod(f.shape_in(case.dim)) for f in fields)
    frames = math.floor(values["t_end"] / values["output_interval"] + 1e-9) + 1

    def size(n):
        return f"{n / 1e9:.3g} GB" if n >= 1e9 else f"{n / 1e6:.3g} MB"
    return (f"size: about {count:.3g} particles (walls included), about {size(count * RUN_BYTES_PER_PARTICLE)} to "
            f"run over all ranks (at most {RUN_BYTES_PER_PARTICLE} bytes a particle, mpisph/memory.py), "
            f"{size(per_frame)} of arrays a frame, {frames} frames to t_end; at most "
            f"{slab_count(case.domain[0][case.slab_axis], case.domain[1][case.slab_axis], support)} ranks "
            f"(slabs {support:g} m wide along {'xyz'[case.slab_axis]})")


def cmd_frame_info(path):
    """What the frame ``path`` holds: its case, time and step, its particles, and each array with its
    type, shape and meaning (the meaning from its case's fields, where the case can be built)."""
    import numpy as np

    from .case import build_case, load_case_module, resolve_params
    from .io.frames import read_frame
    from .parts import make_parts
    frame = read_frame(path, walls=True)
    params = frame["params"]
    try:
        module = load_case_module(params["case"])
        values = resolve_params(module, {}, base=params)  # a parameter newer than the frame: its default
        docs = {f.name: f.doc for f in make_parts(build_case(module, values), values).frame_fields}
    except (InputError, OSError, KeyError):  # the case file gone, or changed past its frames
        docs = {}
    moving = int(np.count_nonzero(frame["kind"] == 0))
    print(f"{path}: case {params.get('case')}, t = {frame['t']:g} s, step {frame['step']}, {frame['dim']}D, "
          f"{len(frame['gid'])} particles ({moving} moving)")
    print("run with: " + " ".join(f"{k}={v}" for k, v in sorted(params.items()) if k != "case"))
    arrays = {k: a for k, a in frame.items() if isinstance(a, np.ndarray)}
    width = max(map(len, arrays))
    for name, a in arrays.items():
        shape = "x".join(map(str, a.shape[1:])) or "scalar"
        print(f"  {name:<{width}}  {a.dtype.name:<7} {shape:<6} {docs.get(name, '')}".rstrip())


def cmd_report(paths):
    """Tensile-instability measure of each frame (a directory: each of its frames; see
    mpisph.instability); for a solid or a soil,
    also the paired share against the first frame of its run's directory (mpisph.pairing); a run
    restarted into a directory of its own has no frame from t = 0 there, and the line says since when,
    or that there is none before the frame."""
    from pathlib import Path

    from . import pairing
    from .case import build_case, load_case_module
    from .instability import tensile_instability
    from .io.frames import check_frame, list_frames, read_frame
    frames = []
    for path in paths:
        if os.path.isdir(path):
            if not list_frames(path):
                raise InputError(f"{path} holds no frames")
            frames += list_frames(path)
        else:
            check_frame(path)
            frames.append(path)
    paths = frames
    firsts = {}  # the first frame of each run directory, read once
    for path in paths:
        frame = read_frame(path, walls=True)
        params = frame["params"]
        case = build_case(load_case_module(params["case"]), params)
        lo, hi = case.domain
        periods = [hi[a] - lo[a] if case.periodic[a] else 0.0 for a in range(case.dim)]
        m = tensile_instability(frame, lo, periods)
        paired = ""
        if pairing.applies(case):
            run = str(Path(path).parent)
            if run not in firsts:
                firsts[run] = read_frame(list_frames(run)[0])
            first = firsts[run]
            since = f" since its first frame here, t = {first['t']:.6g} s" if first["t"] > 0 else ""
            paired = (f" ({100 * pairing.paired_share(frame, first):.3f}% paired{since})"
                      if first["t"] < frame["t"] or not since else " (paired share: no earlier frame in its directory)")
        print(f"{path}: t = {frame['t']:.6g} s, {m['n']} particles, clustering {100 * m['clustering']:.3f}%{paired}, "
              f"inner voids {100 * m['inner_voids']:.3f}%, free surface {100 * m['surface']:.2f}%, "
              f"closest pair {m['min_spacing']:.3f} dp, {m['fragments']} fragment{'s' * (m['fragments'] > 1)} "
              f"({100 * m['detached']:.2f}% outside the largest)")


def cmd_plot(out_dir, png_path=None):
    """PNG of the last frame of a run: particles by plastic strain (or speed), walls, initial outline."""
    from .io.frames import incomplete_frames
    from .plots import deposit_png
    print(f"wrote {deposit_png(out_dir, png_path)}")
    for path, why in incomplete_frames(out_dir).items():
        print(f"mpisph: warning: left out {path} ({why})", file=sys.stderr)


def _prepare_out_dir(comm, path, start, values, keep_later=False, restart_frame=None):
    """Create the output directory on rank 0, check it can be written, and delete the frames an
    earlier run wrote there after ``start``, the time this run (its parameters ``values``) starts
    from (-inf from the start), with a warning when they are another case's; with ``keep_later`` (a
    restart into its frame's directory that no --out named) refuse instead when there are such
    frames. Frames are numbered by t / output_interval: refuse a run whose frames would write over a
    frame it keeps (stored up to ``start``), but ``restart_frame``, the frame a restart with its own
    run's output interval goes on from, which that run would also replace (a frame that a signal or
    the end time put between two output times)."""
    from .io.frames import (drop_frames_after, frame_cases, frame_path, frame_time, frames_after,
                            frames_kept_and_numbered_from, regular_frame_number)

    interval = values["output_interval"]
    problem = None
    if comm.rank == 0:
        later = frames_after(path, start) if keep_later else []
        first = regular_frame_number(start, interval) + 1 if start > -float("inf") else 0
        over = [p for p in frames_kept_and_numbered_from(path, start, first)
                if restart_frame is None or not os.path.samefile(p, restart_frame)]
        if later:
            problem = (f"{path} holds {len(later)} frame(s) after t = {start:g} s, which a restart there "
                       f"replaces: give --out {path} to replace them, or --out another directory")
        elif over:
            problem = (f"this run numbers its frames by t / output_interval = {interval:g} s from "
                       f"{os.path.basename(frame_path(path, first))} on, which would write over "
                       f"{os.path.basename(over[0])} (t = {frame_time(over[0]):g} s) in {path}: keep the "
                       "output_interval it was written with, or give --out another directory")
        else:
            try:
                os.makedirs(path, exist_ok=True)
                with tempfile.NamedTemporaryFile(dir=path):
                    pass
                others = {case: n for case, n in frame_cases(path).items()
                          if case != values["case"]} if start == -float("inf") else {}
                if others:
                    held = ", ".join(f"{n} of case {case}" for case, n in sorted(others.items(), key=str))
                    print(f"mpisph: warning: {path} held frames ({held}), which this run of "
                          f"{values['case']} replaces", file=sys.stderr, flush=True)
                drop_frames_after(path, start)
            except OSError as e:
                problem = f"cannot write output directory {path!r}: {e.strerror or e}"
    problem = comm.bcast(problem, root=0)
    if problem:
        raise InputError(problem)


def _check_restart(frame, t, values):
    """Refuse a restart from ``frame``, written at time ``t``, to an end time (in ``values``) not after it."""
    if not values["t_end"] > t:
        raise InputError(f"t_end = {values['t_end']:g} s is not after the time of {frame}, {t:g} s: "
                         "give a later --t-end")


def _layout(case):
    """What a case's particles are placed by: the domain, and each source's size with its first and
    last positions (sources.py)."""
    import numpy as np

    ends = [(s.size, *(np.asarray(s.position(i)).tolist() for i in (0, s.size - 1))) if s.size else (0,)
            for s in case.sources]
    return np.asarray(case.domain).tolist(), ends


def _check_layout(frame, module, written, overrides, case):
    """Refuse a restart from ``frame`` (written with the parameters ``written``) whose ``overrides``
    build ``case`` with particles or a domain other than the frame's: a restart moves on the frame's
    particles, so the spacing or the shape of a body cannot change there."""
    from .case import case_of_frame

    if _layout(case) != _layout(case_of_frame(written, module)):
        changed = " ".join(f"{k}={v}" for k, v in overrides.items() if k not in ("t_end", "output_interval"))
        raise InputError(f"a restart goes on with the particles of {frame}, which --set {changed} would place "
                         "otherwise: start a new run to change them")


def run(args, comm):
    from . import case as cases
    from .gauges import GaugeRecorder
    from .initial import particles_from_case, particles_from_frame
    from .io.diagnostics import Diagnostics
    from .io.frames import read_rows
    from .memory import check_fits, resident_bytes
    from .observables import observable_names
    from .parallel.stop import StopOnSignal
    from .parts import make_parts
    from .progress import Progress
    from .solver import Simulation
    from .barrier_load import barrier_load_columns
    from .wall_forces import wall_force_columns

    baseline = resident_bytes()
    if args.case is None:  # a restart of the frame's own case
        args.case = str(read_rows(args.restart, 0, 0)["params"].get("case"))
    module = cases.load_case_module(args.case)
    overrides = _overrides(args)
    if args.restart:
        frame = read_rows(args.restart, 0, 0)  # the frame's attributes, no particle
        written = frame["params"]
        if cases.case_key(str(written.get("case"))) != cases.case_key(args.case):
            raise InputError(f"{args.restart} was written by case {written.get('case')!r}, not {args.case!r}")
        values = cases.resolve_params(module, overrides, base=written)
        _check_restart(args.restart, frame["t"], values)
    else:
        values = cases.resolve_params(module, overrides)
    values["case"] = cases.case_key(args.case)
    case = cases.build_case(module, values)
    if args.restart:
        _check_layout(args.restart, module, written, overrides, case)
    parts = make_parts(case, values)
    case.validate(parts.kernel.support)
    if args.restart:
        particles, t, step = particles_from_frame(comm, args.restart, parts)
    else:
        check_fits(comm, case.sources)
        particles, t, step = particles_from_case(comm, case, parts), 0.0, 0
    case.forget_particles()
    restarted = bool(args.restart)
    # a restart continues in its frame's directory unless told otherwise (the frame's own, through links)
    out_dir = args.out or (os.path.dirname(os.path.realpath(args.restart)) if restarted
                           else os.path.join("runs", Path(args.case).stem))  # a case file: runs/ its name
    progress = Progress(comm, quiet=args.quiet, baseline_bytes=baseline)
    stop = StopOnSignal()
    sim = Simulation(comm, case, values, particles, parts, t=t, step=step,
                     configurations=frame["configurations"] if restarted else 0, out_dir=out_dir,
                     diagnostics=None, progress=progress, stop=stop)
    if case.gauges:
        sim.gauges = GaugeRecorder(case, particles, comm, parts.scheme.derived)
    wall0, step0 = time.perf_counter(), sim.step  # the phase timer's span: the first configuration on
    if not restarted:
        sim.configure_start()  # refuses overlapping bodies and walls before anything is written
    own_interval = restarted and values["output_interval"] == written["output_interval"]
    _prepare_out_dir(comm, out_dir, t if restarted else -float("inf"), values,
                     keep_later=restarted and not args.out, restart_frame=args.restart if own_interval else None)
    sim.diagnostics = Diagnostics(out_dir, comm, observable_names(case.dim, parts.scheme, case.probes, case.front,
                                                                  wall_force_columns(case), barrier_load_columns(case)),
                                  append=restarted, restart_time=t if restarted else None)
    if sim.gauges is not None:
        sim.gauges.open(out_dir, append=restarted, restart_time=t if restarted else None)
    progress.start(sim)
    stopped = None
    try:
        sim.run()
    except Stopped as e:
        stopped = e
    finally:
        stop.close()
        sim.diagnostics.close()
        if sim.gauges is not None:
            sim.gauges.close()
    progress.finish(sim, time.perf_counter() - wall0, step0, ended="stopped" if stopped else "done")
    if stopped and comm.rank == 0:
        print(f"mpisph: {stopped}; frame {stopped.frame} written; continue with: mpirun -n {comm.size} "
              f"{shlex.quote(sys.executable)} -m "
              f"mpisph {values['case']} --restart {stopped.frame} --out {out_dir}", flush=True)


def main(argv=None, comm=None):
    """Run the command ``argv`` (default: the command line) on the ranks of ``comm`` (default: all of
    them; tests/runs_in_one_launch.py gives it a part of them); returns the exit status."""
    argv = sys.argv[1:] if argv is None else argv
    if comm is None:
        from mpi4py import MPI
        comm = MPI.COMM_WORLD
    try:
        if argv[:1] and argv[0] in WORD_COMMANDS and {"-h", "--help"} & set(argv[1:]):
            if comm.rank == 0:
                print("usage: {}\n\n{}".format(*WORD_COMMANDS[argv[0]]))
            return 0
        if argv[:1] == ["list"]:
            if len(argv) != 1:
                raise InputError(f"usage: {WORD_COMMANDS['list'][0]}")
            if comm.rank == 0:
                cmd_list()
            return 0
        if argv[:1] == ["info"]:
            info = Parser(prog="mpisph info", usage="python -m mpisph info CASE [--set NAME=VALUE ...] | FRAME | OUT_DIR")
            info.add_argument("case")
            add_set(info)
            args = info.parse_args(argv[1:])
            if os.path.isdir(args.case):  # a run's directory: its last frame
                from .io.frames import list_frames
                frames = list_frames(args.case)
                if not frames:
                    raise InputError(f"info: {args.case} holds no complete frames (frame_*.hdf)")
                args.case = frames[-1]
            if args.case.endswith((".hdf", ".vtkhdf")) or (os.path.isfile(args.case) and not args.case.endswith(".py")):
                if args.overrides:
                    raise InputError("info FRAME takes no --set: a frame holds the parameters it was written with")
                if comm.rank == 0:
                    cmd_frame_info(args.case)
            elif comm.rank == 0:
                cmd_info(args.case, parse_sets(args.overrides))
            return 0
        if argv[:1] == ["report"]:
            if len(argv) < 2:
                raise InputError(f"usage: {WORD_COMMANDS['report'][0]}")
            if comm.rank == 0:
                cmd_report(argv[1:])
            return 0
        if argv[:1] == ["plot"]:
            if len(argv) not in (2, 3):
                raise InputError(f"usage: {WORD_COMMANDS['plot'][0]}")
            if comm.rank == 0:
                cmd_plot(*argv[1:])
            return 0
        if argv[:1] == ["compare"]:
            if comm.size > 1:
                raise InputError("compare starts its own mpirun for each run: start it without mpirun")
            from .compare import main as compare
            return compare(argv[1:])
        parser = _parser()
        args = parser.parse_args(argv)
        if args.case is None and args.restart is None:
            parser.error("the following arguments are required: case")
        run(args, comm)
        return 0
    except InputError as e:
        if comm.rank == 0:
            print(f"mpisph: error: {e}", file=sys.stderr, flush=True)
        return 2
    except BlowUp as e:
        if comm.rank == 0:
            print(f"mpisph: {e}", file=sys.stderr, flush=True)
        return 3
    except Exception:
        if comm.size == 1:
            raise
        traceback.print_exc()  # a fault on one rank: end every rank rather than leave them waiting
        sys.stderr.flush()
        comm.Abort(1)


if __name__ == "__main__":
    try:
        status = main()
        sys.stdout.flush()
    except BrokenPipeError:  # `list | head` closed the pipe: stop quietly, as a shell tool does
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # no second error at exit's flush
        status = 1
    sys.exit(status)
