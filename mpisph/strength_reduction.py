"""The factor of safety of a Drucker-Prager case by strength reduction (Zienkiewicz et al. 1975;
Griffiths & Lane 1999; with SPH, Bui et al. 2011): c and tan phi (and tan psi) divided by a factor F
in stages, each a restart of the last stage that stood.

A stage is one run in a directory of its own: the first, the case's release, runs from the start
with the first factor's strength and settles; every later one restarts from the last frame of the
last stage that stood with a larger factor. A stage slid when the 99th percentile of its particles'
displacements over it passes SLIDE of the height H per second of the stage (0.015 H over a stage of
1 s; a cut at rest creeps by a few thousandths of H a second, docs/CUTS.md, so a longer stage or a
hold may creep by more than 0.015 H and still stand). H is the body's top above the floor y = 0
(``measure.cut_height`` of the release's first frame) unless the search is given another: a slope on
a foundation is judged on the slope's own height, not the foundation's with it. ``search`` climbs
the factors to the first that slides, then halves the bracket between the last that stood and the
first that slid; the factor of safety lies in it, and ``hold`` runs the last that stood on for
longer, to see that it keeps standing. No stage restarts a slid one: a slide changes the body's
shape, so later stages would test another body. Analysis only: the step loop does not load this
module.
"""

import json
import math
import os
from dataclasses import asdict, dataclass

import numpy as np

from mpisph.arguments import parse_sets
from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import frame_time, list_frames, read_frame
from mpisph.measure import cut_height, displacement_percentile
from mpisph.references import vertical_cut_safety_factor

SLIDE = 0.015  # share of the height per second that a stage's 99 % displacement passes when the body slid
RECORD = "stages.json"  # the stages of a search, in the order they ran, in its directory


def reduced(params, factor):
    """(c, phi, psi) of ``params`` with c and the tangents of the angles divided by ``factor``."""
    def angle(name):
        return math.degrees(math.atan(math.tan(math.radians(float(params[name]))) / factor))
    return float(params["cohesion"]) / factor, angle("phi"), angle("psi")


@dataclass
class Stage:
    """One stage's outcome: its factor, directory and time span [s]; the kinetic-energy peak [J] of its
    diagnostics and when it came [s into the stage]; the kinetic energy at its end [J]; the 99 %
    displacement over the stage and since the release, over the height H; 'settling' (the first
    stage), 'stood' or 'slid'; H [m]."""
    factor: float
    directory: str
    start: float
    end: float
    peak_energy: float
    peak_time: float
    end_energy: float
    moved: float
    since_release: float
    outcome: str
    height: float


def stage_outcome(factor, directory, before, release, height, settling=False):
    """The Stage run in ``directory`` from the frame ``before``, the last of the stage it restarted
    (for the release, ``settling``, its own first frame); ``release`` is the release's first frame;
    ``height`` is H."""
    last = read_frame(list_frames(directory)[-1])
    diag = read_diagnostics(os.path.join(directory, "diagnostics.csv"))
    inside = diag["t"] > before["t"] + 1e-9
    energy, times = diag["kinetic_energy"][inside], diag["t"][inside]
    k = int(np.argmax(energy))
    moved = displacement_percentile(before, last) / height
    outcome = "settling" if settling else "slid" if moved > SLIDE * (last["t"] - before["t"]) else "stood"
    return Stage(factor, str(directory), float(before["t"]), float(last["t"]), float(energy[k]),
                 float(times[k] - before["t"]), float(energy[-1]), moved,
                 displacement_percentile(release, last) / height, outcome, height)


def stage_arguments(soil, factor, sets=(), restart=None, t_end=None, interval=None):
    """The mpisph arguments of a stage with ``factor``: the case's ``sets`` for the release, else
    ``--restart`` of the frame ``restart``; the reduced strength (in place of any strength in
    ``sets``); its end time and frame spacing."""
    c, phi, psi = reduced(soil, factor)
    case_sets = parse_sets(sets) if restart is None else {}
    values = {**case_sets, "cohesion": repr(c), "phi": repr(phi), "psi": repr(psi)}  # the reduced strength wins
    start = [] if restart is None else ["--restart", restart]
    start += ["--set", *(f"{name}={value}" for name, value in values.items())]
    return [*start, "--t-end", repr(t_end), "--output-interval", repr(interval)]


def search(launch, case, sets, soil, factors, settle, stage, bisect=0, height=None):
    """Stages of ``case`` (parameters ``soil``, the --set items ``sets``): the release with factors[0]
    for ``settle`` seconds, then a stage of ``stage`` seconds (frames a quarter of it apart) per
    further factor from the last that stood, until one slides, then ``bisect`` stages at the middle of
    the bracket; H is ``height`` (default: the release's cut_height). ``launch(name, case, arguments)``
    runs one stage and returns its directory. Returns the Stages in the order they ran."""
    first = launch(f"stage00_F{factors[0]:g}", case,
                   stage_arguments(soil, factors[0], sets, t_end=settle, interval=stage / 4))
    release = read_frame(list_frames(first)[0])
    stages = [stage_outcome(factors[0], first, release, release, height or cut_height(release), settling=True)]
    stood, slid = stages[0], None
    for factor in factors[1:]:
        slid = restart_stage(launch, case, stages, soil, stood, factor, stage)
        if slid.outcome == "slid":
            break
        stood, slid = slid, None
    for _ in range(bisect if slid is not None else 0):
        middle = restart_stage(launch, case, stages, soil, stood, 0.5 * (stood.factor + slid.factor), stage)
        stood, slid = (stood, middle) if middle.outcome == "slid" else (middle, slid)
    return stages


def restart_stage(launch, case, stages, soil, stood, factor, seconds, suffix=""):
    """A stage with ``factor`` for ``seconds`` (frames a quarter of it apart) from the last frame of
    the Stage ``stood``, in the directory stageNN_F<factor><suffix>; its Stage is appended to
    ``stages`` and returned."""
    before = list_frames(stood.directory)[-1]
    directory = launch(f"stage{len(stages):02d}_F{factor:g}{suffix}", case, stage_arguments(
        soil, factor, restart=before, t_end=stood.end + seconds, interval=seconds / 4))
    stages.append(stage_outcome(factor, directory, read_frame(before), release_frame(stages), stood.height))
    return stages[-1]


def hold(launch, case, stages, soil, seconds):
    """The last stage at the bracket's lower factor run on at that factor for ``seconds`` more (its
    directory ends in _hold); its Stage is appended to ``stages`` and returned. A cut that stood for
    one stage may still give way later: ``bracket`` then counts the factor as slid. Raises ValueError
    when no factor stands below every slide (a hold of the release gave way)."""
    lower = bracket(stages)[0]
    if lower is None:
        raise ValueError(f"no factor stood below every slide (the release, F = {stages[0].factor:g}, gave way "
                         "in a hold): nothing to hold; search again from a smaller first factor")
    stood = [s for s in stages if s.outcome != "slid" and s.factor == lower][-1]
    return restart_stage(launch, case, stages, soil, stood, stood.factor, seconds, suffix="_hold")


def bracket(stages):
    """(the largest factor below every slide at which a stage stood or the release settled, the
    smallest at which one slid, or None when none did): the factor of safety lies between them. A
    factor that stood in one stage and slid in a later one (a hold) counts as slid."""
    slid = [s.factor for s in stages if s.outcome == "slid"]
    least = min(slid, default=math.inf)
    stood = max((s.factor for s in stages if s.outcome != "slid" and s.factor < least), default=None)
    return stood, min(slid, default=None)


def release_creep(stages):
    """How fast the release still moved at its end: the 99 % displacement over its second half (from
    its first frame at or after half its time, so that the ringing of the settling averages out) over
    the height H, per second. A stage that moves SLIDE H per second slid, so a release still creeping
    at SLIDE or more had not settled: the first stage after it would slide at any factor."""
    paths = list_frames(stages[0].directory)
    times = [frame_time(p) for p in paths]  # the attributes alone; three frames are read whole
    middle = next(k for k, t in enumerate(times) if t >= 0.5 * (times[0] + times[-1]) - 1e-9)
    before, last = (read_frame(paths[k]) for k in (middle, -1))
    return displacement_percentile(before, last) / stages[0].height / (last["t"] - before["t"])


def release_frame(stages):
    """The first frame of the release, the first of the Stages."""
    return read_frame(list_frames(stages[0].directory)[0])


def check_record(stages, case, soil):
    """Raise ValueError unless the recorded ``stages`` ran ``case`` (its key) with the strength of
    ``soil``: their release frame holds the case and the strength divided by the first factor, so a
    table or a hold read from a record with another case or --set would carry a strength the stages
    never had."""
    written = release_frame(stages)["params"]
    factor = stages[0].factor
    ran = tuple(float(written.get(name, math.nan)) for name in ("cohesion", "phi", "psi"))
    if written.get("case") != case or not np.allclose(ran, reduced(soil, factor), rtol=1e-9, atol=0.0):
        c, phi, psi = reduced(dict(zip(("cohesion", "phi", "psi"), ran)), 1.0 / factor)  # times the factor
        raise ValueError(f"the search recorded there ran case {written.get('case')!r} with c = {c / 1e3:.4g} kPa, "
                         f"phi = {phi:.4g} deg, psi = {psi:.4g} deg (reduced by F = {factor:g} and on), which "
                         f"case {case!r} with these --set items does not give: name the case and the --set "
                         "items it ran with")


def limit_factors(height, soil):
    """The factors F at which limit analysis puts a vertical cut of ``height`` in ``soil`` critical:
    for associated flow, Chen's, and for the soil's psi, Drescher & Detournay's
    (references.vertical_cut_safety_factor)."""
    return vertical_cut_safety_factor(soil["cohesion"], soil["phi"], soil["rho0"] * soil["g"], height, soil["psi"])


def write_record(directory, stages):
    """Write the Stages to RECORD in ``directory``."""
    with open(os.path.join(directory, RECORD), "w") as f:
        json.dump([asdict(s) for s in stages], f, indent=1)


def read_record(directory):
    """The Stages that ``write_record`` wrote in ``directory`` (a record written before the Stages held
    H: the release's cut_height, as they were judged on)."""
    with open(os.path.join(directory, RECORD)) as f:
        stages = json.load(f)
    if stages and "height" not in stages[0]:
        height = cut_height(read_frame(list_frames(stages[0]["directory"])[0]))
        stages = [{**s, "height": height} for s in stages]
    return [Stage(**s) for s in stages]


def table(stages, soil):
    """The Markdown table of the Stages, with the reduced c and phi of ``soil``."""
    lines = ["| F | c [kPa] | phi [deg] | peak kinetic energy [J] at [s into the stage] | kinetic energy at "
             "the end [J] | 99 % displacement over the stage / H | since the release / H | over "
             f"{SLIDE:g} H per second |", "|---|---|---|---|---|---|---|---|"]
    for s in stages:
        c, phi, _ = reduced(soil, s.factor)
        lines.append(f"| {s.factor:g} | {c / 1e3:.3f} | {phi:.2f} | {s.peak_energy:.3g} at +{s.peak_time:.2f} | "
                     f"{s.end_energy:.3g} | {s.moved:.4f} | {s.since_release:.3f} | {s.outcome} |")
    return lines
