"""tests/conftest.py's rule: a test without the ``ranks`` marker cannot start a run on several ranks
(run_tests.sh would run it beside a second worker)."""

import pytest

from mpisph import launch


def test_a_run_on_several_ranks_needs_the_ranks_marker():
    with pytest.raises(AssertionError, match="without the 'ranks' marker"):
        launch.mpirun_mpisph(["list"], ranks=2, timeout=60)


@pytest.mark.ranks
def test_with_the_marker_it_runs():
    r = launch.mpirun_mpisph(["list"], ranks=2, timeout=120)
    assert r.returncode == 0 and "dam_break_2d" in r.stdout
