"""The README and docs/ name what exists. Every ``python -m mpisph`` command written there still
parses: its case exists, its options are the command line's, and every ``--set NAME=VALUE`` names a
parameter of that case with a value the parameter takes (compare's stabilisers too); a renamed
parameter or choice would otherwise leave the docs' commands failing on a user's first try. Every
file of scripts/, benchmarks/ and the rest that the docs name exists, and docs/ARCHITECTURE.md
names every module of the package, the scripts and the benchmarks by its file name (a
subpackage's __init__.py aside).

The docs' notation is read as written there: ``[x]`` an optional part, ``A|B`` alternatives (each
checked), an upper-case word (CASE, DIR, T, T/20) a placeholder whose value is not checked, and
``;`` or ``&&`` between two commands."""

import re
import shlex
from pathlib import Path

import pytest

from mpisph import compare
from mpisph.__main__ import _parser
from mpisph.arguments import parse_sets
from mpisph.case import all_params, load_case_module, resolve_params
from mpisph.errors import InputError

ROOT = Path(__file__).resolve().parents[1]
DOCS = [ROOT / "README.md", ROOT / "jobs" / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
SUBCOMMANDS_WITHOUT_CASE = ("list", "report", "plot")
PLACEHOLDER = re.compile(r"^[A-Z][A-Z0-9_]*([/*][0-9.]+)?$|\.\.\.")


def code_of(text):
    """The code in a Markdown text: each line of a fenced or indented block (``\\`` continuations
    joined, ``#`` comments dropped), then each inline code span, its line breaks made spaces."""
    pieces, prose, fenced = [], [], False
    lines = iter(text.splitlines())
    for line in lines:
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        if fenced or line.startswith("    "):
            while line.rstrip().endswith("\\"):
                line = line.rstrip()[:-1] + " " + next(lines, "")
            pieces.append(line.split(" # ")[0].strip())
        else:
            prose.append(line)
    pieces += [" ".join(m.group(1).split()) for m in re.finditer(r"`([^`]+)`", "\n".join(prose))]
    return pieces


def mpisph_commands(piece):
    """The argument lists after ``-m mpisph`` in a piece of code."""
    out = []
    for command in re.split(r";|&&", piece):
        if "-m mpisph" not in command:
            continue
        words = command.split("-m mpisph", 1)[1]
        words = re.sub(r"\(.*", "", words)  # a closing remark in parentheses
        words = words.replace("[", " ").replace("]", " ")
        out.append([w for w in shlex.split(words) if w != "|"])
    return out


def documented():
    for path in DOCS:
        for piece in code_of(path.read_text()):
            for argv in mpisph_commands(piece):
                if argv:
                    yield f"{path.relative_to(ROOT)}: {' '.join(argv)}", argv


def _without_placeholders(argv):
    """``argv`` with each placeholder value of an option made a number, which every option takes,
    and each placeholder for more words (OPTIONS) left out."""
    out = []
    for i, w in enumerate(argv):
        if not (i and PLACEHOLDER.search(w)):
            out.append(w)
        elif argv[i - 1].startswith("--") and argv[i - 1] != "--set":
            out.append("1")
        elif "=" in w:
            out.append(w)
    return out


def _check_sets(module, items):
    """Each NAME=VALUE (each alternative of VALUE) against the case's parameters: every name but
    the placeholder NAME is checked, upper-case ones (H, L, I_0) too; a placeholder value (A,
    DIR) is not."""
    params = all_params(module)
    for name, text in parse_sets(items).items():
        if name not in params:
            if name == "NAME":  # --set NAME=VALUE
                continue
            resolve_params(module, {name: "0"})  # raises with the parser's suggestion
        for value in text.split("|"):
            if not PLACEHOLDER.search(value):
                resolve_params(module, {name: value})


def _case(name):
    return load_case_module(str(ROOT / name) if name.endswith(".py") else name)


def check(argv):
    """Raise InputError where ``argv`` (the words after ``python -m mpisph``) would fail to parse."""
    head = argv[0]
    case = argv[1] if head in ("info", "compare") and len(argv) > 1 else head
    if head in SUBCOMMANDS_WITHOUT_CASE or PLACEHOLDER.search(case) or case in ("info", "compare"):
        return
    if head == "info":
        _case(case)
    elif head == "compare":
        a = compare.parse(_without_placeholders(argv[1:]))
        module = _case(a.case)
        varies, values = compare.varied(a)
        compare.set_overrides(a.overrides, varies)
        _check_sets(module, a.overrides)
        names = [name for name in values if not PLACEHOLDER.search(name)]
        if names or varies not in compare.all_params(module):
            compare.check_values(a.case, module, varies, names, {})
    else:
        a = _parser().parse_args(_without_placeholders(argv))
        _check_sets(_case(a.case), a.overrides)


COMMANDS = dict(documented())


def test_the_docs_hold_commands():
    """The extraction finds the docs' commands (a change of notation would otherwise check none)."""
    assert len(COMMANDS) > 100
    assert any(argv[0] == "compare" for argv in COMMANDS.values())


@pytest.mark.parametrize("where", sorted(COMMANDS))
def test_documented_command_parses(where):
    try:
        check(COMMANDS[where])
    except InputError as e:
        pytest.fail(f"{where}\n  -> {e}")


@pytest.mark.parametrize("argv, why", [
    (["lube_collapse_2d", "--set", "a_ratio=1"], "unknown parameter"),
    (["lube_collapse_3d", "--set", "I0=0.05"], "unknown parameter"),
    (["inclined_plane", "--set", "H=deep"], "takes a number"),
    (["lube_collapse_2d", "--set", "viscous_step=implicit|semi"], "must be one of"),
    (["compare", "vertical_cut", "--stabiliser", "none,utvf,tvd"], "must be one of"),
    (["compare", "vertical_cut", "--stabiliser", "none", "--set", "stabiliser=utvf"], "give its values to --stabiliser, not --set"),
    (["compare", "lube_collapse_2d", "--vary", "m_0=1.2,-1"], "m_0 must be positive"),
    (["compare", "dam_break_3d", "--stabiliser", "none,utvf"], "has no stabiliser parameter"),
    (["cube_failure_3d", "--t-end", "1", "--frames", "3"], "unrecognized"),
    (["no_such_case"], "unknown case"),
])
def test_a_stale_command_fails(argv, why):
    with pytest.raises(InputError, match=why):
        check(argv)


def test_notation():
    piece = "mpirun -n 2 python -m mpisph vertical_cut --set stabiliser=S [kernel=cubic_spline] (and the same); ls"
    assert mpisph_commands(piece) == [["vertical_cut", "--set", "stabiliser=S", "kernel=cubic_spline"]]
    assert code_of("text `python -m mpisph a\n--set b=1` more\n\n    python -m mpisph c \\\n      --quiet # c\n") == [
        "python -m mpisph c        --quiet", "python -m mpisph a --set b=1"]


def _sources():
    """{file name: path} of the repository's Python and shell files outside the virtual environment
    and the runs."""
    return {p.name: p for p in ROOT.rglob("*") if p.suffix in (".py", ".sh")
            and not {".venv", "runs", ".git"} & set(p.relative_to(ROOT).parts)}


def test_named_files_exist():
    names = set()
    for path in DOCS:
        named = re.finditer(r"\b((?:scripts|benchmarks|jobs|tests|mpisph|cases)/[\w/]+\.(?:py|sh))\b", path.read_text())
        names |= {m.group(1) for m in named}
    assert len(names) > 20
    names = {n for n in names if not re.search(r"/[A-Z]+\.", n)}  # cases/NAME.py: a placeholder
    assert [n for n in sorted(names) if not (ROOT / n).is_file()] == []


def test_architecture_names_every_module():
    text = (ROOT / "docs" / "ARCHITECTURE.md").read_text()
    named = set(re.findall(r"`(?:[\w/]*/)?(\w+\.py)`", text)) - {"NAME.py"}
    sources = _sources()
    assert [n for n in sorted(named) if n not in sources] == []
    # a subpackage's __init__.py is described with its folder, not by its file name
    modules = [p for folder in ("mpisph", "scripts", "benchmarks") for p in (ROOT / folder).rglob("*.py")
               if "__pycache__" not in p.parts and (p.name != "__init__.py" or p.parent.name == "mpisph")]
    assert len(modules) > 50
    assert sorted(str(p.relative_to(ROOT)) for p in modules if p.name not in named) == []
