"""The stress diffusion of riemann_granular (mpisph/physics/drucker_prager.py) on a jittered 3D block
of soil particles: Feng et al.'s term acts on a linear stress field that is not geostatic; the linear
one leaves every linear field alone, conserves the stress and damps noise. On a laterally confined
layer at rest (tests/cases/confined_layer.py), only Feng's term changes the lateral stress."""

from pathlib import Path

import numpy as np
import pytest

from lattice import lattice
from mpirun import mpisph
from mpisph.io.frames import list_frames, read_frame
from mpisph.measure import thrust_ratio
from mpisph.neighbours import neighbour_lists
from mpisph.physics.drucker_prager import (STRESS_DIFFUSIONS, linear_stress_diffusion, stress_diffusion,
                                           stress_gradient)

DP = 0.04
RHO0, G, K0, C0 = 1850.0, 9.8, 0.58, 50.0
LAYER = str(Path(__file__).parent / "cases" / "confined_layer.py")


@pytest.fixture(scope="module")
def block():
    """A 10^3 block jittered by 0.2 dp, its masses and densities varied by up to 10 %."""
    x, _, _, _, k, _ = lattice(3, 1.3, n=10, dp=DP)
    rng = np.random.default_rng(1)
    x = x + rng.uniform(-0.2, 0.2, x.shape) * DP
    n = len(x)
    kind = np.zeros(n, np.int8)
    mass = RHO0 * DP**3 * rng.uniform(0.9, 1.1, n)
    rho = RHO0 * rng.uniform(0.95, 1.05, n)
    start, nbr = neighbour_lists(x, np.arange(n), kind, n, k.support, x.min(axis=0) - DP)
    return x, k, kind, mass, rho, start, nbr


def geostatic_and_gradients(x):
    """The geostatic field of a level surface at z = 1 m plus horizontal gradients of 20 kPa/m in
    sigma_xx and 10 kPa/m in sigma_xy (packed xx, yy, zz, xy, yz, xz)."""
    s = np.zeros((len(x), 6))
    sv = -RHO0 * G * (1.0 - x[:, 2])
    s[:, 0], s[:, 1], s[:, 2] = K0 * sv + 2e4 * x[:, 0], K0 * sv, sv
    s[:, 3] = 1e4 * x[:, 1]
    return s


def linear_rate(block, stress):
    x, k, kind, mass, rho, start, nbr = block
    n = len(x)
    grad, rate = np.zeros((n, 6, 3)), np.zeros((n, 6))
    stress_gradient(n, start, nbr, x, stress, mass, rho, kind, k.params, grad)
    linear_stress_diffusion(n, start, nbr, x, stress, grad, mass, rho, kind, C0, k.params, rate)
    return grad, rate


def test_the_gradient_of_a_linear_field_is_exact(block):
    grad, _ = linear_rate(block, geostatic_and_gradients(block[0]))
    np.testing.assert_allclose(grad[:, 0, 0], 2e4, rtol=1e-9)
    np.testing.assert_allclose(grad[:, 3, 1], 1e4, rtol=1e-9)
    np.testing.assert_allclose(grad[:, 2, 2], RHO0 * G, rtol=1e-9)
    assert np.abs(grad[:, 4]).max() < 1e-6


def test_only_the_linear_diffusion_leaves_a_linear_field_that_is_not_geostatic_alone(block):
    x, k, kind, mass, rho, start, nbr = block
    stress = geostatic_and_gradients(x)
    feng = np.zeros((len(x), 6))
    stress_diffusion(len(x), start, nbr, x, stress, mass, rho, kind, RHO0, G, K0, C0, k.params, feng)
    _, linear = linear_rate(block, stress)
    assert np.abs(feng).max() > 1e5  # Pa/s, at the faces
    assert np.abs(linear).max() < 1e-6


def test_the_linear_diffusion_conserves_and_damps_noise(block):
    x, _, _, mass, rho, _, _ = block
    noise = np.random.default_rng(2).normal(0.0, 1e3, (len(x), 6))
    _, rate = linear_rate(block, geostatic_and_gradients(x) + noise)
    volume = mass / rho
    total = np.abs(volume[:, None] * rate).sum(axis=0)
    assert np.all(np.abs((volume[:, None] * rate).sum(axis=0)) < 1e-12 * total)
    assert np.sum(volume[:, None] * noise * rate) < 0.0


@pytest.fixture(scope="module")
def confined_layers(tmp_path_factory):
    """{stress_diffusion: the last frame} of tests/cases/confined_layer.py run to 1 s on one rank."""
    out = {}
    for diffusion in STRESS_DIFFUSIONS:
        d = tmp_path_factory.mktemp(f"layer_{diffusion}")
        r = mpisph([LAYER, "--set", f"stress_diffusion={diffusion}", "--out", d, "--quiet"])
        assert r.returncode == 0, r.stderr
        out[diffusion] = read_frame(list_frames(d)[-1])
    return out


def test_a_confined_layer_at_rest_keeps_its_lateral_stress_without_feng_s_term(confined_layers):
    """The thrust ratio (mpisph/measure.py) at 1 s: without diffusion within 2 % of nu / (1 - nu) =
    0.4286 (0.421), with the linear form within 10 % (0.398). Feng's term, which subtracts a lateral
    stress of (1 - sin phi) sigma_v = 0.577 sigma_v, drives it down instead (0.279; 0.21 from 2 s
    on, docs/FLUME.md): it rewrites the lateral stress of a soil at rest in equilibrium."""
    elastic = 0.3 / 0.7
    k = {diffusion: thrust_ratio(frame) for diffusion, frame in confined_layers.items()}
    assert k["none"] == pytest.approx(elastic, rel=0.02)
    assert k["linear"] == pytest.approx(elastic, rel=0.10)
    assert k["geostatic"] < 0.75 * elastic


def test_the_stress_budget_script_splits_the_lateral_stress_change(tmp_path):
    """scripts/stress_budget.py on the confined layer with Feng's term, to 1 s: the diffusion's parts
    of the three bands sum to zero (it conserves sum V sigma), it makes the floor's band more
    compressive and the layer above less, the elastic response takes the floor's band the other way
    and further, and the causes add up to the change of sum V sigma_xx (to 5 %: the volumes change
    with the summed density)."""
    import re
    import subprocess
    import sys

    script = Path(__file__).parent.parent / "scripts" / "stress_budget.py"
    run = subprocess.run([sys.executable, str(script), LAYER, "--set", "stress_diffusion=geostatic", "--t-end", "1",
                          "--out", str(tmp_path / "budget")], capture_output=True, text=True, timeout=300, check=True)
    lines = [line for line in run.stdout.splitlines() if line.startswith("t ")]
    table, band = {}, None
    for b, part, value in re.findall(r"(?:(top|middle|bottom): )?(diffusion|elastic|plastic) (-?\d+)", lines[-1]):
        band = b or band
        table[band, part] = float(value)
    assert len(table) == 9
    assert abs(sum(table[b, "diffusion"] for b in ("top", "middle", "bottom"))) <= 2.0  # printed to 1 N/m
    assert table["bottom", "diffusion"] < -100.0 and table["middle", "diffusion"] > 100.0
    assert table["bottom", "elastic"] > -table["bottom", "diffusion"]
    integral = [float(re.search(r"sum V sigma_xx (-?\d+)", line).group(1)) for line in (lines[0], lines[-1])]
    assert abs((integral[1] - integral[0]) - sum(table.values())) <= 0.05 * abs(sum(table.values()))
