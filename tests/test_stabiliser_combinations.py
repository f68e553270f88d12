"""Several remedies at once: ``stabiliser=a+b`` (stabilisers/__init__.py), refused where two of them
would shift the positions or a name comes twice; the runs' bits on 1-3 ranks are in
tests/test_rank_agreement.py."""

import pytest

from mpisph.case import build_case, load_case_module, resolve_params
from mpisph.compare import check_values
from mpisph.errors import InputError
from mpisph.parts import make_parts
from mpisph.stabilisers import STABILISERS, stabiliser_names


def parts_of(case_name, **sets):
    module = load_case_module(case_name)
    params = resolve_params(module, {k: str(v) for k, v in sets.items()})
    case = build_case(module, params)
    return case, make_parts(case, params)


def test_a_combination_makes_each_stabiliser_in_its_order():
    case, parts = parts_of("vertical_cut", dp=0.2, stabiliser="artificial_stress+utvf", kernel="wendland_c2")
    assert case.stabilisers == ("artificial_stress", "utvf")
    assert [type(s) for s in parts.stabilisers] == [STABILISERS["artificial_stress"], STABILISERS["utvf"]]
    assert not parts.kernel.adaptive
    # the force term of artificial stress beside the scheme's, and UTVF's surface classes
    assert "artificial_stress" in [t.name for t in parts.forces.terms]
    assert parts.needs_surface
    case, parts = parts_of("vertical_cut", dp=0.2, stabiliser="utvf+adaptive_kernel")
    assert [s.name for s in parts.stabilisers] == ["utvf", "adaptive_kernel"]
    assert parts.kernel.adaptive  # the adaptive kernel adapts the spline for every pair sum, UTVF's too
    assert {"knot", "displacement_gradient"} <= {f.name for f in parts.fields}


@pytest.mark.parametrize("value, fragments", [
    ("utvf+utvf", ["'utvf' is listed twice"]),
    ("utvf+shifting", ["utvf and shifting both shift the positions"]),
    ("tvf+artificial_stress+tvf_limited", ["tvf and tvf_limited both shift the positions"]),
    ("none+utvf", ["several of them (not none) joined by +"]),
    ("utvf+artificial", ["several of them (not none) joined by +", "'utvf+artificial'"]),
    ("utvf,artificial_stress", ["must be one of"]),
])
def test_combinations_that_are_refused(value, fragments):
    with pytest.raises(InputError) as e:
        resolve_params(load_case_module("cohesive_failure_2d"), {"stabiliser": value})
    for fragment in fragments:
        assert fragment in str(e.value)


def test_a_case_file_is_held_to_the_same_rules():
    """A case file's ``stabilisers="a+b"`` is read by stabiliser_names (Case.__post_init__), which
    holds it to the parameter's rules (tests/test_architecture.py reads its plain lists)."""
    with pytest.raises(InputError, match="both shift the positions"):
        stabiliser_names("shifting+tvf")


def test_compare_takes_a_combination_as_one_run():
    module = load_case_module("cohesive_failure_2d")
    check_values("cohesive_failure_2d", module, "stabiliser", ("none", "utvf", "artificial_stress+utvf"), {})
    with pytest.raises(InputError, match="both shift the positions"):
        check_values("cohesive_failure_2d", module, "stabiliser", ("none", "utvf+shifting"), {})
