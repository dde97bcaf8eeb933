"""Named oils: ``[lubricant]`` key values of three common bearing oils, each with its source.

Copy an oil's keys into a case's ``[lubricant]`` section (:func:`lubricant_table` gives them as a
TOML-ready dict; docs/case-format.md lists them). Values are typical data of the oil class, not of
one product: the viscosities follow the viscosity-grade or specification limits named in
``source``; pressure-viscosity coefficients are those tabulated for the fluid class by Hamrock
(NASA RP-1255, 1991, table of alpha at 38 degC); the rheology (Eyring stress, limiting-shear-stress
coefficient, film shear modulus) lies in the ranges measured by Johnson & Tevaarwerk (Proc. R. Soc.
A 356, 1977) and Bair & Winer (J. Lubr. Technol. 101, 1979) [E: class values, not fitted to one
oil]. Beta comes from the two viscosities at 40 and 100 degC.
"""

from __future__ import annotations

import math


def _beta(nu_40: float, nu_100: float) -> float:
    """Temperature-viscosity coefficient [1/K] through two kinematic viscosities 60 K apart."""
    return math.log(nu_40 / nu_100) / 60.0


#: name -> (``[lubricant]`` keys, source text)
OILS: dict[str, tuple[dict, str]] = {
    "spindle-mineral-vg32": (
        {
            "traction_model": "rheology",
            "viscosity_Pas": 32.0e-6 * 870.0,  # 32 mm^2/s at 40 degC, 870 kg/m^3
            "reference_temperature_C": 40.0,
            "temperature_viscosity_per_K": round(_beta(32.0, 5.4), 4),
            "pressure_viscosity_per_GPa": 25.0,
            "eyring_stress_MPa": 5.0,
            "limiting_shear_stress_MPa": 2.0,
            "limiting_shear_coefficient": 0.07,
            "film_shear_modulus_GPa": 0.5,
            "thermal_conductivity_W_mK": 0.13,
            "density_kg_m3": 870.0,
        },
        "paraffinic mineral spindle oil ISO VG 32 (ISO 3448: 28.8-35.2 mm^2/s at 40 degC; "
        "about 5.4 mm^2/s at 100 degC for viscosity index ~100); alpha of mineral oils at 38 degC "
        "about 18-25 /GPa (Hamrock, NASA RP-1255), 25 /GPa taken",
    ),
    "ester-vg22": (
        {
            "traction_model": "rheology",
            "viscosity_Pas": 22.0e-6 * 920.0,
            "reference_temperature_C": 40.0,
            "temperature_viscosity_per_K": round(_beta(22.0, 4.6), 4),
            "pressure_viscosity_per_GPa": 13.0,
            "eyring_stress_MPa": 3.0,
            "limiting_shear_stress_MPa": 2.0,
            "limiting_shear_coefficient": 0.06,
            "film_shear_modulus_GPa": 0.4,
            "thermal_conductivity_W_mK": 0.15,
            "density_kg_m3": 920.0,
        },
        "synthetic (polyol) ester spindle oil ISO VG 22 (ISO 3448: 19.8-24.2 mm^2/s at 40 degC; "
        "about 4.6 mm^2/s at 100 degC, viscosity index ~140); alpha of an advanced ester at "
        "38 degC (Hamrock, NASA RP-1255: about 1.3e-8 /Pa)",
    ),
    "jet-oil-mil-prf-23699": (
        {
            "traction_model": "rheology",
            "viscosity_Pas": 25.0e-6 * 1000.0,
            "reference_temperature_C": 40.0,
            "temperature_viscosity_per_K": round(_beta(25.0, 5.0), 4),
            "pressure_viscosity_per_GPa": 13.7,
            "eyring_stress_MPa": 3.0,
            "limiting_shear_stress_MPa": 2.0,
            "limiting_shear_coefficient": 0.06,
            "film_shear_modulus_GPa": 0.4,
            "thermal_conductivity_W_mK": 0.15,
            "density_kg_m3": 1000.0,
        },
        "gas-turbine jet oil to MIL-PRF-23699 (5 cSt polyol ester: at least 23 mm^2/s at 40 degC, "
        "4.9-5.4 mm^2/s at 100 degC, density about 1.0 g/cm^3); alpha of a formulated advanced "
        "ester at 38 degC (Hamrock, NASA RP-1255: 1.37e-8 /Pa). The ADORE example traction curve "
        "of physics.md is for this oil class.",
    ),
}


def lubricant_table(name: str) -> dict:
    """The ``[lubricant]`` keys of oil ``name``; ValueError naming the known oils otherwise."""
    try:
        keys, _ = OILS[name]
    except KeyError:
        raise ValueError(f"unknown oil {name!r}; known oils: {', '.join(OILS)}") from None
    return dict(keys)
