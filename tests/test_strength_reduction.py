"""mpisph/strength_reduction.py: the reduced strength, a stage's outcome read from its frames and
diagnostics, the search's order of stages on hand-built runs, and two real stages of a coarse cut."""

import math
import os

import numpy as np
import pytest
from mpi4py import MPI

from mpisph import references, strength_reduction
from mpisph.io.frames import frame_path, list_frames, read_frame, write_frame
from repo_script import load_script

DP = 0.1
SOIL = {"cohesion": 5e3, "phi": 20.0, "psi": 0.0}


def test_the_factor_divides_the_cohesion_and_the_tangents_of_the_angles():
    c, phi, psi = strength_reduction.reduced({"cohesion": 5e3, "phi": 20.0, "psi": 10.0}, 1.25)
    assert c == pytest.approx(4e3, rel=1e-12)
    assert math.tan(math.radians(phi)) == pytest.approx(math.tan(math.radians(20.0)) / 1.25, rel=1e-12)
    assert math.tan(math.radians(psi)) == pytest.approx(math.tan(math.radians(10.0)) / 1.25, rel=1e-12)


def test_a_stage_sets_the_reduced_strength_once_in_place_of_the_cases_own():
    """A strength among the case's --set items is replaced by the reduced one (mpisph refuses a name
    given twice), the other items kept; a restart sets the reduced strength alone."""
    c, phi, psi = strength_reduction.reduced(SOIL, 1.25)
    release = strength_reduction.stage_arguments(SOIL, 1.25, ["H=1.5", "cohesion=5000"], t_end=1.0, interval=0.25)
    assert release == ["--set", "H=1.5", f"cohesion={c!r}", f"phi={phi!r}", f"psi={psi!r}",
                       "--t-end", "1.0", "--output-interval", "0.25"]
    later = strength_reduction.stage_arguments(SOIL, 1.25, ["H=1.5"], restart="f.hdf", t_end=2.0, interval=0.25)
    assert later[:3] == ["--restart", "f.hdf", "--set"] and later[3:6] == release[2:5]


def write_block(directory, index, t, shift):
    """Frame ``index`` at time ``t`` of a 10-layer block (H = 1 m) moved right by ``shift`` [m]."""
    i, j = np.meshgrid(np.arange(10), np.arange(10), indexing="ij")
    x = (np.c_[i.ravel(), j.ravel()] + 0.5) * DP
    n = len(x)
    fields = {"x": x + [shift, 0.0], "gid": np.arange(n, dtype=np.int64), "kind": np.zeros(n, np.int8),
              "v": np.zeros((n, 2)), "rho": np.ones(n), "mass": np.ones(n)}
    write_frame(frame_path(str(directory), index), MPI.COMM_SELF, fields, time=t, step=index, dim=2,
                params={"case": "block", "dp": DP})


def write_diagnostics(directory, times, energies):
    (directory / "diagnostics.csv").write_text("t,step,kinetic_energy\n" + "".join(
        f"{float(t)!r},{k},{float(e)!r}\n" for k, (t, e) in enumerate(zip(times, energies))))


def test_a_stage_that_moves_the_body_beyond_the_slide_share_slid_and_the_release_settles(tmp_path):
    """The release moves the block by 0.01 H over 1 s; a restart of it by nothing, another by 0.03 H
    (beyond SLIDE H in its second), which over a height of 2.5 H stands; their kinetic energy peaks
    0.25 s into each."""
    release, stood, slid = (tmp_path / name for name in ("release", "stood", "slid"))
    for directory, shift in ((release, 0.01), (stood, 0.01), (slid, 0.04)):
        directory.mkdir()
        write_block(directory, 1, 1.0 if directory == release else 2.0, shift)
    write_block(release, 0, 0.0, 0.0)
    write_diagnostics(release, [0.0, 0.25, 0.5, 1.0], [0.0, 5.0, 1.0, 0.5])
    for directory in (stood, slid):
        write_diagnostics(directory, [1.25, 1.5, 2.0], [5.0, 1.0, 0.25])
    first, end = read_frame(list_frames(release)[0]), read_frame(list_frames(release)[-1])
    settled = strength_reduction.stage_outcome(0.9, release, first, first, 1.0, settling=True)
    assert settled.outcome == "settling" and settled.moved == pytest.approx(0.01, abs=1e-12)
    assert (settled.peak_energy, settled.peak_time, settled.end_energy) == (5.0, 0.25, 0.5)
    held = strength_reduction.stage_outcome(1.0, stood, end, first, 1.0)
    assert held.outcome == "stood" and held.moved == pytest.approx(0.0, abs=1e-12)
    assert (held.start, held.end, held.peak_time) == (1.0, 2.0, 0.25)
    gone = strength_reduction.stage_outcome(1.1, slid, end, first, 1.0)
    assert gone.outcome == "slid" and gone.moved == pytest.approx(0.03, abs=1e-12)
    assert gone.since_release == pytest.approx(0.04, abs=1e-12)
    # judged over H = 2.5 m (a slope of its own height, --height), 0.03 m is 0.012 H: it stood
    shorter = strength_reduction.stage_outcome(1.1, slid, end, first, 2.5)
    assert shorter.outcome == "stood" and shorter.moved == pytest.approx(0.012, abs=1e-12)
    rows = strength_reduction.table([settled, held, gone], SOIL)
    assert rows[4].startswith(f"| 1.1 | {5 / 1.1:.3f} |") and rows[4].endswith("| 0.0300 | 0.040 | slid |")


def test_the_slide_share_is_per_second_of_the_stage(tmp_path):
    """A hold of 2 s that creeps 0.02 H (0.01 H a second, the creep of a cut at rest) stands, where
    over a stage of 1 s the same 0.02 H is a slide: the share SLIDE is per second of the stage."""
    release, long, short = (tmp_path / name for name in ("release", "long", "short"))
    for directory, t, shift in ((release, 1.0, 0.0), (long, 3.0, 0.02), (short, 2.0, 0.02)):
        directory.mkdir()
        write_block(directory, 1, t, shift)
        write_diagnostics(directory, [t - 0.5, t], [1.0, 0.5])
    write_block(release, 0, 0.0, 0.0)
    first, end = (read_frame(path) for path in list_frames(release))
    assert strength_reduction.stage_outcome(0.9, long, end, first, 1.0).outcome == "stood"
    assert strength_reduction.stage_outcome(0.9, short, end, first, 1.0).outcome == "slid"


def test_the_release_creep_is_its_second_halfs_displacement_per_second(tmp_path):
    """A release to 2 s whose block moves 0.008 H from 1 s to its end creeps at 0.008 H/s, whatever it
    did before (0.5 H by 0.5 s) or in between (a swing at 1.5 s): under SLIDE H per second."""
    release = tmp_path / "release"
    release.mkdir()
    for index, (t, shift) in enumerate(((0.0, 0.0), (0.5, 0.5), (1.0, 0.6), (1.5, 0.65), (2.0, 0.608))):
        write_block(release, index, t, shift)
    stages = [strength_reduction.Stage(0.6, str(release), 0.0, 2.0, 1.0, 0.1, 0.1, 0.6, 0.6, "settling", 1.0)]
    creep = strength_reduction.release_creep(stages)
    assert creep == pytest.approx(0.008, rel=1e-9)
    assert creep < strength_reduction.SLIDE


def hand_built_launch(tmp_path, safety_factor, launched):
    """A ``launch`` that writes a stage's frames by hand: the block creeps 0.001 H per stage at a
    factor below ``safety_factor`` and slides 0.03 H above it; each stage's factor (from its reduced
    cohesion) and the frame it restarted go into ``launched``."""
    def launch(name, case, arguments):
        directory = tmp_path / name
        directory.mkdir()
        factor = SOIL["cohesion"] / float(next(a for a in arguments if a.startswith("cohesion="))[9:])
        t_end = float(arguments[arguments.index("--t-end") + 1])
        if "--restart" in arguments:
            before = read_frame(arguments[arguments.index("--restart") + 1])
            t0, index, shift = before["t"], 1 + len(launched), before["x"][0, 0] - 0.5 * DP
        else:
            write_block(directory, 0, 0.0, 0.0)
            t0, index, shift, before = 0.0, 1, 0.0, None
        write_block(directory, index, t_end, shift + (0.03 if factor > safety_factor else 0.001))
        write_diagnostics(directory, [t0 + 0.1, t_end], [1.0, 0.5])
        launched.append((round(factor, 9), None if before is None else round(before["t"], 9)))
        return str(directory)
    return launch


def test_the_search_climbs_to_the_first_slide_then_halves_the_bracket_from_the_last_stage_that_stood(tmp_path):
    launched = []
    stages = strength_reduction.search(hand_built_launch(tmp_path, 0.72, launched), "block", ["dp=0.1"], SOIL,
                                       [0.6, 0.65, 0.7, 0.75, 0.8], 2.0, 1.0, bisect=2)
    # 0.8 never runs: the 0.75 stage slid; 0.725 slides, 0.7125 stands; each restarts the last that stood
    assert launched == [(0.6, None), (0.65, 2.0), (0.7, 3.0), (0.75, 4.0), (0.725, 4.0), (0.7125, 4.0)]
    assert [s.outcome for s in stages] == ["settling", "stood", "stood", "slid", "slid", "stood"]
    assert [os.path.basename(s.directory) for s in stages][::5] == ["stage00_F0.6", "stage05_F0.7125"]
    assert strength_reduction.bracket(stages) == (pytest.approx(0.7125, rel=1e-12), 0.725)
    soil = dict(SOIL, rho0=1850.0, g=9.8)
    height = stages[0].height
    assert height == pytest.approx(1.0, rel=1e-12)  # the release's first frame, not the slid block's last
    assert strength_reduction.limit_factors(height, soil) == \
        references.vertical_cut_safety_factor(5e3, 20.0, 1850.0 * 9.8, 1.0, 0.0)
    assert all(s.height == height for s in stages)
    strength_reduction.write_record(str(tmp_path), stages)
    assert strength_reduction.read_record(str(tmp_path)) == stages
    # a record written before the stages held H reads the release's height
    import json
    record = tmp_path / strength_reduction.RECORD
    old = [{k: v for k, v in s.items() if k != "height"} for s in json.loads(record.read_text())]
    record.write_text(json.dumps(old))
    assert strength_reduction.read_record(str(tmp_path)) == stages


def test_a_hold_runs_the_last_factor_that_stood_on_and_a_factor_that_gives_way_counts_as_slid(tmp_path):
    launched = []
    stages = strength_reduction.search(hand_built_launch(tmp_path, 0.72, launched), "block", [], SOIL,
                                       [0.6, 0.7, 0.75], 2.0, 1.0, bisect=1)
    assert strength_reduction.bracket(stages) == (0.7, 0.725)
    kept = strength_reduction.hold(hand_built_launch(tmp_path, 0.72, launched), "block", stages, SOIL, 2.0)
    assert launched[-1] == (0.7, 3.0) and (kept.start, kept.end, kept.outcome) == (3.0, 5.0, "stood")
    assert os.path.basename(kept.directory) == "stage04_F0.7_hold"
    assert strength_reduction.bracket(stages) == (0.7, 0.725)
    # the same factor, held again from the hold, now gives way: the bracket falls to the factor below
    gone = strength_reduction.hold(hand_built_launch(tmp_path, 0.65, launched), "block", stages, SOIL, 1.0)
    assert launched[-1] == (0.7, 5.0) and gone.outcome == "slid"
    assert strength_reduction.bracket(stages) == (0.6, 0.7)
    # the release's factor gives way too: no factor is left to hold
    strength_reduction.hold(hand_built_launch(tmp_path, 0.5, launched), "block", stages, SOIL, 1.0)
    assert strength_reduction.bracket(stages) == (None, 0.6)
    with pytest.raises(ValueError, match="nothing to hold"):
        strength_reduction.hold(hand_built_launch(tmp_path, 0.5, launched), "block", stages, SOIL, 1.0)


def test_with_no_slide_the_bracket_is_open_and_no_stage_bisects(tmp_path):
    launched = []
    stages = strength_reduction.search(hand_built_launch(tmp_path, 2.0, launched), "block", [], SOIL,
                                       [0.8, 0.9], 1.0, 1.0, bisect=3)
    assert len(launched) == 2 and strength_reduction.bracket(stages) == (0.9, None)


def test_each_stage_restarts_the_last_frame_with_its_reduced_strength(tmp_path):
    """A coarse cut in two short stages by mpirun (scripts/strength_reduction.py's launch): the second
    stage's frames carry c / F and atan(tan phi / F) of the case's own strength and start where the
    release ended."""
    launch = load_script("strength_reduction").launcher(str(tmp_path), 1)
    sets = ["dp=0.2", "kernel=wendland_c2", "h_factor=1.3"]
    stages = strength_reduction.search(launch, "vertical_cut", sets, SOIL, [1.0, 1.25], 0.02, 0.02)
    assert [(s.start, s.end) for s in stages] == [(0.0, pytest.approx(0.02)), (pytest.approx(0.02),
                                                                                pytest.approx(0.04))]
    last = read_frame(list_frames(stages[1].directory)[-1])
    assert (last["params"]["cohesion"], last["params"]["phi"], last["params"]["psi"]) == \
        strength_reduction.reduced(SOIL, 1.25)
    assert float(last["params"]["dp"]) == 0.2 and stages[0].outcome == "settling"
    # a report or a hold read from the record must name the case and strength the stages ran with
    strength_reduction.check_record(stages, "vertical_cut", SOIL)
    for case, soil in (("vertical_cut", dict(SOIL, cohesion=2e3)), ("vertical_cut", dict(SOIL, phi=25.0)),
                       ("cohesive_failure_2d", SOIL)):
        with pytest.raises(ValueError, match="name the case and the --set items it ran with"):
            strength_reduction.check_record(stages, case, soil)


def test_the_script_refuses_a_case_without_a_strength_to_reduce(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr("sys.argv", ["strength_reduction.py", "dam_break_2d", "--factors", "0.8", "1.0",
                                     "--out", str(tmp_path / "search")])
    with pytest.raises(SystemExit) as stop:
        load_script("strength_reduction").main()
    assert stop.value.code == 2 and "has no Drucker-Prager strength" in capsys.readouterr().err
    assert not (tmp_path / "search").exists()
