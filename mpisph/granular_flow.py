"""What every mu(I) case shares (004_): the scheme's discretisation options as case parameters,
and the scheme and integrator they select."""

from .case import Param


def mu_i_params(alpha_doc, viscous_step):
    """Typed parameters of the mu_i scheme's options (physics/mu_i.py), with the case's word on
    alpha and its default viscous step."""
    return {
        "alpha": Param(0.0, "-", f"artificial viscosity (Eq. 38; {alpha_doc})"),
        "beta_max": Param(1.5, "-", "cap of the Morris wall factor (Eq. 36)", positive=True),
        "viscous_form": Param("cleary", "-", "viscous term: Eq. 27 as printed, or the corrected stress divergence",
                              choices=("cleary", "corrected_stress")),
        "viscous_step": Param(viscous_step, "-", "explicit: Eq. 39's viscous limit bounds the step; implicit: the "
                              "viscous term backward in time (physics/implicit_viscosity.py)",
                              choices=("explicit", "implicit")),
        "viscosity_mean": Param("secant", "-", "viscosity of a particle pair: harmonic (Eq. 37), arithmetic or "
                                "secant (mu_i_law.pair_viscosity)", choices=("harmonic", "arithmetic", "secant")),
    }


def mu_i_scheme(p):
    """Case keywords of the mu_i scheme with the options of ``mu_i_params`` and symplectic Verlet."""
    return dict(scheme="mu_i", integrator="symplectic_verlet",
                scheme_options={"alpha": p.alpha, "beta_max": p.beta_max, "viscous_form": p.viscous_form,
                                "viscous_step": p.viscous_step, "viscosity_mean": p.viscosity_mean})
