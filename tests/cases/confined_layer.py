"""A soil layer at rest filling a tank of free-slip walls (tests/test_stress_diffusion.py), under
the geostatic stress an elastic layer loaded by gravity in one-dimensional compression takes:
sigma_h = nu / (1 - nu) sigma_v. Laterally confined, it is in equilibrium with any lateral stress,
so the lateral stress should stay as it is. The density is summed (density_reinit=free_surface, as
flume_3d): evolved by Eq. 16 alone it spreads to 0.56-2.8 rho0 within 1 s in this layer without
stress diffusion."""

from mpisph.case import Param
from mpisph.soil import confined_layer, scheme_params, soil_params

PARAMS = {
    "L": Param(0.5, "m", "width of the layer and the tank", positive=True),
    "H": Param(1.0, "m", "depth of the layer", positive=True),
    "dp": Param(0.05, "m", "particle spacing", positive=True),
    **soil_params(rho0=1850.0, E=1.8e6, nu=0.3, cohesion=5.0e3, phi=25.0,  # 000_ Table 2
                  density_reinit="free_surface"),
    **scheme_params(),
    "t_end": Param(1.0, "s", "simulated end time", positive=True),
    "output_interval": Param(0.25, "s", "simulated time between frames", positive=True),
}


def setup(p):
    return confined_layer(p, p.L, p.H, "layer", k_lateral=p.nu / (1.0 - p.nu))
