"""Import one of the repository's scripts (scripts/NAME.py) or a module of a package of scripts (scripts/NAME/) for the
tests of its functions."""

import importlib.util
import sys
from pathlib import Path

SCRIPTS = Path(__file__).resolve().parent.parent / "scripts"
BEAM = ["--set", "H_over_dp=5", "--t-end", "0.002", "--output-interval", "0.001"]  # an oscillating_beam run of seconds


def load_script(name):
    """The module of scripts/``name``.py, freshly executed, with scripts/ on the import path as when it
    runs (a script may import its siblings)."""
    _scripts_on_the_path()
    spec = importlib.util.spec_from_file_location(name, SCRIPTS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def load_package(name):
    """The module ``name`` of a package in scripts/ (say "validation.runs" for
    scripts/validation/runs.py) as the scripts import it, scripts/ on the import path; checked to
    come from scripts/ and not from an installed package of the same name."""
    _scripts_on_the_path()
    module = importlib.import_module(name)
    assert Path(module.__file__).is_relative_to(SCRIPTS / name.split(".")[0]), f"{name} from {module.__file__}"
    return module


def fix_code_version(monkeypatch):
    """Give the scripts' runs (scripts/validation/runs.py) a fixed code version, so that they are stamped
    even while mpisph/ or cases/ hold uncommitted changes (code_version's own test is in
    test_validate_reuse.py)."""
    monkeypatch.setattr(load_package("validation.runs"), "code_version", lambda: ["tree-of-mpisph", "tree-of-cases"])


def _scripts_on_the_path():
    """scripts/ on the import path, as when a script runs (a script may import its siblings)."""
    if str(SCRIPTS) not in sys.path:
        sys.path.append(str(SCRIPTS))
