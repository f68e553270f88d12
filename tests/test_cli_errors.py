"""Every bad input stops with one line on stderr, a non-zero exit, no traceback,
and leaves existing output alone."""

import os
import shutil
import subprocess
import sys
from types import SimpleNamespace

import pytest

from mpirun import mpisph, stderr_lines

from mpisph.__main__ import main as mpisph_main
from mpisph.arguments import with_times
from mpisph.io.frames import list_frames, read_frame
from mpisph.launch import ROOT

TINY = ["--set", "dp=0.2", "--t-end", "0.0004", "--output-interval", "0.0002", "--quiet"]


def assert_clean_error(result, *fragments):
    lines = stderr_lines(result.stderr)
    assert result.returncode != 0
    assert "Traceback" not in result.stderr
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith("mpisph: error: "), lines[0]
    for f in fragments:
        assert f in lines[0], lines[0]


@pytest.fixture
def existing_output(tmp_path):
    """An output directory with a file in it that no bad run may touch."""
    out = tmp_path / "out"
    out.mkdir()
    marker = out / "frame_00000.hdf"
    marker.write_bytes(b"earlier result")
    return out, marker


@pytest.mark.parametrize("args, fragments", [
    (["no_such_case"], ["unknown case 'no_such_case'"]),
    (["elliptical_drp"], ["did you mean 'elliptical_drop'"]),
    (["elliptical_drop", "--set", "radiuss=2"], ["unknown parameter 'radiuss'", "did you mean 'radius'"]),
    (["lube_collapse_2d", "--set", "mu_s=0.38"],
     ["did you mean 'mu_s_deg' (in degrees: a friction coefficient 0.38 is 20.81)?"]),
    (["elliptical_drop", "--set", "dp=fine"], ["dp takes a number", "'fine'"]),
    (["taylor_green", "--set", "nx=2.5"], ["nx takes a whole number"]),
    (["elliptical_drop", "--set", "dp=-0.01"], ["dp must be positive"]),
    (["elliptical_drop", "--set", "dp=0"], ["dp must be positive"]),
    (["elliptical_drop", "--t-end", "0"], ["t_end must be positive"]),
    (["elliptical_drop", "--t-end", "-1"], ["t_end must be positive"]),
    (["elliptical_drop", "--set", "dp=3"], ["larger than the drop"]),
    (["dam_break_2d", "--set", "dp=5"], ["larger than the water column"]),
    (["elliptical_drop", "--set", "dp"], ["NAME=VALUE"]),
    (["dam_break_2d", "--set", "dp=1e-12"], ["fills the water column with 2e+24 particles", "GB to run",
                                             "GB available"]),
    (["flume_3d", "--set", "dp=1e-12"], ["the case has about", "particles", "GB to run", "GB available"]),
    (["cube_failure_3d", "--set", "dp=1e-12"], ["the case has about 8e+36 particles", "GB to run",
                                                 "GB available"]),
    (["vertical_cut", "--set", "stabiliser=adaptive_kernel", "density_reinit=inner"],
     ["adaptive_kernel needs density_reinit=none, not 'inner'", "4.3 % above rho0 in 2D"]),
])
def test_bad_parameters(args, fragments, existing_output):
    out, marker = existing_output
    result = mpisph(args + ["--out", out, "--quiet"], timeout=120)
    assert_clean_error(result, *fragments)
    assert marker.read_bytes() == b"earlier result"
    assert sorted(os.listdir(out)) == [marker.name]


def in_process(argv, capsys):
    """``python -m mpisph argv`` run in this process (mpisph.__main__.main): its status and
    (stdout, stderr). For input refused before any rank works, where mpirun would add only its start."""
    status = mpisph_main([str(a) for a in argv])
    out = capsys.readouterr()
    return SimpleNamespace(returncode=status, stdout=out.out, stderr=out.err)


@pytest.mark.parametrize("args, fragments", [
    (["inclined_plane", "--set", "theta=95"], ["theta must lie in [0, 90), not 95.0"]),
    (["inclined_plane", "--set", "columns=4"], ["periodic axis x is 0.02 m, 4 dp long, shorter than twice the "
                                               "kernel support, 0.026 m = 5.2 dp"]),
    (["lube_collapse_2d", "--set", "mu_s_deg=0"], ["tau_0 = 0 takes mu_s phi_max rho_s0 g H_0, which mu_s_deg = 0"]),
    (["vertical_cut", "--set", "nu=0.5"], ["nu must lie in [0, 0.5), not 0.5"]),
    (["oscillating_beam", "--set", "nu=0.7"], ["nu must lie in [0, 0.5), not 0.7"]),
    (["vertical_cut", "--set", "phi=95"], ["phi must lie in [0, 90), not 95.0"]),
    (["vertical_cut", "--set", "phi=nan"], ["phi must be a finite number, not nan"]),
    (["vertical_cut", "--set", "cohesion=-1"], ["cohesion must lie in [0, inf), not -1.0"]),
    (["vertical_cut", "--set", "psi=30"], ["dilatancy angle psi (30 deg) must not exceed the friction angle phi (20 deg)"]),
    (["elliptical_drop", "--set", "radius=inf"], ["radius must be a finite number, not inf"]),
    (["elliptical_drop", "--t-end", "inf"], ["t_end must be a finite number, not inf"]),
    (["elliptical_drop", "--set", "max_time_step=-1"], ["max_time_step must lie in [0, inf), not -1.0"]),
    (["lube_collapse_2d", "--set", "mu_s_deg=95"], ["mu_s_deg must lie in [0, 90), not 95.0"]),
    (["elliptical_drop", "--set", "h_factor=0.1"], ["h_factor must lie in [1, 3), not 0.1"]),
    (["vertical_cut", "--set", "h_factor=100"], ["h_factor must lie in [1, 3), not 100.0"]),
    (["elliptical_drop", "--set", "dp=0.3", "dp=0.2"], ["--set gives dp twice, '0.3' and '0.2': keep one"]),
    (["elliptical_drop", "--set", "t_end=0.5", "--t-end", "0.4"], ["--t-end 0.4 and --set t_end=0.5 disagree"]),
    (["elliptical_drop", "--set", "output_interval=fine", "--output-interval", "0.4"],
     ["--output-interval 0.4 and --set output_interval=fine disagree"]),
    (["ELLIPTICAL_DROP"], ["unknown case 'ELLIPTICAL_DROP'; did you mean 'elliptical_drop'?"]),
    (["oscillating_beam", "--set", "h_over_dp=10"], ["unknown parameter 'h_over_dp'", "did you mean 'H_over_dp'?"]),
])
def test_parameters_out_of_their_bounds(args, fragments, existing_output, capsys):
    out, marker = existing_output
    assert_clean_error(in_process(args + ["--out", out, "--quiet"], capsys), *fragments)
    assert sorted(os.listdir(out)) == [marker.name] and marker.read_bytes() == b"earlier result"


def test_body_outside_domain(tmp_path):
    """A case whose body sticks out of its domain is refused before the run."""
    case = tmp_path / "cases"
    case.mkdir()
    src = open(os.path.join(os.path.dirname(__file__), "..", "cases", "elliptical_drop.py")).read()
    (case / "drop_outside.py").write_text(src.replace('disk((0.0, 0.0)', 'disk((2.4, 0.0)'))
    result = mpisph([case / "drop_outside.py", "--quiet", "--out", tmp_path / "o"], timeout=120)
    assert_clean_error(result, "lies outside the domain")
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("text, fragment", [
    ("PARAMS = {\n", "line 1: '{' was never closed"),
    ("def setup(p):\n    return None\n", "defines no PARAMS (cases/*.py show the form)"),
    ("PARAMS = {}\n", "defines no setup"),
])
def test_a_case_file_that_is_not_a_case(tmp_path, text, fragment, capsys):
    case = tmp_path / "my_case.py"
    case.write_text(text)
    result = in_process([case, "--quiet", "--out", tmp_path / "o"], capsys)
    assert_clean_error(result, f"case file {case}", fragment)
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("args, fragment", [
    (["NOWHERE/my_case.py"], "no case file "),
    (["elliptical_drop", "--out", ""], "--out needs a path, not an empty one"),
    (["elliptical_drop", "--restart", ""], "--restart needs a path, not an empty one"),
])
def test_empty_or_missing_paths(tmp_path, args, fragment, capsys):
    args = [a.replace("NOWHERE", str(tmp_path / "nowhere")) for a in args]
    result = in_process([*args, "--quiet"], capsys)
    assert_clean_error(result, fragment)


@pytest.mark.ranks
def test_more_ranks_than_slabs(existing_output):
    out, marker = existing_output
    # dp = 1 gives a support of 2.6 m in a 5 m domain: two slabs
    result = mpisph(["elliptical_drop", "--set", "dp=1.0", "--out", out, "--quiet"], ranks=3,
                    timeout=120)
    assert_clean_error(result, "3 ranks", "only 2 slabs")
    assert marker.read_bytes() == b"earlier result"


@pytest.mark.ranks
def test_unwritable_output_directory(tmp_path):
    blocker = tmp_path / "a_file"
    blocker.write_text("not a directory")
    result = mpisph(["elliptical_drop", *TINY, "--out", blocker / "out"], ranks=2, timeout=120)
    assert_clean_error(result, "cannot write output directory")


@pytest.fixture(scope="module")
def good_frame(tmp_path_factory):
    out = tmp_path_factory.mktemp("good")
    result = mpisph(["elliptical_drop", *TINY, "--out", out], timeout=300)
    assert result.returncode == 0, result.stderr
    return out / "frame_00001.hdf"


def test_restart_missing_file(tmp_path, existing_output):
    out, marker = existing_output
    result = mpisph(["elliptical_drop", "--restart", tmp_path / "nope.hdf", "--out", out], timeout=120)
    assert_clean_error(result, "no such file")
    assert marker.read_bytes() == b"earlier result"


@pytest.mark.ranks
def test_restart_truncated_file(tmp_path, good_frame, existing_output):
    out, marker = existing_output
    cut = tmp_path / "cut.hdf"
    data = good_frame.read_bytes()
    cut.write_bytes(data[: len(data) // 2])
    result = mpisph(["elliptical_drop", "--restart", cut, "--out", out], ranks=2, timeout=120)
    assert_clean_error(result, "cut.hdf")
    assert marker.read_bytes() == b"earlier result"


def test_restart_foreign_file(tmp_path, existing_output):
    out, marker = existing_output
    foreign = tmp_path / "foreign.hdf"
    foreign.write_text("this is not HDF5")
    result = mpisph(["elliptical_drop", "--restart", foreign, "--out", out], timeout=120)
    assert_clean_error(result, "not an HDF5 file")
    assert marker.read_bytes() == b"earlier result"


def test_restart_frame_of_another_case(good_frame, existing_output):
    out, marker = existing_output
    result = mpisph(["taylor_green", "--restart", good_frame, "--out", out], timeout=120)
    assert_clean_error(result, "written by case 'elliptical_drop'")
    assert marker.read_bytes() == b"earlier result"


@pytest.mark.parametrize("args, fragments", [
    (["--t-end", "0.0002"], ["t_end = 0.0002 s is not after the time of", "0.0002 s: give a later --t-end"]),
    (["--t-end", "0.0001"], ["t_end = 0.0001 s is not after"]),
    (["--set", "dp=0.1"], ["a restart goes on with the particles of", "which --set dp=0.1 would place otherwise"]),
    (["--set", "A0=200", "radius=0.8"], ["which --set A0=200 radius=0.8 would place otherwise"]),
])
def test_restart_that_cannot_go_on_leaves_the_run_alone(tmp_path, good_frame, args, fragments):
    """A restart into the run's own directory with an end time not after the frame's, or with a
    spacing or a body's size that would place other particles, is refused before the frames after it
    are deleted; a parameter that leaves them in place (A0, the drop's initial stretch) is taken."""
    run = tmp_path / "run"
    shutil.copytree(good_frame.parent, run)
    before = {p.name: p.read_bytes() for p in run.iterdir()}
    result = mpisph(["elliptical_drop", "--restart", run / good_frame.name, *args, "--out", run, "--quiet"],
                    timeout=120)
    assert_clean_error(result, *fragments)
    assert {p.name: p.read_bytes() for p in run.iterdir()} == before


@pytest.mark.ranks
def test_blow_up_names_step_time_rank_particle(tmp_path):
    """The drop stretches past the domain edge: the run stops and writes a last frame."""
    out = tmp_path / "blow"
    result = mpisph(["elliptical_drop", "--set", "dp=0.1", "--t-end", "0.04",
                     "--output-interval", "0.01", "--out", out, "--quiet"], ranks=2, timeout=300)
    assert result.returncode == 3
    assert "Traceback" not in result.stderr
    line = result.stderr.strip().splitlines()[-1]
    for word in ("step", "t =", "rank", "particle", "left the domain"):
        assert word in line, line
    frames = sorted(p.name for p in out.glob("frame_*.hdf"))
    assert len(frames) >= 2  # the first frame and the last one at the blow-up
    shutil.rmtree(out)


@pytest.mark.parametrize("old, new, fragments", [
    ('scheme="riemann_fluid"', 'scheme="riemann_granular"', ["scheme riemann_granular takes a DruckerPrager",
                                                              "not Fluid"]),
    ('scheme="riemann_fluid"', 'scheme="sph"', ["scheme must be one of riemann_fluid"]),
    ("stabilisers=p.stabiliser", 'stabilisers="tvf+artificial"',
     ["stabiliser must be none or one of", "'artificial'"]),
    ('scheme="riemann_fluid"', 'scheme="riemann_fluid", integrator="euler"', ["integrator must be one of"]),
    ('scheme_options={"limiter": p.limiter}', 'scheme_options={"limiter": p.limiter, "alpha": 0.1}',
     ["scheme riemann_fluid has no option 'alpha'", "it takes: limiter"]),
])
def test_parts_that_do_not_exist_or_fit(tmp_path, old, new, fragments):
    """A case naming an unknown scheme, stabiliser, integrator or scheme option, or a scheme for
    another material, is refused with one line."""
    src = open(os.path.join(os.path.dirname(__file__), "..", "cases", "elliptical_drop.py")).read()
    assert old in src
    (tmp_path / "drop.py").write_text(src.replace(old, new))
    result = mpisph([tmp_path / "drop.py", *TINY, "--out", tmp_path / "o"], timeout=120)
    assert_clean_error(result, *fragments)
    assert not (tmp_path / "o").exists()


def test_unknown_kernel(existing_output):
    out, _ = existing_output
    result = mpisph(["elliptical_drop", "--set", "kernel=gaussian", "--out", out, "--quiet"], timeout=120)
    assert_clean_error(result, "kernel must be one of")


@pytest.mark.ranks
def test_a_case_too_large_for_the_node_is_refused_with_its_count(existing_output, monkeypatch):
    """A case whose lattices fit but whose run would not (memory.check_fits, 2 ranks on this node)."""
    from mpisph import memory
    available = memory.available_bytes()
    # dp for a dam break (a 1 m x 2 m water column, then walls) of 1.5 times what 2 ranks could run here
    count = 1.5 * available / (2 * (memory.BUILD_BYTES_PER_PARTICLE + memory.RUN_BYTES_PER_PARTICLE / 2))
    dp = (2.0 / count) ** 0.5
    out, marker = existing_output
    result = mpisph(["dam_break_2d", "--set", f"dp={dp:.4g}", "--out", out, "--quiet"], ranks=2, timeout=300)
    assert_clean_error(result, "the case has", "on this node's 2 ranks", "GB available")
    assert marker.read_bytes() == b"earlier result"


def test_two_particles_at_the_same_place_are_refused_before_anything_is_written(existing_output, tmp_path):
    """Every pair sum divides by the pair's distance: a drop with one particle twice is refused at
    its first configuration, naming both, instead of a ZeroDivisionError from a kernel (or, as
    before, a blow-up with a frame written over the directory's earlier results)."""
    src = open(os.path.join(os.path.dirname(__file__), "..", "cases", "elliptical_drop.py")).read()
    old = '    velocity = p.A0 * np.stack'
    assert old in src
    (tmp_path / "drop.py").write_text(src.replace(old, "    x = np.concatenate([x, x[:1]])\n" + old))
    out, marker = existing_output
    result = mpisph([tmp_path / "drop.py", *TINY, "--out", out], timeout=120)
    assert result.returncode == 2
    assert_clean_error(result, "particles 0 of 'drop' and", "start at the same place")
    assert marker.read_bytes() == b"earlier result" and os.listdir(out) == ["frame_00000.hdf"]


@pytest.mark.parametrize("ranks", [1, pytest.param(2, marks=pytest.mark.ranks)])
def test_a_body_reaching_into_a_wall_is_refused_before_anything_is_written(existing_output, tmp_path, ranks):
    """The dam break's water (5 x 10 particles at dp = 0.2) moved 1.5 dp down and left, into the
    tank's floor and side (overlap.py): its bottom row and left column lie behind the walls' surface. It ran on before with those particles
    inside the wall; now it stops with one line naming body and wall, and on 2 ranks the same line."""
    src = open(os.path.join(os.path.dirname(__file__), "..", "cases", "dam_break_2d.py")).read()
    old = '    pressure = p.rho0 * p.g * (H - water[:, 1])'
    assert old in src
    (tmp_path / "sunk.py").write_text(src.replace(old, "    water = water - 1.5 * p.dp\n" + old))
    out, marker = existing_output
    result = mpisph([tmp_path / "sunk.py", *TINY, "--out", out], ranks=ranks, timeout=120)
    # the bottom row and the left column (5 + 10 - 1) lie a spacing behind; the next ones on the surface
    assert_clean_error(result, "14 particles of 'water' start behind the surface of wall 'tank'")
    assert marker.read_bytes() == b"earlier result" and os.listdir(out) == ["frame_00000.hdf"]


@pytest.mark.parametrize("ranks", [1, pytest.param(2, marks=pytest.mark.ranks)])
def test_a_wall_thinner_than_the_kernel_is_warned_of(tmp_path, ranks):
    """The dam break's tank built one layer deep, where the kernel reaches 2.6 dp (overlap.py): each
    of its 52 particles but the two at its bottom corners (whose neighbours lie in front of them,
    dp away along their slanted normals) is on its surface with nothing behind it, and the run says
    so in one line on any rank count, then runs; the case's own tank of 3 layers is not warned of."""
    src = open(os.path.join(os.path.dirname(__file__), "..", "cases", "dam_break_2d.py")).read()
    old = "    layers = support_layers(p.h_factor)\n"
    assert old in src
    (tmp_path / "thin.py").write_text(src.replace(old, "    layers = 1\n"))
    for case, warned in ((tmp_path / "thin.py", True), ("dam_break_2d", False)):
        result = mpisph([case, *TINY, "--out", tmp_path / "out"], ranks=ranks, timeout=120)
        assert result.returncode == 0, result.stderr
        lines = [line for line in stderr_lines(result.stderr) if "dp thick" in line]
        assert lines == (["mpisph: warning: wall 'tank' is 1 dp thick behind 50 of its surface particles, where "
                          "the kernel reaches 2.6 dp: material can pass through it; give it 3 layers (a thicker "
                          "wall or a smaller dp)"] if warned else []), result.stderr


def test_a_wall_outside_the_domain_is_warned_of(tmp_path):
    """docs/examples/slope_2d.py with its domain's left edge moved 0.2 m right, into the back wall 3
    layers deep (dp = 0.1 m): its outer layer, 63 particles 0.15 m out, is warned of, and the run goes
    on; with the example's own domain nothing is."""
    src = open(os.path.join(os.path.dirname(__file__), "..", "docs", "examples", "slope_2d.py")).read()
    old = "        domain=((-margin, -margin), (length + margin, 2.0 * top)),\n"
    assert old in src
    (tmp_path / "cut.py").write_text(src.replace(old, old.replace("(-margin, -margin)", "(-margin + 0.2, -margin)")))
    for case, warned in ((tmp_path / "cut.py", True), (os.path.join(os.path.dirname(__file__), "..", "docs",
                                                                    "examples", "slope_2d.py"), False)):
        result = mpisph([case, "--t-end", "0.001", "--output-interval", "0.001", "--out", tmp_path / "out",
                         "--quiet"], timeout=120)
        assert result.returncode == 0, result.stderr
        lines = [line for line in stderr_lines(result.stderr) if "outside the domain" in line]
        assert lines == (["mpisph: warning: wall 'back': 63 of its particles lie outside the domain (-0.1, -0.3) "
                          "to (8.3, 6), up to 0.15 m, where no material reaches them"] if warned else []), \
            result.stderr


def test_a_run_started_by_its_file_restarts_by_its_name(tmp_path):
    """The frame names a case of cases/ by its name however the run named it (case.case_key), so
    `cases/elliptical_drop.py` (from the repository root) restarts as `elliptical_drop`; a case file
    elsewhere is named by its absolute path."""
    out = tmp_path / "by_path"
    first = mpisph(["cases/elliptical_drop.py", *TINY, "--out", out], timeout=300)
    assert first.returncode == 0, first.stderr
    again = mpisph(["elliptical_drop", "--restart", out / "frame_00001.hdf", "--t-end", "0.0006",
                    "--out", tmp_path / "again", "--quiet"], timeout=300)
    assert again.returncode == 0, again.stderr
    assert read_frame(out / "frame_00001.hdf")["params"]["case"] == "elliptical_drop"
    mine = tmp_path / "my_drop.py"
    shutil.copy(ROOT / "cases" / "elliptical_drop.py", mine)
    own = mpisph([mine, *TINY, "--out", tmp_path / "own"], timeout=300)
    assert own.returncode == 0, own.stderr
    assert read_frame(tmp_path / "own" / "frame_00001.hdf")["params"]["case"] == str(mine)


def test_info_lists_the_arrays_an_option_adds_and_refuses_a_bad_one(capsys):
    """`info CASE --set ...`: the adaptive kernel's frames hold its knots, the default's do not; a bad
    value is one line before the description."""
    def arrays(*sets):
        r = in_process(["info", "vertical_cut", *sets], capsys)
        assert r.returncode == 0, r.stderr
        return {line.split()[0] for line in r.stdout.split("frames hold for each particle", 1)[1].splitlines()[1:]
                if line.strip()}
    assert {"knot", "displacement_gradient"} <= arrays("--set", "stabiliser=adaptive_kernel") - arrays()
    bad = in_process(["info", "vertical_cut", "--set", "stabiliser=bogus"], capsys)
    assert_clean_error(bad, "parameter stabiliser must be one of")
    assert bad.stdout == ""


def test_the_same_value_twice_is_one_value(capsys):
    """A parameter given twice with one value is that value."""
    r = in_process(["info", "elliptical_drop", "--set", "dp=0.05", "dp=0.05"], capsys)
    assert r.returncode == 0, r.stderr


def test_info_names_only_the_density_modes_the_case_offers_and_a_parameters_bounds(capsys):
    """Each case's density_reinit help describes the modes it takes, and no other; a bounded
    parameter's line ends with its bounds."""
    def help_line(case, name="density_reinit"):
        r = in_process(["info", case], capsys)
        assert r.returncode == 0, r.stderr
        return next(line for line in r.stdout.splitlines() if line.split()[:1] == [name])
    taylor_green, drop, incline = help_line("taylor_green"), help_line("elliptical_drop"), help_line("inclined_plane")
    assert "inner, on every particle" in taylor_green and "free_surface," not in taylor_green
    assert "free_surface, not below" in drop and "inner," not in drop
    assert all(f"{mode}," in incline for mode in ("inner", "free_surface", "none"))
    assert help_line("vertical_cut", "h_factor").endswith("(002_ Table 4: h = 1.5 dp) (in [1, 3))")


def test_list_takes_no_argument_and_describes_each_case_by_its_first_paragraph(capsys):
    r = in_process(["list"], capsys)
    assert r.returncode == 0, r.stderr
    cavity = next(line for line in r.stdout.splitlines() if line.startswith("lid_driven_cavity "))
    assert cavity.endswith("(`--set Re=1000 nx=100`).")  # its docstring's first line ends mid-sentence
    assert_clean_error(in_process(["list", "extra"], capsys), "usage: python -m mpisph list")


def test_an_output_interval_below_the_time_step_is_warned_of(tmp_path):
    """The drop at dp = 0.2 steps by about 1e-4 s: a 1e-7 s interval cuts every step to it, and says so."""
    r = mpisph(["elliptical_drop", "--set", "dp=0.2", "--t-end", "3e-7", "--output-interval", "1e-7", "--quiet",
                "--out", tmp_path], timeout=120)
    assert r.returncode == 0, r.stderr
    (line,) = stderr_lines(r.stderr)
    assert line.startswith("mpisph: warning: output_interval = 1e-07 s is shorter than the time step, "), line
    assert "each step ends at a frame and is cut to the interval" in line


@pytest.mark.parametrize("command", [["list"], ["info", "column_collapse_2d"]])
def test_output_into_a_closed_pipe_ends_without_a_traceback(command):
    """`python -m mpisph list | head -1`: the reader is gone before mpisph writes (its start-up takes
    a fraction of a second), so every write meets a closed pipe; mpisph stops with status 1, silently."""
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    proc = subprocess.Popen([sys.executable, "-m", "mpisph", *command], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, cwd=ROOT, env=env)
    proc.stdout.close()
    stderr = proc.stderr.read()
    assert proc.wait(timeout=120) == 1 and stderr == ""


@pytest.mark.parametrize("argv", [["--set", "dp=0.01", "column_collapse_2d"],
                                  ["info", "--set", "dp=0.01", "column_collapse_2d"],
                                  ["compare", "--set", "dp=0.01", "column_collapse_2d", "--stabiliser", "none"]])
def test_a_case_after_set_is_named_not_missing(argv, capsys):
    """--set takes every word up to the next option, the case too: the error says which word."""
    assert_clean_error(in_process(argv, capsys), "--set took 'column_collapse_2d'", "give the case before --set")


def test_info_with_parameters_that_cannot_go_together_prints_only_the_error(capsys):
    """The adaptive kernel on the column's Wendland kernel: one line, and no table before it."""
    r = in_process(["info", "column_collapse_2d", "--set", "stabiliser=adaptive_kernel"], capsys)
    assert_clean_error(r, "set kernel=cubic_spline")
    assert r.stdout == ""


@pytest.mark.parametrize("word, usage", [("list", "python -m mpisph list"),
                                         ("report", "python -m mpisph report FRAME"),
                                         ("plot", "python -m mpisph plot OUT_DIR [PNG]")])
def test_help_of_a_word_command_is_its_usage_not_a_missing_file(word, usage, capsys):
    """`report --help` used to look for a frame named --help."""
    r = in_process([word, "--help"], capsys)
    assert r.returncode == 0 and r.stderr == "" and r.stdout.startswith(f"usage: {usage}")
    assert len(r.stdout.strip().splitlines()) == 3  # the usage, a blank line, what it does


def test_compare_takes_the_times_as_a_run_does(capsys):
    """--t-end and --output-interval are the --set times by another name, in compare as in a run."""
    from mpisph import compare
    a = compare.parse(["elliptical_drop", "--stabiliser", "none", "--t-end", "0.002", "--output-interval", "0.001"])
    assert with_times(compare.set_overrides(a.overrides, "stabiliser"), a) == {"t_end": "0.002",
                                                                                 "output_interval": "0.001"}
    r = in_process(["compare", "elliptical_drop", "--stabiliser", "none", "--set", "t_end=0.1", "--t-end", "0.2"],
                   capsys)
    assert_clean_error(r, "--t-end 0.2 and --set t_end=0.1 disagree")


GAUGED_TANK = os.path.join(os.path.dirname(__file__), "cases", "gauged_tank.py")


@pytest.mark.parametrize("gauge, fragments", [
    ('Gauge("oops", np.array([[0.1, 0.1, 0.1], [0.2, 0.2, 0.2], [0.3, 0.3, 0.3]]))',
     ["gauge 'oops': its points take 2 coordinates each in this 2D case", "shape (3, 3)"]),
    ('SurfaceGauge("tops", np.array([0.1, 0.2]))', ["gauge 'tops': its stations take 1 coordinate each in this 2D case", "shape (2,)"]),
    ('Gauge("typo", np.array([[0.1, 0.1]]), fields=("stres",))', ["gauge 'typo': no particle field 'stres'"]),
    ('Gauge("column", np.array([[0.1, 0.1]]))', ["gauge names 'column' are given twice"]),
])
def test_a_bad_gauge_is_refused_before_anything_is_written(existing_output, tmp_path, gauge, fragments):
    """Points of the wrong dimension were reshaped into other points (or a reshape traceback after
    the first files were written); a field the particles lack stopped only after diagnostics.csv
    was written. Each is now one line, the directory untouched."""
    src = open(GAUGED_TANK).read()
    old = '    case.wall_forces = {"tank": (0.0, 0.0)}'
    assert old in src
    (tmp_path / "bad_gauge.py").write_text(src.replace(old, f"    case.gauges.append({gauge})\n" + old))
    out, marker = existing_output
    result = mpisph([tmp_path / "bad_gauge.py", *TINY, "--out", out], timeout=120)
    assert_clean_error(result, *fragments)
    assert marker.read_bytes() == b"earlier result" and os.listdir(out) == ["frame_00000.hdf"]


def test_info_on_a_frame_lists_what_it_holds(tmp_path, capsys):
    """`info FRAME`: the frame's case, time and particles, the parameters it was run with, and each
    array with its meaning and unit (from its case's fields), where `info` took only a case; a --set
    with a frame is refused, and a frame that is not there is named as such, not as an unknown case."""
    r = mpisph(["elliptical_drop", *TINY, "--out", tmp_path], timeout=120)
    assert r.returncode == 0, r.stderr
    frame = tmp_path / "frame_00001.hdf"
    out = in_process(["info", frame], capsys)
    assert out.returncode == 0 and out.stderr == ""
    lines = out.stdout.splitlines()
    assert lines[0].startswith(f"{frame}: case elliptical_drop, t = 0.0002 s, step ")
    assert lines[0].endswith(" particles (" + lines[0].split("(")[1])  # its moving particles counted
    assert lines[1].startswith("run with: ") and " dp=0.2 " in lines[1] and " t_end=0.0004 " in lines[1]
    rho = next(line for line in lines if line.split()[0] == "rho")
    assert rho.split()[1:3] == ["float64", "scalar"] and rho.endswith("[kg/m^3]")
    assert_clean_error(in_process(["info", frame, "--set", "dp=0.1"], capsys), "info FRAME takes no --set")
    assert_clean_error(in_process(["info", tmp_path / "nope.hdf"], capsys), "nope.hdf: no such file")


def test_a_wall_distance_below_zero_is_refused_before_anything_is_written(existing_output, tmp_path):
    """Wall.distance is a depth behind the wall surface: one written with its sign turned (as a user
    writing the distance of a mesh wall may) ran into a non-positive density some 1900 steps later
    under the Morris walls of mu_i; now the run stops in one line naming the wall."""
    (tmp_path / "signed.py").write_text(
        "import dataclasses\n"
        "from mpisph.case import load_case_module\n"
        "_cut = load_case_module('vertical_cut')\n"
        "PARAMS = _cut.PARAMS\n"
        "def setup(p):\n"
        "    case = _cut.setup(p)\n"
        "    tank = case.walls[0]\n"
        "    case.walls = [dataclasses.replace(tank, distance=lambda x, d=tank.distance: -d(x))]\n"
        "    return case\n")
    out, marker = existing_output
    result = mpisph([tmp_path / "signed.py", *TINY, "--out", out], timeout=120)
    assert_clean_error(result, "wall 'tank': its distance gives -", "Wall.distance is each particle's depth")
    assert marker.read_bytes() == b"earlier result" and os.listdir(out) == ["frame_00000.hdf"]


def test_a_restart_without_its_case_takes_the_frames(tmp_path):
    """`python -m mpisph --restart FRAME`: the frame names its case, so the case may be left out; the
    restart ends with the bits of one that names it."""
    r = mpisph(["elliptical_drop", *TINY, "--out", tmp_path / "run"], timeout=120)
    assert r.returncode == 0, r.stderr
    frame = tmp_path / "run" / "frame_00001.hdf"
    ends = []
    for words, out in (([], "bare"), (["elliptical_drop"], "named")):
        r = mpisph([*words, "--restart", frame, "--t-end", "0.0006", "--out", tmp_path / out, "--quiet"], timeout=120)
        assert r.returncode == 0, r.stderr
        ends.append(read_frame(str(tmp_path / out / "frame_00003.hdf")))
    for name in ("x", "v", "rho", "p"):
        assert ends[0][name].tobytes() == ends[1][name].tobytes(), name


def test_the_closing_lines_phases_fit_in_the_wall_time(tmp_path):
    """The timing line's phase shares add up to at most the wall time: the first configuration
    (configure_start, timed into the phases) lies inside it (they added up to 105-108 %, a 3D
    probe's cube)."""
    import re
    r = mpisph(["dam_break_2d", "--set", "dp=0.2", "--t-end", "0.0004", "--output-interval", "0.0002",
                "--out", tmp_path / "out"], ranks=1, timeout=120)
    assert r.returncode == 0, r.stderr
    [line] = [ln for ln in r.stdout.splitlines() if "timing: wall" in ln]
    shares = [float(v) for v in re.findall(r" (\d+\.\d)%", line)]
    assert len(shares) == 4 and sum(shares) <= 100.2, line


@pytest.mark.parametrize("case, dp", [("dam_break_2d", "0.05"), ("cube_failure_3d", "0.2")])
def test_info_tells_a_runs_size_before_it_runs(tmp_path, capsys, case, dp):
    """`info CASE --set dp=...` gives the particles (walls included) and the size of a frame's
    arrays from the sources' estimates: within 5 % of the particles of a run, and its first frame's
    file is that size to 10 % plus 0.1 MB of HDF5's own (a 3D probe found the size of a fine run
    only once it was built), and the most ranks its slabs allow; `info OUT_DIR` reads the run's
    last frame."""
    import re
    from mpisph.__main__ import cmd_info
    cmd_info(case, {"dp": dp})
    [line] = [ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("size: ")]
    count = float(re.search(r"about (\S+) particles", line).group(1))
    value, unit = re.search(r"([\d.e+-]+) ([MG])B of arrays a frame", line).groups()
    frame_bytes = float(value) * (1e9 if unit == "G" else 1e6)
    out = tmp_path / "out"
    r = mpisph([case, "--set", f"dp={dp}", "--t-end", "1e-6", "--quiet", "--out", out], ranks=1, timeout=300)
    assert r.returncode == 0, r.stderr
    first = list_frames(str(out))[0]
    assert count == pytest.approx(len(read_frame(first, walls=True)["x"]), rel=0.05)
    assert frame_bytes <= os.path.getsize(first) <= 1.1 * frame_bytes + 1e5
    # the most ranks is the count of slabs the run's decomposition refuses more ranks than
    from mpisph.case import build_case, load_case_module, resolve_params
    from mpisph.errors import InputError
    from mpisph.parallel.decomposition import SlabDecomposition
    ranks, support = re.search(r"at most (\d+) ranks \(slabs (\S+) m wide", line).groups()
    module = load_case_module(case)
    built = build_case(module, resolve_params(module, {"dp": dp}))
    lo, hi = (corner[built.slab_axis] for corner in built.domain)
    with pytest.raises(InputError, match=f"use at most {ranks} ranks"):
        SlabDecomposition(SimpleNamespace(size=int(ranks) + 1), built.slab_axis, lo, hi, float(support))
    assert mpisph_main(["info", str(out)]) == 0
    assert capsys.readouterr().out.startswith(f"{list_frames(str(out))[-1]}: case {case}, ")
