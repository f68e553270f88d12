"""Run the 3D cases of 000_ Secs. 5.3-5.4 at the paper's spacing and write docs/PRODUCTION_3D.md.

    .venv/bin/python scripts/production.py [--ranks 2] [--only cube_failure_3d|cube_band_start|flume_3d ...] [--reuse]

Each run's command, wall time and throughput are printed in the page beside its pictures; each
case runs again with other settings (``VARIANTS``): 000_'s stress diffusion (Feng et al.'s, the
default until session 26) alone and with the options of 3D UTVF (the free-surface particles beside
an edge left in place, then also the near-surface particles projected on the outermost particles'
normals), and, for the cube, the defaults with both UTVF options; their clustering is reported
beside the default's. The script exits non-zero, listing
them, when a figure of the default run misses what issue 15 asks: clustering above 0.1 %
(tensile_instability, checked in 3D), a flume deposit not at rest (largest speed at the end at
least 1 % of its peak) or a load imbalance of 15 % or more while the mass moves. The section
cube_band_start follows where the cube's plastic strain starts with each initial stress. ``--reuse``
measures the runs already in runs/production/ that the same command, rank count and committed code
made (their stamp, as validate.py's) instead of running them again, and runs the others.
"""

import argparse
import json
import re
from pathlib import Path
from types import SimpleNamespace

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from mpisph import measure, pairing, render  # noqa: E402
from mpisph.instability import tensile_instability  # noqa: E402
from mpisph.io.diagnostics import read_diagnostics  # noqa: E402
from mpisph.io.frames import list_frames, read_frame  # noqa: E402
from mpisph.launch import command_line, mpirun_mpisph, stopped_by_signal  # noqa: E402
from mpisph.particles import MOVING  # noqa: E402
from mpisph.soil import drucker_prager  # noqa: E402

import make_flume_stl as flume  # noqa: E402  (this directory: the flume's dimensions)
from clustered import CLASSES, beside_an_edge, shifted_on_the_surface  # noqa: E402  (this directory)
from validation import page  # noqa: E402  (the same page sections as docs/VALIDATION.md)
from validation.runs import has_stamp, stamp_of  # noqa: E402  (and the same stamps of runs)

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
IMG = DOCS / "img"
RUNS = ROOT / "runs" / "production"
STAMP = "production_run.json"
PAGE = DOCS / "PRODUCTION_3D.md"


def run(case, args, ranks, reuse, name=None):
    """The output directory (runs/production/``name``, by default the case's name), the command, the
    wall time, the throughput per core and the blow-up message (None for a run that ended) of a run;
    a blown-up run is measured up to its last frame, its wall time and throughput taken from its last
    progress line. With ``reuse``, a run of the same stamp (stamp_of) is read, not run again."""
    out = RUNS / (name or case)
    shown = command_line(["-m", "mpisph", case, *args], ranks)
    log, stamp = out / "run.log", stamp_of(case, args, ranks)
    if reuse and log.exists() and has_stamp(out / STAMP, stamp):
        print(f"  reusing {out} (same command and code)")
    else:
        for earlier in (out / STAMP, log):  # a failed run leaves neither behind
            earlier.unlink(missing_ok=True)
        r = mpirun_mpisph([case, *args, "--out", out], ranks=ranks, accept=(0, 3))
        log.write_text(r.stdout + r.stderr)
        stopped = stopped_by_signal(r.stdout)
        if stopped:  # not finished: no stamp, so that --reuse does not read it as a finished run
            raise SystemExit(f"{case} {' '.join(map(str, args))}: {stopped}")
        if stamp["code"] is not None:
            (out / STAMP).write_text(json.dumps(stamp))
    text = log.read_text()
    blow_up = re.search(r"^mpisph: (blow-up .*)$", text, re.M)
    if blow_up is None:
        wall = float(re.search(r"timing: wall ([0-9.]+) s", text).group(1))
        rate = float(re.search(r"throughput: ([0-9.e+]+) particle-steps/s/core", text).group(1))
        return out, shown, wall, rate, None
    last = re.findall(r"wall +([0-9.]+) s .* ([0-9.e+]+) particle-steps/s", text)[-1]
    return out, shown, float(last[0]), float(last[1]) / ranks, blow_up.group(1)


# other settings of each case: 3D UTVF's options (stabilisers/transport_velocity.py) and 000_'s
# stress diffusion, Feng et al.'s geostatic form (physics/drucker_prager.py):
# {case: {run name suffix: (label, arguments)}}
KEPT = "utvf_edge_neighbours=kept"
OUTERMOST = "utvf_near_surface_normal=outermost"
GEOSTATIC = "stress_diffusion=geostatic"
_GEOSTATIC_VARIANTS = {
    "geostatic_diffusion": ("000_: Feng's stress diffusion, UTVF as printed", ["--set", GEOSTATIC]),
    "geostatic_edge_neighbours_kept": ("Feng's stress diffusion, UTVF edge neighbours kept", ["--set", GEOSTATIC, KEPT]),
    "geostatic_outermost_normals": ("Feng's stress diffusion, UTVF edge neighbours kept, near-surface normals from "
                                    "the outermost particles", ["--set", GEOSTATIC, KEPT, OUTERMOST]),
}
VARIANTS = {
    "cube_failure_3d": {"outermost_normals": ("UTVF edge neighbours kept, near-surface normals from the outermost "
                                              "particles", ["--set", KEPT, OUTERMOST]), **_GEOSTATIC_VARIANTS},
    "flume_3d": _GEOSTATIC_VARIANTS,
}
DEFAULT_LABEL = "the defaults: linear stress diffusion, UTVF as printed (Eq. 37)"


def variant_runs(case, ranks, reuse, times):
    """Each variant's run of ``case``: {suffix: (output directory, command, blow-up message or None,
    ``instability_rows`` at ``times``, particle-steps/s/core)}."""
    runs = {}
    for suffix, (_, args) in VARIANTS[case].items():
        out, cmd, _, rate, blow_up = run(case, args, ranks, reuse, name=f"{case}_{suffix}")
        runs[suffix] = out, cmd, blow_up, instability_rows(out, times), rate
    return runs


def variants_table(case, rows, rate, runs):
    """``instability_table`` of the default's ``rows`` (its run at ``rate`` particle-steps/s/core)
    and the variants' ``runs`` of ``case``, each label with its throughput."""
    return instability_table({f"{DEFAULT_LABEL} ({rate:.3g} particle-steps/s/core)": rows,
                              **{f"{VARIANTS[case][s][0]} ({r[4]:.3g})": r[3] for s, r in runs.items()}})


def clustered_at(out, times):
    """``clustered_summary`` of the frames of ``out`` nearest ``times``, joined by '; '."""
    return "; ".join(clustered_summary(f) for f in render.frames_at(out, times))


def stopped(blow_up):
    """' (which stopped: ...)' for a run that blew up, else ''."""
    return f" (which stopped: {blow_up})" if blow_up else ""


def instability_rows(out, times):
    """(t, clustering, inner voids, smallest spacing / dp) at the frames nearest ``times``."""
    rows = []
    for f in render.frames_at(out, times):
        m = tensile_instability(f)
        rows.append((f["t"], m["clustering"], m["inner_voids"], m["min_spacing"]))
    return rows


def instability_table(variants):
    """A row per variant ({label: rows of ``instability_rows``}) and time."""
    lines = ["| run | t [s] | clustering | inner voids | smallest spacing / dp |", "|---|---|---|---|---|"]
    return lines + [f"| {label} | {t:.2f} | {100 * c:.3f} % | {100 * v:.3f} % | {s:.2f} |"
                    for label, rows in variants.items() for t, c, v, s in rows]


def clustered_summary(frame):
    """What the clustered particles of ``frame`` are: by free-surface class, and how many in tension."""
    i, _ = pairing.clustered_pairs(frame, walls=True)
    counts = np.bincount(frame["surface"][i], minlength=len(CLASSES))
    return (f"at t = {frame['t']:.1f} s, {len(i)} clustered: "
            + ", ".join(f"{c} {name}" for name, c in zip(CLASSES, counts))
            + f"; {int(np.sum(frame['p'][i] < 0))} in tension, {int(np.sum(beside_an_edge(frame)[i]))} beside an edge")


def edge_share(frame):
    """The free-surface particles that Eq. 37 shifts and the kept option does not, over all it shifts."""
    return f"{int(np.sum(beside_an_edge(frame)))} of {int(np.sum(shifted_on_the_surface(frame)))}"


# the horizontal axis of the cube's vertical diagonal plane, our plane ABC
ABC = np.array([1.0, 1.0, 0.0]) / np.sqrt(2.0)


def strain_by_height(frame, axis=None):
    """The accumulated plastic strain of the moving particles of ``frame`` in five bands of height
    (bottom first, each a fifth of the highest particle's height), and its largest value: of the
    particles within dp/2 of the vertical plane through the origin along the horizontal ``axis``,
    or of all."""
    moving = frame["kind"] == MOVING
    x, strain = frame["x"][moving], frame["plastic_strain"][moving]
    if axis is not None:
        _, _, dist = render.plane_coordinates(x, (0.0, 0.0, 0.0), axis, (0.0, 0.0, 1.0))
        near = dist < 0.5 * float(frame["params"]["dp"])
        x, strain = x[near], strain[near]
    band = np.minimum((5.0 * x[:, 2] / x[:, 2].max()).astype(int), 4)
    return [strain[band == k] for k in range(5)], float(strain.max())


def cube_failure_3d(ranks, reuse):
    out, cmd, wall, rate, blow_up = run("cube_failure_3d", [], ranks, reuse)
    rows = instability_rows(out, (0.5, 1.0))
    variants = variant_runs("cube_failure_3d", ranks, reuse, (0.5, 1.0))
    snap = render.snapshots_png(out, (0.0, 0.5, 1.0), IMG / "cube_failure_3d_speed.png", view=(25.0, -50.0),
                                title="cube_failure_3d: speed")
    cut = render.slice_png(out, (0.5, 1.0), IMG / "cube_failure_3d_abc.png", (0.0, 0.0, 0.0), ABC,
                           (0.0, 0.0, 1.0), field="plastic_strain", label="accumulated deviatoric plastic strain",
                           title="cube_failure_3d: the diagonal plane ABC")
    bands = []
    for f in render.frames_at(out, (0.5, 1.0)):
        fifths, largest = strain_by_height(f, ABC)
        bands.append(f"t = {f['t']:.1f} s: {fifths[-1].mean():.2f} in the top fifth of the cut, "
                     f"{fifths[0].mean():.2f} in the bottom fifth, {largest:.2f} at most")
    misses = [f"cube_failure_3d: clustering {100 * c:.3f} % at t = {t:.2f} s (at most 0.1 %)"
              for t, c, _, _ in rows if c > 0.001] + ([f"cube_failure_3d: {blow_up}"] if blow_up else [])
    n = len(read_frame(list_frames(out)[0])["x"])
    text = [
        "## The 3D cohesive cube (000_ Sec. 5.3, Figs. 22-24)",
        "",
        f"`{cmd}`: {n} particles, dp = 0.04 m, UTVF and the linear stress diffusion, to t = 1 s: **wall time {wall:.0f} s, "
        f"{rate:.3g} particle-steps/s/core**." + (f" **The run stopped: {blow_up}.**" if blow_up else ""),
        "",
        *variants_table("cube_failure_3d", rows, rate, variants),
        "",
        "As printed, Eq. 37 moves a perfect 3D lattice's face particles towards its edges, where they crowd "
        f"against the unshifted edge particles. `{KEPT}` leaves the free-surface particles within h of an edge "
        f"or corner (div r < 0.6 d) unshifted; `{OUTERMOST}` also projects a near-surface particle's shift on "
        "the mean normal of the outermost particles within h, which on a disordered surface is the surface's "
        "normal where its own is not (mpisph/stabilisers/transport_velocity.py). The default stress diffusion "
        f"takes each stress component less its local linear part; `{GEOSTATIC}` is 000_'s (Feng et al.'s), "
        "the default until session 26 (mpisph/physics/drucker_prager.py). The rows' commands: "
        + "; ".join(f"{VARIANTS['cube_failure_3d'][s][0]}: `{c}`{stopped(b)}" for s, (_, c, b, _, _) in variants.items())
        + ". The clustered particles (scripts/clustered.py), with the defaults: " + clustered_at(out, (0.5, 1.0))
        + "".join(f"; {VARIANTS['cube_failure_3d'][s][0]}: " + clustered_at(o, (0.5, 1.0))
                  for s, (o, _, _, _, _) in variants.items()) + ".",
        "",
        f"![speed]({Path(snap).relative_to(DOCS)})",
        "",
        "The plane ABC: the paper draws it in Fig. 22; we take the vertical plane through the cube's "
        "diagonal (through two opposite vertical edges), the particles within dp/2 of it. 000_ Fig. 24 shows the "
        "shear band start at the top of the column and run down to its foot between 0.5 s and 1 s (the next section "
        "tries other initial stresses). The mean "
        "accumulated deviatoric plastic strain in the cut: " + "; ".join(bands) + ".",
        "",
        f"![plane ABC]({Path(cut).relative_to(DOCS)})",
    ]
    return text, misses


def outside_the_flume(frame, dp):
    """Moving particles more than dp/2 behind a side wall (y outside [0, W]) or below the floor (the
    slope's plane through the foot for x < 0, z = 0 beyond), in the shipped geometry."""
    x = frame["x"][frame["kind"] == MOVING]
    _, _, up = flume.slope_axes()
    floor = np.where(x[:, 0] > 0, x[:, 2], x @ up)
    return int(np.sum((x[:, 1] < -0.5 * dp) | (x[:, 1] > flume.WIDTH + 0.5 * dp) | (floor < -0.5 * dp)))


def max_speeds(out):
    """(t, largest speed of a moving particle) over the frames."""
    t, v = [], []
    for path in list_frames(out):
        f = read_frame(path)
        t.append(f["t"])
        v.append(measure.max_speed(f))
    return np.array(t), np.array(v)


def at_the_end(out):
    """The largest speed of the last frame of ``out`` over its largest over the frames."""
    return measure.final_over_peak(max_speeds(out)[1])


def flume_3d(ranks, reuse):
    out, cmd, wall, rate, blow_up = run("flume_3d", [], ranks, reuse)
    d = read_diagnostics(out / "diagnostics.csv")
    # the approach speed and depth, alpha and the force: the run's diagnostics (mpisph/barrier_load.py)
    v, top = d["approach_speed_barrier"], d["approach_depth_barrier"]
    first = read_frame(list_frames(out)[0], walls=True)
    params = first["params"]
    t_frames, speed = max_speeds(out)
    at_rest = measure.final_over_peak(speed)
    moving = d["kinetic_energy"] > 0.01 * d["kinetic_energy"].max()
    imbalance = float(d["imbalance"][moving].max())
    force = d["force_barrier_x"]
    arriving = np.nan_to_num(v) >= 0.1 * np.nanmax(v)  # alpha describes the impact, not the deposit at rest
    alpha = np.where(arriving, d["alpha_barrier"], np.nan)
    peak = int(np.argmax(force))
    # the engineering coefficient: the peak force over the largest momentum flux of the approaching
    # flow at the gauge before it (rho v^2 h w at its maximum)
    flux = np.nan_to_num(float(params["rho0"]) * v**2 * top * 1.0)
    before = int(np.argmax(flux[:peak + 1]))
    alpha_peak = force[peak] / flux[before] if flux[before] > 0 else float("nan")
    rows = instability_rows(out, (1.0, 2.0, 4.0))
    variants = variant_runs("flume_3d", ranks, reuse, (1.0, 2.0, 4.0))
    kept_at_1, = render.frames_at(variants["geostatic_edge_neighbours_kept"][0], (1.0,))
    # the cube's run of the same variant (cube_failure_3d's section makes it; here it is made if missing)
    cube_kept = "geostatic_edge_neighbours_kept"
    cube_out, *_ = run("cube_failure_3d", VARIANTS["cube_failure_3d"][cube_kept][1], ranks, True,
                       name=f"cube_failure_3d_{cube_kept}")
    cube_kept_at_1, = render.frames_at(cube_out, (1.0,))
    snap = render.snapshots_png(out, (0.0, 1.0, 2.0, 4.0), IMG / "flume_3d_speed.png", view=(30.0, -65.0),
                                title="flume_3d: speed")
    fig, ax = plt.subplots(1, 3, figsize=(15, 4))
    ax[0].plot(d["t"], force / 1e3, label="F_x")
    ax[0].plot(d["t"], d["force_barrier_z"] / 1e3, label="F_z")
    ax[0].set_xlabel("t [s]")
    ax[0].set_ylabel("force of the soil on the barrier [kN]")
    ax[0].legend()
    ax[1].plot(d["t"], alpha, ".")
    ax[1].set_xlabel("t [s]")
    ax[1].set_ylabel("alpha = F / (rho v^2 h w)")
    ax[1].set_yscale("log")
    ax[2].plot(t_frames, speed)
    ax[2].set_xlabel("t [s]")
    ax[2].set_ylabel("largest speed [m/s]")
    ax[2].set_yscale("log")
    fig.tight_layout()
    fig.savefig(IMG / "flume_3d_barrier.png", dpi=90)
    misses = [f"flume_3d: clustering {100 * c:.3f} % at t = {t:.2f} s (at most 0.1 %)" for t, c, _, _ in rows if c > 0.001]
    if at_rest >= 0.01:
        misses.append(f"flume_3d: largest speed at the end {at_rest:.3g} of its peak (below 0.01 is at rest)")
    if imbalance >= 0.15:
        misses.append(f"flume_3d: imbalance {100 * imbalance:.1f} % while the mass moves (under 15 %)")
    if blow_up:
        misses.append(f"flume_3d: {blow_up}")
    leaked = outside_the_flume(read_frame(list_frames(out)[-1]), float(params["dp"]))
    n = int(d["n"][0])
    text = [
        "## The flume (000_ Sec. 5.4, Fig. 25)",
        "",
        f"`{cmd}`: {n} soil particles and {len(first['x']) - n} wall particles, dp = 0.04 m, UTVF and the linear stress diffusion, to t = 4 s: "
        f"**wall time {wall:.0f} s, {rate:.3g} particle-steps/s/core**. Geometry: docs/FLUME.md. The density by kernel "
        "summation (the case's default since session 21; docs/FLUME.md has the run with 000_'s Eq. 16 beside it).",
        "",
        *([f"**The run stopped at t = {d['t'][-1]:.2f} s: {blow_up}.** The figures below are up to that "
           f"time. Soil particles more than dp/2 behind a side wall or the floor at the end: {leaked}: "
           "they squeeze through the dummy walls where the flow turns at the foot of the slope and "
           "meets the barrier, and one finally left the domain.", ""] if blow_up else
          [f"Soil particles more than dp/2 behind a side wall or the floor at the end: {leaked}.", ""]),
        f"- Peak force on the barrier: **{force[peak] / 1e3:.2f} kN** (x) at t = {d['t'][peak]:.2f} s. The "
        f"approaching flow's largest momentum flux at the gauge before it, rho v^2 h w = {flux[before] / 1e3:.2f} kN "
        f"at t = {d['t'][before]:.2f} s (v = {v[before]:.2f} m/s, h = {top[before]:.2f} m), gives **alpha = "
        f"{alpha_peak:.2f}** (peak force over approach flux).",
        f"- At rest: the largest speed at t = {t_frames[-1]:.1f} s is {speed[-1]:.3g} m/s, "
        f"{at_rest:.2g} of its peak {speed.max():.3g} m/s (criterion: below 0.01).",
        f"- The deposit's force on the barrier at the end: {force[-1] / 1e3:.2f} kN (docs/FLUME.md sets it "
        "beside the classical earth pressures, scripts/deposit_stress.py).",
        f"- Load balance while the mass moves (kinetic energy above 1 % of its peak): largest imbalance "
        f"{100 * imbalance:.1f} %, {int(d['rebalances'][-1])} rebalances.",
        "- alpha uses the depth-averaged speed on the approach gauge (0.4 m upstream of the barrier, "
        "its points inside the soil) and the flow depth there (gauge approach_top), rho = rho0, w = 1 m; "
        "it is drawn while that speed is at least a tenth of its peak (the impact, not the deposit at rest).",
        "",
        *variants_table("flume_3d", rows, rate, variants),
        "",
        "The other rows (docs/FLUME.md): "
        + "; ".join(f"{VARIANTS['flume_3d'][s][0]} (`{c}`{stopped(b)}): largest speed at the end "
                    f"{at_the_end(o):.2g} of its peak; "
                    + clustered_summary(render.frames_at(o, (1.0,))[0]) for s, (o, c, b, _, _) in variants.items())
        + "; with the defaults " + clustered_summary(render.frames_at(out, (1.0,))[0]) + ". Beside an edge: the "
        "free-surface particles that Eq. 37 shifts and the kept option leaves in place, " + edge_share(kept_at_1)
        + " on the flowing layer at 1 s (on the cube at 1 s: " + edge_share(cube_kept_at_1) + "): the option "
        "leaves much of the rough free surface of the thin flow unregularised.",
        "",
        f"![speed]({Path(snap).relative_to(DOCS)})",
        "",
        "![barrier](img/flume_3d_barrier.png)",
    ]
    return text, misses


# the initial stresses the band's start is tried with (physics/drucker_prager.py's geostatic_stress)
STARTS = {"geostatic": "geostatic, at rest (the default)", "none": "none, loaded by gravity at t = 0",
          "inverted": "inverted, as the authors' SPHinXsys soil cases start"}
EARLY = (0.1, 0.2, 0.3, 0.5)  # the times the band's start is followed at [s]


def soil_of(params):
    """The Drucker-Prager soil of the run ``params`` (a frame's, by name)."""
    return drucker_prager(SimpleNamespace(**params))


def yield_depth(params, lateral):
    """The depth below a level top at which a column at rest, sigma_v = -rho0 g z and the lateral
    principal stresses ``lateral`` times sigma_v, reaches the Drucker-Prager surface alpha_phi I1 +
    sqrt(J2) = k_c (return_mapping's) of the soil of the run ``params``."""
    soil = soil_of(params)
    s = np.array([*lateral, 1.0])  # principal stresses over sigma_v
    sqrt_j2 = np.sqrt(((s[0] - s[1]) ** 2 + (s[1] - s[2]) ** 2 + (s[2] - s[0]) ** 2) / 6.0)
    return soil.k_c / ((sqrt_j2 - soil.alpha_phi * s.sum()) * soil.rho0 * params["g"])


def cube_band_start(ranks, reuse):
    """Where the cube's plastic strain starts, with each initial stress of ``STARTS``, at dp = 0.08 m:
    a row per start and time, the share of yielded particles (plastic strain > 0.01) in each fifth of
    the height, over the whole cube and over the plane ABC."""
    rows, cmds, top_first, first, params, outs = [], [], [], [], None, {}
    for start, label in STARTS.items():
        args = ["--set", "dp=0.08", f"initial_stress={start}", "--t-end", str(EARLY[-1]), "--output-interval", "0.05"]
        out, cmd, _, _, blow_up = run("cube_failure_3d", args, ranks, reuse, name=f"cube_band_start_{start}")
        cmds.append(f"`{cmd}`{stopped(blow_up)}")
        outs[start] = out
        for k, f in enumerate(render.frames_at(out, EARLY)):
            params = f["params"]
            shares = [[np.mean(b > 0.01) for b in strain_by_height(f, axis)[0]] for axis in (None, ABC)]
            rows.append(f"| {label} | {f['t']:.2f} | " + " | ".join(" / ".join(f"{v:.2f}" for v in s) for s in shares)
                        + " |")
            if shares[0][-1] > shares[0][0] and label not in top_first:
                top_first.append(label)
            if k == 0:
                first.append(f"{start} {shares[0][0]:.2f} / {shares[0][-1]:.2f}")
    cut = render.slice_grid_png(outs, EARLY, IMG / "cube_band_start_abc.png", (0.0, 0.0, 0.0), ABC, (0.0, 0.0, 1.0),
                                title="cube_failure_3d, dp = 0.08 m: accumulated deviatoric plastic strain on the "
                                      "plane ABC, each panel coloured to its own 99th percentile", each=True)
    face, edge = yield_depth(params, (0.0, soil_of(params).k0)), yield_depth(params, (0.0, 0.0))
    mechanics = (f"At rest the soil meets the Drucker-Prager surface (alpha_phi I1 + sqrt(J2) = k_c) on a free face, "
                 f"where the stress across the face is zero and the one along it (1 - sin phi) sigma_v, below "
                 f"{face:.2f} m from the top. On a vertical edge, both lateral stresses zero, it does so below "
                 f"{edge:.2f} m (scripts/production.py's yield_depth). Of a {params['edge']:g} m cube the foot "
                 "yields first and the top last wherever the lateral stress relaxes: near the top the stress "
                 "vanishes and alpha_phi I1 + sqrt(J2) - k_c tends to -k_c, so the top yields first only "
                 "under a tension.")
    verdict = (f"At t = {EARLY[0]} s, the bottom fifth's share over the top fifth's, whole cube: " + "; ".join(first)
               + ". " + ("With no start does the top fifth yield before the bottom fifth: the band's start at the "
                         "foot is not the initial stress's doing." if not top_first else
                         "The top fifth yields before the bottom fifth with: " + "; ".join(top_first) + "."))
    text = [
        "## Where the cube's plastic strain starts (000_ Fig. 24)",
        "",
        "000_ Fig. 24 shows the shear band on the plane ABC start at the top of the cube and run down to its foot; "
        "in the runs above it starts at the foot. 000_ does not print the initial stress. The default is at "
        "rest: sigma_v = -rho0 g depth, sigma_h = (1 - sin phi) sigma_v. The authors' SPHinXsys soil cases "
        "start from sigma_yy = -rho0 g y, zero at the floor and largest at the top (for example "
        "tests/2d_examples/test_2d_cohesive_soil_failure), so the cube is run from that start, from no stress "
        "at all, and from the default, at dp = 0.08 m (15 625 particles): "
        + "; ".join(cmds) + ". A row per start and time: the share of particles whose accumulated "
        "plastic strain exceeds 0.01, in each fifth of the height from the floor up (bottom / ... / top), over "
        "the whole cube and over the plane ABC (within dp/2 of it).",
        "",
        "| initial stress | t [s] | whole cube, bottom to top | plane ABC, bottom to top |",
        "|---|---|---|---|",
        *rows,
        "",
        verdict,
        "",
        "The plane ABC at those times (a row per start), each panel coloured up to its own 99th percentile "
        "of the strain, so that where the strain starts shows while it is still small:",
        "",
        f"![plane ABC, each start]({Path(cut).relative_to(DOCS)})",
        "",
        mechanics,
    ]
    return text, []


RUNNERS = {"cube_failure_3d": cube_failure_3d, "cube_band_start": cube_band_start, "flume_3d": flume_3d}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--only", nargs="+", choices=list(RUNNERS), help="these sections (default: all)")
    ap.add_argument("--reuse", action="store_true",
                    help="measure the runs in runs/production/ of the same command, rank count and committed "
                         "code (their stamp), run the others")
    a = ap.parse_args()
    IMG.mkdir(parents=True, exist_ok=True)
    RUNS.mkdir(parents=True, exist_ok=True)
    kept = page.existing_sections(PAGE)
    misses = []
    for name, runner in RUNNERS.items():
        if a.only and name not in a.only:
            continue
        text, missed = runner(a.ranks, a.reuse)
        kept[name] = page.MARK.format(name) + "\n" + "\n".join(text) + "\n"
        misses += missed
    head = ["# The 3D cases at the paper's spacing", "",
            f"Written by `scripts/production.py` ({a.ranks} ranks; `--only NAME` re-runs one and keeps the other "
            "sections and the text above them). The pictures are drawn off-screen by `mpisph/render.py`.", ""]
    kept_head = page.existing_head(PAGE) if a.only else None
    page.write(PAGE, kept, RUNNERS, head=kept_head or "\n".join(head) + "\n")
    if misses:
        raise SystemExit("missed:\n" + "\n".join(misses))


if __name__ == "__main__":
    main()
