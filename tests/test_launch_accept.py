"""mpisph.launch's ``accept``: a script or benchmark whose run ends with a status it does not
accept stops with the command and the run's error, instead of reading frames that are not there."""

import pytest

from mpisph import launch


def test_a_status_outside_accept_stops_with_the_command_and_its_error():
    with pytest.raises(SystemExit) as stop:
        launch.mpirun_mpisph(["no_such_case", "--quiet"], timeout=120, accept=(0, 3))
    message = str(stop.value)
    assert message.startswith("mpirun -n 1 python -m mpisph no_such_case --quiet (in ")
    assert "exited with status 2" in message
    assert "mpisph: error:" in message and "no_such_case" in message.split("status 2")[1]


def test_an_accepted_status_returns_the_run():
    r = launch.mpirun_mpisph(["no_such_case"], timeout=120, accept=(0, 2))
    assert r.returncode == 2 and "no_such_case" in r.stderr
