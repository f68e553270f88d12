"""Vertical cut in cohesive soil: a 4 m x 2 m Drucker-Prager block against a left wall fails under its own weight (002_ Sec. 6, Bui et al. 2008).

002_'s material, spacing and kernel, run by default with the Riemann scheme and UTVF of the other
soil cases, so that the remedies compare on one scheme (docs/VALIDATION.md, section remedies_cuts);
``--set scheme=classic_granular`` runs 002_'s own SPH, the only one that reads its alpha and beta.
The step follows the CFL condition; ``--set max_time_step=5e-5`` caps it at 002_ Table 4's.
"""

from mpisph.case import Param, h_factor_param
from mpisph.kernels import KERNELS
from mpisph.soil import block_on_floor, scheme_params, soil_params

PARAMS = {
    "L": Param(4.0, "m", "length of the soil block", positive=True),
    "H": Param(2.0, "m", "height of the cut", positive=True),
    "dp": Param(0.025, "m", "particle spacing (002_ Table 4)", positive=True),
    **soil_params(rho0=1850.0, E=1.5e6, nu=0.2, cohesion=5.0e3, phi=20.0),  # 002_ Table 3
    **scheme_params(alpha=1.0, beta=0.0),  # 002_ Table 4
    "kernel": Param("cubic_spline", "-", "smoothing kernel (002_: the cubic B-spline)", choices=tuple(KERNELS)),
    "h_factor": h_factor_param(1.5, "002_ Table 4: h = 1.5 dp"),
    "t_end": Param(2.0, "s", "simulated end time", positive=True),
    "output_interval": Param(0.1, "s", "simulated time between frames", positive=True),
}


def setup(p):
    return block_on_floor(p, p.L, p.H, 2.5 * p.L, "soil")
