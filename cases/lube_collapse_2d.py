"""Planar collapse of a sand column on a rough floor, mu(I) rheology (Lube et al. 2005; 004_ Sec. 5.2).

A column L_0 long and H_0 = a L_0 high stands against a back wall at x = 0 and
is released at t = 0; it spreads along +x over a no-slip floor. The back wall
is free-slip by default, which makes the run the right half of a symmetric
column 2 L_0 wide. The sand and its defaults are granular_column.py's. The
front (largest x of a grain) and the grains' force on the floor
(force_floor_x, _y) are columns of diagnostics.csv; the deposit's
runout L_inf is measure.runout of the last frame, compared with
references.planar_runout. With ``channel_width`` > 0 the run is a slice of a
channel that narrow, whose side walls hold the grains back by Coulomb friction
(physics/side_walls.py); the default is plane strain, no side walls.
"""

from mpisph.case import Param
from mpisph.granular_column import column_params, planar_column
from mpisph.granular_flow import side_wall_params, side_walls

PARAMS = {
    "L_0": Param(0.0972, "m", "length of the column from the back wall", positive=True),
    **column_params(a=0.9, dp=0.00324, m_0=1.2),  # 004_ Table 3, row 3; dp = L_0 / 30, H_0 = 27 dp
    "back_wall": Param("free_slip", "-", "the wall behind the column", choices=("free_slip", "no_slip")),
    **side_wall_params(),
    "t_end": Param(1.0, "s", "simulated end time", positive=True),
    "output_interval": Param(0.05, "s", "simulated time between frames", positive=True),
}


def setup(p):
    case = planar_column(p, p.L_0, back_wall_slip=p.back_wall == "free_slip")
    case.forces += side_walls(p, p.a * p.L_0)
    return case
