"""case.case_of_frame: a frame's case built again from the parameters the frame carries (what
scripts/well_posedness.py and scripts/incline_layers.py read a run's material with)."""

import pytest

from mpisph.case import case_of_frame


def test_a_frame_s_parameters_build_its_case_and_newer_ones_take_their_defaults():
    """A planar column written with I_0 = 0.05 (and a run parameter, which the case does not read):
    its material has that I_0; mu_s, absent from the frame, takes the case's default, tan 30.5 degrees."""
    case = case_of_frame({"case": "lube_collapse_2d", "a": 1.0, "dp": 0.0243, "I_0": 0.05, "t_end": 0.6})
    assert case.material.I_0 == 0.05
    assert case.material.mu_s == pytest.approx(0.5890, abs=1e-4)
