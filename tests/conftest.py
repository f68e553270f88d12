"""The suite's one rule on launches: a test that starts runs on more than one rank carries the
``ranks`` marker. scripts/run_tests.sh runs those tests in a stage of their own, one at a time, so
that their ranks have the cores to themselves: beside a second pytest worker, the ranks of a run
waiting for each other take turns on the cores (three ranks of the rank-agreement runs and a
worker's run on two cores took three times as long). Launches through mpisph.launch are checked
here; a test that starts mpirun by another way is marked by hand."""

import pytest

from mpisph import launch

_marked = {"ranks": False}
_mpirun_python = launch.mpirun_python


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_setup(item):
    """Before the test's fixtures, which may launch runs too."""
    _marked["ranks"] = item.get_closest_marker("ranks") is not None


# After a rank exits with a non-zero status, Open MPI 4's mpirun takes twice its
# odls_base_sigkill_timeout (1 s by default) to end the job: `mpirun -n 1 python -c "import sys;
# sys.exit(2)"` took 2.2 s here, 4.1 s with the timeout at 2 s and 0.1 s at 0. On one rank the only
# process has then already exited, so a test's 1-rank launch takes no grace; runs on several ranks
# keep theirs.
NO_GRACE_AFTER_EXIT = {"OMPI_MCA_odls_base_sigkill_timeout": "0"}


def _checked_mpirun_python(args, ranks=1, env=None, **kwargs):
    if ranks > 1 and not _marked["ranks"]:
        raise AssertionError(f"a run on {ranks} ranks from a test without the 'ranks' marker")
    if ranks == 1:
        env = {**NO_GRACE_AFTER_EXIT, **(env or {})}
    return _mpirun_python(args, ranks=ranks, env=env, **kwargs)


launch.mpirun_python = _checked_mpirun_python
