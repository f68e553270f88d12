"""``python -m mpisph compare CASE --stabiliser none,tvf,utvf [--set NAME=VALUE ...] [--t-end T]
[--output-interval DT] [-n RANKS] [--out DIR] [--colour FIELD]``: the case once per stabiliser, side
by side (the times as in a run, or as --set t_end and output_interval); a run may combine remedies,
as ``--stabiliser utvf,artificial_stress+utvf`` (stabilisers/__init__.py). ``--vary NAME=A,B,...``
compares the values of any other parameter instead (``--vary m_0=1.2,40``, ``--vary
viscous_form=cleary,corrected_stress``); ``--stabiliser A,B`` is ``--vary stabiliser=A,B``.

Each run goes to OUT/<value>/ (OUT defaults to runs/compare_CASE) under ``mpirun -n RANKS``;
OUT/compare.md gets a table with, for each, how the run ended and, from its last frame and its
diagnostics:

- clustering, inner voids, the closest pair over dp and the fragments, with the share of the
  particles outside the largest (instability.py, walls included);
- for an elastic solid or a soil on a domain without periodic axes, the paired share: particles
  nearer than dp/2 that the flow did not bring together (pairing.py), where clustering also counts
  a lattice squeezed by the flow;
- the change of total energy, kinetic plus gravitational plus an elastic solid's strain energy,
  dE = E_end - E_0 in J and as a fraction of the energy that moved, max KE + max |PE - PE_0| (PE
  with the strain energy);
- for a case without walls or clamped particles, the drift of linear momentum from gravity's impulse, |P_end - P_0 -
  M g t| / (M v_ref), and with neither gravity nor a periodic axis the drift of angular momentum,
  |L_end - L_0| / (M v_ref R), where v_ref = sqrt(2 max KE / M) and R is the initial radius of
  gyration (walls and clamps exchange momentum with the body and periodic wraps move r x p, so
  there the columns would say nothing and are left out);
- the runout (last ``front`` minus the first) where the case records a front;

and, in a second table, what the case records: each probe's displacement at the end and the peak
force on each wall of ``Case.wall_forces``.

OUT/compare_particles.png shows the last frame of each run coloured by FIELD (default: speed; 3D
runs seen along y) on one colour scale, three panels a row, each framing the material of every run
(walls beyond it cut off), and OUT/compare_energy.png the kinetic and total energy
against time. A run that blows up (status 3) is measured at its last frame; a run that fails
otherwise is listed as failed, with its error line (its whole standard error is in
OUT/<value>/stderr.txt), and compare then exits with status 1 once the others are written. A value
named twice, one the parameter does not take, or a ``--colour`` field that a run's frames would not
hold, stops compare before any run.
"""

import os
from pathlib import Path

import numpy as np

from . import pairing
from .arguments import COMPARE_USAGE, Parser, add_set, add_times, parse_sets, with_times
from .case import all_params, build_case, load_case_module, resolve_params
from .errors import InputError
from .instability import tensile_instability
from .io.diagnostics import read_diagnostics
from .io.frames import list_frames, read_frame
from .launch import mpirun_mpisph
from .particles import MOVING
from .parts import make_parts
from .plots import SPEED_LABEL


def parse(argv):
    p = Parser(prog="mpisph compare", usage=COMPARE_USAGE)
    p.add_argument("case", help="the case (a name of cases/ or a case file)")
    p.add_argument("--stabiliser", help="stabilisers to compare, separated by commas")
    p.add_argument("--vary", metavar="NAME=A,B,...", help="another parameter's values to compare instead")
    add_set(p)
    add_times(p)
    p.add_argument("-n", dest="ranks", type=int, default=1, help="MPI ranks per run (default 1)")
    p.add_argument("--out", help="output directory (default runs/compare_CASE)")
    p.add_argument("--colour", default="speed", help="particle field of the picture (default: speed)")
    a = p.parse_args(argv)
    if a.ranks < 1:
        raise InputError(f"-n takes a positive number of ranks, not {a.ranks}")
    if (a.stabiliser is None) == (a.vary is None):
        raise InputError("compare takes --stabiliser A,B,... or --vary NAME=A,B,..., one of the two")
    if a.vary is not None and "=" not in a.vary:
        raise InputError(f"--vary takes NAME=A,B,..., not {a.vary!r}")
    return a


def varied(a):
    """(the parameter compared, its values) of the parsed command line ``a``."""
    name, values = ("stabiliser", a.stabiliser) if a.vary is None else a.vary.split("=", 1)
    return name.strip(), run_names(values)


def run_names(text):
    """The values of ``--stabiliser A,B+C,...`` or ``--vary NAME=A,B,...``, one run each (``none`` is
    a run too, and B+C one with two remedies)."""
    return tuple(t.strip() for t in text.split(",") if t.strip())


def _option(name):
    """The option of compare that names the values of the parameter ``name``."""
    return "--stabiliser" if name == "stabiliser" else "--vary"


def set_overrides(items, name):
    """The parameters of ``--set``; InputError for the compared parameter ``name`` among them."""
    out = parse_sets(items)
    if name in out:
        raise InputError(f"{name} is what compare varies: give its values to {_option(name)}, not --set")
    return out


def check_values(case_name, module, name, runs, overrides):
    """InputError for a case (its name and module) without the parameter ``name``, an empty list of
    values ``runs`` or one that the parameter does not take beside ``overrides``."""
    option = _option(name)
    if name not in all_params(module):
        raise InputError(f"case {case_name!r} has no {name} parameter to compare")
    if not runs:
        raise InputError(f"{option} names no value")
    twice = sorted({value for value in runs if runs.count(value) > 1})
    if twice:
        raise InputError(f"{option} names {', '.join(twice)} twice: each run goes to a directory of its name")
    for value in runs:
        resolve_params(module, {**overrides, name: value})


def check_colour(module, name, runs, overrides, colour):
    """InputError, before any run, when ``colour`` is neither the speed nor a field that the frames
    of every run (its value of ``name`` beside ``overrides``) hold."""
    if colour == "speed":
        return
    for value in runs:
        values = resolve_params(module, {**overrides, name: value})
        fields = {f.name for f in make_parts(build_case(module, values), values).frame_fields}
        if colour not in fields:
            raise InputError(f"--colour {colour}: the frames with {name}={value} have no such field "
                             f"(they hold {', '.join(sorted(fields | {'speed'}))})")


def check(case_name, name, runs, overrides, colour):
    """The case module and one Case of it (for domain and walls), after ``check_values`` and
    ``check_colour``."""
    module = load_case_module(case_name)
    check_values(case_name, module, name, runs, overrides)
    check_colour(module, name, runs, overrides, colour)
    return module, build_case(module, resolve_params(module, overrides))


def run_one(case_name, setting, overrides, ranks, out):
    """Run the case with ``setting`` ({name: value}) beside ``overrides`` into ``out``; how it ended:
    done, blew up, or failed, and why.

    A run that did not finish leaves its whole standard error in ``out``/stderr.txt; the reason given
    is its last line from mpisph (``mpisph: ...``), so that what Open MPI or numba writes after it
    does not take its place."""
    sets = [f"{k}={v}" for k, v in {**overrides, **setting}.items()]
    r = mpirun_mpisph([case_name, "--set", *sets, "--out", out, "--quiet"], ranks=ranks)
    if r.returncode == 0:
        return "done", ""
    Path(out).mkdir(parents=True, exist_ok=True)
    (Path(out) / "stderr.txt").write_text(r.stderr)
    lines = [line for line in r.stderr.strip().splitlines() if line.strip()]
    ours = [line for line in lines if line.startswith("mpisph:")]
    why = (ours or lines or [f"exit {r.returncode}"])[-1]
    return ("blew up" if r.returncode == 3 else "failed"), why


def potential_energy(d):
    """Gravitational energy plus, for an elastic solid, its strain energy, from diagnostics ``d``."""
    return d["potential_energy"] + (d["strain_energy"] if "strain_energy" in d else 0.0)


def measures(out, case):
    """The table's figures for the run in ``out`` (module docstring)."""
    d = read_diagnostics(Path(out) / "diagnostics.csv")
    frames = list_frames(os.fspath(out))
    first, last = read_frame(frames[0]), read_frame(frames[-1], walls=True)
    lo, hi = case.domain
    periods = [hi[a] - lo[a] if case.periodic[a] else 0.0 for a in range(case.dim)]
    m = tensile_instability(last, lo, periods)
    potential = potential_energy(d)
    energy = d["kinetic_energy"] + potential
    moved = d["kinetic_energy"].max() + np.abs(potential - potential[0]).max()
    out = {"t": float(last["t"]), "clustering": m["clustering"], "inner_voids": m["inner_voids"],
           **({"paired": pairing.paired_share(last, first)} if pairing.applies(case) else {}),
           "closest": m["min_spacing"], "fragments": m["fragments"], "detached": m["detached"],
           "dE": float(energy[-1] - energy[0]),
           "dE_rel": float((energy[-1] - energy[0]) / moved) if moved > 0 else 0.0}
    mass = float(d["mass"][0])
    v_ref = np.sqrt(2.0 * d["kinetic_energy"].max() / mass) if mass > 0 else 0.0
    held = any(b.clamped is not None and np.any(b.clamped) for b in case.bodies)
    if not case.walls and not held and v_ref > 0:
        dim = case.dim
        p = np.array([d[f"momentum_{c}"] for c in "xyz"[:dim]])
        impulse = mass * np.asarray(case.gravity)[:, None] * (d["t"] - d["t"][0])
        out["dP"] = float(np.linalg.norm(p[:, -1] - p[:, 0] - impulse[:, -1]) / (mass * v_ref))
        if not np.any(case.gravity) and not any(case.periodic):
            names = ["angular_momentum_z"] if dim == 2 else [f"angular_momentum_{c}" for c in "xyz"]
            ang = np.array([d[n] for n in names])
            x0 = first["x"]
            radius = np.sqrt(np.mean(np.sum((x0 - x0.mean(axis=0)) ** 2, axis=1)))
            out["dL"] = float(np.linalg.norm(ang[:, -1] - ang[:, 0]) / (mass * v_ref * radius))
    if "front" in d:
        out["runout"] = float(d["front"][-1] - d["front"][0])
    axes = "xyz"[:case.dim]
    out["records"] = {
        **{f"{name}'s displacement at the end [m]": float(np.sqrt(sum(d[f"{name}_u{c}"][-1] ** 2 for c in axes)))
           for name in case.probes},
        **{key: value for name in case.wall_forces for key, value in _peak_force(d, name, axes, case.dim).items()}}
    return out


COLUMNS = ("Of each run's last frame: clustering, the share of particles nearer than dp/2 to another; paired, "
           "of those the ones that the flow's own squeeze of the lattice does not explain (solids and soils); "
           "inner voids, particles at holes inside the material; the closest pair over dp; fragments, the "
           "pieces the body is in (particles within 1.5 dp linked) and the share outside the largest. Over the "
           "run: dE, the change of kinetic, gravitational and strain energy, and over the energy that moved; "
           "the drifts of momentum and angular momentum (cases without walls); the runout, the front's advance "
           "(mpisph/compare.py).")


def _peak_force(d, name, axes, dim):
    """{column: value} of the largest force on wall ``name`` in the diagnostics ``d``: its size |F|,
    when, and its components then."""
    size = np.sqrt(sum(d[f"force_{name}_{c}"] ** 2 for c in axes))
    k = int(np.argmax(size))
    unit = "N" if dim == 3 else "N/m"
    return {f"peak force on {name}, its size [{unit}]": float(size[k]), f"{name}: at t [s]": float(d["t"][k]),
            **{f"{name}: F_{c} then [{unit}]": float(d[f"force_{name}_{c}"][k]) for c in axes}}


def records_table(case_name, rows, name="stabiliser"):
    """Markdown lines of what the case records of each run (its probes' displacement at the end, the
    peak force on each of its named walls, when and its components then); none for a case that
    records neither."""
    columns = next((list(row["records"]) for _, row in rows.values() if row is not None and row["records"]), [])
    if not columns:
        return []
    lines = [f"| {name} ({case_name}) | " + " | ".join(columns) + " |", "|---" * (len(columns) + 1) + "|"]
    for value, (_, row) in rows.items():
        cells = [f"{row['records'][c]:.4g}" for c in columns] if row is not None else ["–"] * len(columns)
        lines.append(f"| {value} | " + " | ".join(cells) + " |")
    return ["", "What the case records (diagnostics.csv):", "", *lines]


def _cell(row, key, fmt, scale=1.0):
    return fmt.format(scale * row[key]) if key in row else "–"


def table(case_name, rows, name="stabiliser"):
    """Markdown lines of the comparison, a row for each value of the parameter ``name``."""
    lines = [f"| {name} ({case_name}) | ended | t [s] | clustering | paired | inner voids | closest pair / dp | "
             f"fragments (outside the largest) | dE [J] | dE / moved | momentum drift | angular drift | runout [m] |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, (status, row) in rows.items():
        if row is None:
            lines.append(f"| {name} | {status} | " + " | ".join(["–"] * 11) + " |")
            continue
        lines.append(f"| {name} | {status} | {row['t']:.4g} | {100 * row['clustering']:.3f} % | "
                     f"{_cell(row, 'paired', '{:.3f} %', 100.0)} | "
                     f"{100 * row['inner_voids']:.3f} % | {row['closest']:.3f} | "
                     f"{row['fragments']} ({100 * row['detached']:.2f} %) | {row['dE']:.4g} | "
                     f"{row['dE_rel']:.3g} | {_cell(row, 'dP', '{:.2e}')} | {_cell(row, 'dL', '{:.2e}')} | "
                     f"{_cell(row, 'runout', '{:.4g}')} |")
    return lines


def _field(frame, name):
    moving = frame["kind"] == MOVING
    if name == "speed":
        return np.linalg.norm(frame["v"][moving], axis=1)
    if name not in frame:
        raise InputError(f"--colour {name}: the frames have no such field")
    value = np.asarray(frame[name])[moving]
    return value if value.ndim == 1 else np.linalg.norm(value.reshape(len(value), -1), axis=1)


def _label(frames, colour):
    """The colour bar's label: the speed with its unit, a field by its name (the norm of its
    components where it has several)."""
    if colour == "speed":
        return SPEED_LABEL
    several = any(np.ndim(f[colour]) > 1 for f in frames.values())
    return f"|{colour}|, the norm of its components" if several else colour


def _material_box(lasts):
    """((x0, z0), (x1, z1)) about every run's moving particles in the pictures' plane (x and the
    last axis), widened by a twentieth of its size: the walls' far layers and the empty domain
    above the material are left out of the panels."""
    x = np.concatenate([last["x"][last["kind"] == MOVING][:, [0, -1]] for last in lasts.values()] or [np.zeros((0, 2))])
    if not len(x):
        return (0.0, 0.0), (1.0, 1.0)
    lo, hi = x.min(axis=0), x.max(axis=0)
    pad = 0.05 * max(float((hi - lo).max()), 1e-12)
    return tuple(lo - pad), tuple(hi + pad)


def pictures(runs, colour, out):
    """compare_particles.png and compare_energy.png in ``out`` from {run's title: its directory}."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    done = {k: v for k, v in runs.items() if list_frames(os.fspath(v))}
    lasts = {name: read_frame(list_frames(os.fspath(run))[-1], walls=True) for name, run in done.items()}
    values = {name: _field(last, colour) for name, last in lasts.items()}
    every = np.concatenate([v[np.isfinite(v)] for v in values.values()] or [np.zeros(0)])
    lo, hi = (float(every.min()), float(every.max())) if len(every) else (0.0, 1.0)
    box = _material_box(lasts)
    columns = min(max(len(done), 1), 3)
    rows = -(-max(len(done), 1) // columns)
    aspect = float(np.clip((box[1][1] - box[0][1]) / (box[1][0] - box[0][0]), 0.3, 1.5))
    fig = Figure(figsize=(4.5 * columns + 0.8, (4.5 * aspect + 0.6) * rows), dpi=110)
    FigureCanvasAgg(fig)
    sc = None
    for k, (name, last) in enumerate(lasts.items()):
        moving = last["kind"] == MOVING
        x = last["x"]
        axes = (0, x.shape[1] - 1)
        ax = fig.add_subplot(rows, columns, k + 1)
        ax.set_xlim(box[0][0], box[1][0])
        ax.set_ylim(box[0][1], box[1][1])
        ax.scatter(x[~moving][:, axes[0]], x[~moving][:, axes[1]], s=0.5, c="0.85", linewidths=0, rasterized=True)
        sc = ax.scatter(x[moving][:, axes[0]], x[moving][:, axes[1]], s=1.0, c=values[name], vmin=lo,
                        vmax=hi if hi > lo else lo + 1.0, linewidths=0, rasterized=True)
        ax.set_aspect("equal")
        ax.set_title(f"{name}, t = {last['t']:.3g} s", fontsize=10)
    if sc is not None:  # one scale for every run, so that their colours compare
        fig.colorbar(sc, ax=fig.axes, shrink=0.8).set_label(_label(lasts, colour))
    fig.savefig(out / "compare_particles.png", bbox_inches="tight", facecolor="white")
    fig = Figure(figsize=(10, 4), dpi=110)
    FigureCanvasAgg(fig)
    kinetic, total = fig.add_subplot(1, 2, 1), fig.add_subplot(1, 2, 2)
    for name, run in done.items():
        d = read_diagnostics(Path(run) / "diagnostics.csv")
        e = d["kinetic_energy"] + potential_energy(d)
        kinetic.plot(d["t"], d["kinetic_energy"], label=name)
        total.plot(d["t"], e - e[0], label=name)
    kinetic.set_xlabel("t [s]")
    kinetic.set_ylabel("kinetic energy [J]")
    total.set_xlabel("t [s]")
    total.set_ylabel("E - E_0, kinetic + gravitational + strain [J]")
    if done:
        kinetic.legend()
    fig.tight_layout()
    fig.savefig(out / "compare_energy.png", facecolor="white")


def main(argv):
    a = parse(argv)
    varies, names = varied(a)
    overrides = with_times(set_overrides(a.overrides, varies), a)
    _, case = check(a.case, varies, names, overrides, a.colour)
    # the runs start in the repository's root (launch.mpirun_mpisph): paths given from here go absolute
    case_arg = str(Path(a.case).resolve()) if a.case.endswith(".py") else a.case
    out = Path(a.out or Path("runs") / f"compare_{Path(a.case).stem}").resolve()
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise InputError(f"cannot write output directory {str(out)!r}: {e.strerror or e}") from None
    runs, rows = {}, {}
    label = (lambda value: value) if varies == "stabiliser" else (lambda value: f"{varies}={value}")
    for name in names:
        runs[name] = out / name
        status, why = run_one(case_arg, {varies: name}, overrides, a.ranks, runs[name])
        has_frames = runs[name].is_dir() and list_frames(os.fspath(runs[name]))
        rows[name] = (status + (f": {why}" if why and status != "done" else ""),
                      measures(runs[name], case) if status != "failed" and has_frames else None)
        print(f"compare: {a.case} with {label(name)}: {status}" + (f": {why}" if status == "failed" else ""), flush=True)
    sets = " ".join(f"--set {k}={v}" for k, v in overrides.items())
    choice = f"--stabiliser {','.join(names)}" if varies == "stabiliser" else f"--vary {varies}={','.join(names)}"
    text = [f"# {a.case}: {'stabilisers' if varies == 'stabiliser' else varies} side by side", "",
            f"`python -m mpisph compare {a.case} {choice} {sets} -n {a.ranks}`", "", *table(a.case, rows, varies), "",
            COLUMNS, *records_table(a.case, rows, varies), "",
            "![particles](compare_particles.png)", "", "![energy](compare_energy.png)", ""]
    pictures({label(name): run for name, run in runs.items()}, a.colour, out)
    (out / "compare.md").write_text("\n".join(text))
    print(f"compare: wrote {out / 'compare.md'}", flush=True)
    failed = [name for name in names if rows[name][0].startswith("failed")]
    if failed:
        print(f"compare: {', '.join(failed)} failed (compare.md and the lines above say why)", flush=True)
    return 1 if failed else 0
