"""scripts/run_tests.sh reads each stage's counts from pytest's last summary line, warnings or not."""

import pathlib
import subprocess

import pytest

SCRIPT = pathlib.Path(__file__).resolve().parent.parent / "scripts" / "run_tests.sh"


@pytest.mark.parametrize("summary, counts", [
    ("828 passed, 2 warnings in 408.40s (0:06:48)", "828 0"),
    ("1 passed, 1 warning in 0.50s", "1 0"),
    ("3 passed, 1 failed, 2 errors in 1.2s", "3 3"),
    ("9 passed, 1038 deselected in 2.97s", "9 0"),
    ("no tests ran in 0.01s", "0 0"),
])
def test_pytest_counts(tmp_path, summary, counts):
    log = tmp_path / "stage.log"
    log.write_text("....\n" + summary + "\n")
    function = subprocess.run(["sed", "-n", "/^pytest_counts()/,/^}/p", str(SCRIPT)], capture_output=True,
                              text=True, check=True).stdout
    out = subprocess.run(["bash", "-c", function + f'\npytest_counts "{log}"'], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == counts
