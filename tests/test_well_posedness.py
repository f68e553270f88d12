"""Where the mu(I) friction law is well-posed (mpisph/well_posedness.py: Barker et al. 2015, in the
form of Barker & Gray 2017, Eq. 3.9): rate-independent friction is ill-posed, 004_'s materials are
well-posed in a window of I that scales with I_0, the glass beads' uniform incline flows inside its
window and Lube's sand columns below theirs; the share of a frame's dissipation outside the window; and
the mu(I) scheme's start-up lines on the window and on the particles' jostle."""

import math

import numpy as np
import pytest

from mpisph.case import build_case, load_case_module, resolve_params
from mpisph.parts import make_parts
from mpisph.physics.mu_i import JOSTLE_STRESS, jostle_inertial_number
from mpisph.physics.mu_i_law import friction
from mpisph.well_posedness import criterion, ill_posed_dissipation_share, ill_posed_energy_share, ill_posedness, \
    partial_regularisation_alphas, partially_regularised_friction, table_1_law, well_posed_range, well_posed_window


@pytest.mark.parametrize("I_s", [0.0, 0.01])
def test_rate_independent_friction_is_ill_posed(I_s):
    """At I = 0 the law's slope drops out of nu = I mu'/mu, and C = mu(0)^2 > 0; with Eq. 18's shift
    mu(0) = mu_s + (mu_2 - mu_s) I_s / (I_s + I_0)."""
    m = table_1_law("sand_0.4mm", I_s=I_s)
    mu_0 = m.mu_s + (m.mu_2 - m.mu_s) * I_s / (I_s + m.I_0)
    assert ill_posedness(0.0, m) == pytest.approx(mu_0 ** 2, rel=1e-14)


def test_at_i_0_the_criterion_takes_its_closed_form():
    """At I = I_0 (no shift) mu is the mean of mu_s and mu_2 and nu = (mu_2 - mu_s) / (4 mu); glass
    beads: C = -0.2148, inside the window."""
    m = table_1_law("glass_beads")
    mu = 0.5 * (m.mu_s + m.mu_2)
    nu = (m.mu_2 - m.mu_s) / (4.0 * mu)
    expected = 4 * nu ** 2 - 4 * nu + mu ** 2 * (1 - nu / 2) ** 2
    assert ill_posedness(m.I_0, m) == pytest.approx(expected, rel=1e-13)
    assert expected == pytest.approx(-0.2148, abs=1e-4)


@pytest.mark.parametrize("name, window", [("glass_beads", (0.01935, 0.8523)),
                                          ("sand_0.8mm", (0.1388, 1.382)), ("sand_0.4mm", (0.4315, 1.815))])
def test_each_material_is_well_posed_in_one_window(name, window):
    """The window's ends are where C changes sign; C < 0 inside, > 0 a little outside on either
    side; the ends to four digits."""
    m = table_1_law(name)
    lo, hi = well_posed_window(m)
    assert (lo, hi) == pytest.approx(window, rel=1e-3)
    inside = np.geomspace(lo * 1.001, hi * 0.999, 50)
    assert (ill_posedness(inside, m) < 0).all()
    assert ill_posedness(lo * 0.999, m) > 0 and ill_posedness(hi * 1.001, m) > 0


def test_the_window_scales_with_i_0():
    """C depends on I only through I / I_0 (without Eq. 18's shift)."""
    lo, hi = well_posed_window(table_1_law("sand_0.4mm"))
    lo2, hi2 = well_posed_window(table_1_law("sand_0.4mm", I_0=2 * 2.65))
    assert (lo2, hi2) == pytest.approx((2 * lo, 2 * hi), rel=1e-8)
    # the scan follows I_0 far from the materials' values
    for scale in (1e-10, 1e4):
        window = well_posed_window(table_1_law("sand_0.4mm", I_0=scale * 2.65))
        assert window == pytest.approx((scale * lo, scale * hi), rel=1e-8)


def test_a_law_of_nearly_no_friction_is_well_posed_beyond_the_scan():
    """mu_s and mu_2 of 0.38 and 0.64 degrees (coefficients typed as angles): C < 0 from I_1 =
    I_0 mu_s^3 / (4 (mu_2 - mu_s)) to the lowest order (where -4 nu + mu_s^2 changes sign) up to
    some 1e4 I_0, past the scan's 1e3 I_0, so the window's upper end is inf and the start-up
    report says so, where both ended in a ValueError traceback."""
    mu_s, mu_2 = math.tan(math.radians(0.38)), math.tan(math.radians(0.64))
    m = table_1_law("glass_beads", mu_s=mu_s, mu_2=mu_2)
    lo, hi = well_posed_window(m)
    assert hi == math.inf
    assert lo == pytest.approx(m.I_0 * mu_s**3 / (4 * (mu_2 - mu_s)), rel=0.01)
    assert (ill_posedness(np.geomspace(lo * 1.001, 1e3 * m.I_0, 50), m) < 0).all()
    assert well_posed_range(lo, hi) == f"only for I > {lo:.3g}"
    assert well_posed_range(0.0, 2.0) == "only for I < 2" and well_posed_range(0.0, math.inf) == "for every I"


def test_a_nearly_rate_independent_law_has_no_window():
    m = table_1_law("sand_0.4mm")._replace(mu_2=table_1_law("sand_0.4mm").mu_s * 1.01)
    assert well_posed_window(m) is None


def test_the_incline_is_inside_its_window_and_the_columns_are_below_theirs():
    """The glass beads' uniform flow at 25 degrees, I_u = 0.133 (004_ Sec. 5.1), lies inside their
    window; the sand columns' window starts above I = 0.4, where their collapses dissipate nearly all
    their energy at I < 0.04 (scripts/well_posedness.py, docs/COLLAPSES.md)."""
    lo, hi = well_posed_window(table_1_law("glass_beads"))
    assert lo < 0.1330 < hi
    assert well_posed_window(table_1_law("sand_0.4mm"))[0] > 0.4


def log_slope(f, I, step=1e-6):
    """nu = d ln mu / d ln I of the function f by central differences in ln I."""
    return (np.log(f(I * math.exp(step))) - np.log(f(I * math.exp(-step)))) / (2.0 * step)


@pytest.mark.parametrize("name", ["glass_beads", "sand_0.8mm", "sand_0.4mm"])
def test_the_partial_regularisation_is_well_posed_below_the_window_for_its_alphas(name):
    """Barker & Gray 2017's branch below I_1: continuous at I_1, sqrt(alpha / ln(A / I)) with
    A = I_1 exp(alpha / mu(I_1)^2), nu = mu^2 / (2 alpha), and C < 0 from I_1 down to 1e-12 I_1 for
    alphas inside partial_regularisation_alphas, C > 0 just below I_1 for alphas 1 % outside. nu is
    taken by differences, not from the closed form the alphas are computed with."""
    m = table_1_law(name)
    lower = well_posed_window(m)[0]
    lo, hi = partial_regularisation_alphas(m)
    I = lower * np.geomspace(1e-12, 0.999, 200)
    for alpha in (1.01 * lo, 0.5 * (lo + hi), 0.99 * hi):
        def mu(x):
            return partially_regularised_friction(x, m, alpha)

        a = lower * math.exp(alpha / friction(lower, m) ** 2)
        assert mu(I) == pytest.approx(np.sqrt(alpha / np.log(a / I)), rel=1e-12)
        assert mu(lower * (1 - 1e-9)) == pytest.approx(friction(lower, m), rel=1e-8)
        nu = log_slope(mu, I)
        assert nu == pytest.approx(mu(I) ** 2 / (2.0 * alpha), rel=1e-6)
        assert (criterion(nu, mu(I)) < 0.0).all()
    for alpha in (0.99 * lo, 1.01 * hi):
        just_below = lower * 0.999
        mu = partially_regularised_friction(just_below, m, alpha)
        assert criterion(log_slope(lambda x: partially_regularised_friction(x, m, alpha), just_below), mu) > 0.0
    # above I_1 the law is 004_'s
    assert partially_regularised_friction(2.0 * lower, m, hi) == friction(2.0 * lower, m)


def test_the_partial_regularisation_lowers_the_sands_friction_where_the_columns_flow():
    """With the largest admissible alpha (the friction nearest 004_'s below I_1), the 0.32 mm sand's
    friction at I = 1e-3, where its collapses dissipate, falls from 0.589 (30.5 degrees) to 0.439
    (23.7 degrees); the glass beads', whose window starts at I = 0.019, from 0.383 to 0.359."""
    for name, ours, regularised in (("sand_0.4mm", 0.5893, 0.4386), ("glass_beads", 0.3828, 0.3588)):
        m = table_1_law(name)
        assert friction(1e-3, m) == pytest.approx(ours, abs=1e-4)
        alpha = partial_regularisation_alphas(m)[1]
        assert float(partially_regularised_friction(1e-3, m, alpha)) == pytest.approx(regularised, abs=1e-4)


def test_the_dissipation_share_outside_the_window():
    """eta gamma_dot^2 m / rho per grain: 1, 4 and 3 W at I = 0.01, 0.5 and 2 with the window
    (0.432, 1.82): 4 of 8 W lie outside it; a wall particle does not count; with no window all of it;
    NaN where nothing dissipates."""
    frame = {"kind": np.array([0, 0, 0, 1]), "inertial_number": np.array([0.01, 0.5, 2.0, 0.01]),
             "eta": np.array([1.0, 1.0, 3.0, 100.0]), "gamma_dot": np.array([1.0, 2.0, 1.0, 1.0]),
             "mass": np.array([2.0, 2.0, 2.0, 2.0]), "rho": np.array([2.0, 2.0, 2.0, 2.0])}
    assert ill_posed_dissipation_share(frame, (0.432, 1.82)) == pytest.approx(0.5, rel=1e-15)
    assert ill_posed_dissipation_share(frame, None) == 1.0
    assert math.isnan(ill_posed_dissipation_share(dict(frame, gamma_dot=np.zeros(4)), (0.432, 1.82)))


def test_the_energy_share_integrates_the_frames_in_time():
    """Two grains, at I = 0.01 (outside the window) and 0.5 (inside), dissipating 0 and 0 W at t = 0,
    1 and 1 W at t = 1 s, 2 and 0 W at t = 2 s: by trapezoids 3 J in all, 2 J of them at the first."""
    def frame(t, first, second):
        return {"t": t, "kind": np.array([0, 0]), "inertial_number": np.array([0.01, 0.5]),
                "eta": np.array([first, second]), "gamma_dot": np.ones(2), "mass": np.ones(2), "rho": np.ones(2)}

    frames = [frame(0.0, 0.0, 0.0), frame(1.0, 1.0, 1.0), frame(2.0, 2.0, 0.0)]
    assert ill_posed_energy_share(frames, (0.432, 1.82)) == pytest.approx(2.0 / 3.0, rel=1e-15)
    assert math.isnan(ill_posed_energy_share(frames[:1], (0.432, 1.82)))


def test_the_mu_i_start_up_report_names_the_window():
    module = load_case_module("lube_collapse_2d")
    p = resolve_params(module, {"dp": "0.02"})
    lines = make_parts(build_case(module, p), p).scheme.report()
    assert any("well-posed only for 0.432 < I < 1.82" in line for line in lines)


def test_the_mu_i_start_up_report_says_where_the_particles_jostle_carries_a_stress():
    """dp / d of the incline's defaults is 10; the inertial numbers the line gives put the jostle's
    stress, JOSTLE_STRESS (I dp / d)^2, at 1 % and 10 % of the pressure."""
    module = load_case_module("inclined_plane")
    p = resolve_params(module, {})
    lines = make_parts(build_case(module, p), p).scheme.report()
    assert any("dp / d = 10 grains wide" in line and "1 % at I = 0.029, 10 % at I = 0.091" in line
               for line in lines)
    for share in (0.01, 0.1):
        I = jostle_inertial_number(share, 10.0)
        assert JOSTLE_STRESS * (I * 10.0) ** 2 == pytest.approx(share, rel=1e-12)
