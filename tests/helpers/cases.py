"""The test bearings, defined once: case texts (no catalogue needed) and the SI inputs that the
dynamic-model tests build from them."""

from __future__ import annotations

import math
from dataclasses import replace
from functools import cache

from solver.case import parse_case
from solver.geometry import BearingGeometry
from solver.inputs import Inputs, OperatingPoint, to_inputs
from solver.materials import BUILTIN_MATERIALS


def case_text(title: str, bearing: dict, operating: dict, *more: str) -> str:
    """A case file: ``title``, the ``[bearing]`` and ``[operating]`` keys (case units, in the order
    given) and ``more`` TOML text after them."""
    return (
        f'\ntitle = "{title}"\n'
        + toml_table("bearing", bearing)
        + toml_table("operating", operating)
        + "".join(more)
    )


def toml_table(name: str, values: dict) -> str:
    """``[name]`` and a ``key = value`` line a key (texts quoted, numbers in ``repr``)."""
    lines = [f"[{name}]"] + [
        f'{key} = "{value}"' if isinstance(value, str) else f"{key} = {value!r}"
        for key, value in values.items()
    ]
    return "\n".join(lines) + "\n"


#: The 7008C-class hybrid spindle bearing without designation, provenance and lands.
SPINDLE_BEARING = {
    "ball_count": 18,
    "ball_diameter_mm": 7.144,
    "pitch_diameter_mm": 54.0,
    "inner_groove_radius_ratio": 0.54,
    "outer_groove_radius_ratio": 0.53,
    "free_contact_angle_deg": 15.0,
    "ball_material": "silicon_nitride",
    "ring_material": "bearing_steel",
}
SPINDLE_NAME = {"designation": "7008C-class hybrid", "provenance": "estimated"}
SPINDLE_TITLE = "7008C-class hybrid spindle bearing, combined load"

SPINDLE = case_text(
    SPINDLE_TITLE,
    SPINDLE_NAME
    | SPINDLE_BEARING
    | {"inner_shoulder_diameter_mm": 49.0, "outer_shoulder_diameter_mm": 59.0},
    {"inner_ring_speed_rpm": 20000.0, "axial_load_N": 500.0, "radial_load_N": 300.0},
)

LUBRICANT = """
[lubricant]
viscosity_Pas = 0.01
pressure_viscosity_per_GPa = 20.0
"""

#: A 209-class deep-groove bearing with diametral clearance.
DEEP_GROOVE_BEARING = {
    "designation": "209-class",
    "provenance": "estimated",
    "ball_count": 9,
    "ball_diameter_mm": 12.7,
    "pitch_diameter_mm": 65.0,
    "inner_groove_radius_ratio": 0.52,
    "outer_groove_radius_ratio": 0.52,
    "diametral_clearance_mm": 0.015,
    "ball_material": "bearing_steel",
    "ring_material": "bearing_steel",
}
DEEP_GROOVE_RADIAL = case_text(
    "deep groove, radial load",
    DEEP_GROOVE_BEARING,
    {"inner_ring_speed_rpm": 6000.0, "radial_load_N": 2000.0},
)

# The example of the case-format contract with the shoulder diameters the contract gives (45.9 /
# 62.2 mm, see "About the contract's example lands" in docs/case-format.md): these lands do not rise
# above the 7008C grooves, so the case loads with warnings.
CONTRACT_EXAMPLE = case_text(
    SPINDLE_TITLE,
    SPINDLE_NAME
    | SPINDLE_BEARING
    | {"inner_shoulder_diameter_mm": 45.9, "outer_shoulder_diameter_mm": 62.2},
    {
        "inner_ring_speed_rpm": 20000.0,
        "outer_ring_speed_rpm": 0.0,
        "axial_load_N": 500.0,
        "radial_load_N": 300.0,
        "radial_load_angle_deg": 0.0,
        "misalignment_deg": 0.0,
        "misalignment_axis_deg": 90.0,
        "misalignment_frame": "space",
    },
    """
[materials.my_steel]
youngs_modulus_GPa = 208.0
poisson_ratio = 0.3
density_kg_m3 = 7800.0

[cage]
guidance = "outer_ring"
pocket_diametral_clearance_mm = 0.20
guide_diametral_clearance_mm = 0.30
mass_g = 6.0

[lubricant]
viscosity_Pas = 0.01
pressure_viscosity_per_GPa = 20.0
traction = { mu_zero = 0.0, mu_max = 0.05, slip_at_max_m_s = 1.0, mu_infinity = 0.036 }

[simulation]
shaft_revolutions = 10.0
samples_per_revolution = 180
""",
)

# The spindle as the dynamic-model tests run it: explicit cage values and a short run at a tight
# tolerance; no [lubricant], so the schema's default oil.
SPINDLE_RUN = (
    SPINDLE
    + """
[cage]
guidance = "outer_ring"
pocket_diametral_clearance_mm = 0.20
guide_diametral_clearance_mm = 0.30
mass_g = 6.0
pocket_friction = 0.08
guide_land_width_mm = 3.0
land_flooding = 1.0
[simulation]
shaft_revolutions = 2.0
samples_per_revolution = 90
tolerance = 1e-4
"""
)


def spindle_bearing(**changes) -> BearingGeometry:
    """The bearing of :data:`SPINDLE_BEARING` in SI, without lands; ``changes`` replace fields."""
    return BearingGeometry(
        **{
            "ball_count": 18,
            "ball_diameter": 7.144e-3,
            "pitch_diameter": 54.0e-3,
            "inner_conformity": 0.54,
            "outer_conformity": 0.53,
            "free_contact_angle": math.radians(15.0),
            "ball_material": BUILTIN_MATERIALS["silicon_nitride"],
            "ring_material": BUILTIN_MATERIALS["bearing_steel"],
        }
        | changes
    )


def bearing_218(**changes) -> BearingGeometry:
    """The textbook 218 angular-contact bearing (Harris) in SI: D = 22.225 mm, d_m = 125.26 mm,
    f = 0.5232, alpha_0 = 40 deg, steel; ``changes`` replace fields."""
    steel = BUILTIN_MATERIALS["bearing_steel"]
    return BearingGeometry(
        **{
            "ball_count": 16,
            "ball_diameter": 22.225e-3,
            "pitch_diameter": 125.26e-3,
            "inner_conformity": 0.5232,
            "outer_conformity": 0.5232,
            "free_contact_angle": math.radians(40.0),
            "ball_material": steel,
            "ring_material": steel,
        }
        | changes
    )


@cache
def _spindle_run_inputs() -> Inputs:
    """:data:`SPINDLE_RUN` in SI, without its case text (the tests replace its operating point)."""
    inputs = to_inputs(parse_case(SPINDLE_RUN, source="tests.helpers.cases.SPINDLE_RUN"))
    return replace(inputs, case_text="")


def spindle_geometry() -> BearingGeometry:
    """The 7008C-class hybrid spindle bearing of :data:`SPINDLE` (SI)."""
    return _spindle_run_inputs().geometry


def spindle_inputs(rpm=20000.0, axial=500.0, radial=0.0, **operating_changes) -> Inputs:
    """:data:`SPINDLE_RUN` at ``rpm`` under ``axial`` and ``radial`` loads [N]; other
    ``operating_changes`` replace fields of the :class:`OperatingPoint` (SI)."""
    operating = OperatingPoint(
        inner_ring_speed=rpm * math.pi / 30.0,
        outer_ring_speed=0.0,
        axial_load=axial,
        radial_load=radial,
        radial_load_angle=0.0,
        misalignment=0.0,
        misalignment_axis=math.radians(90.0),
        misalignment_frame="space",
        tilting_moment=None,
        moment_axis=math.radians(90.0),
    )
    return replace(_spindle_run_inputs(), operating=replace(operating, **operating_changes))


def operating_point(
    inner_ring_speed: float,
    outer_ring_speed: float = 0.0,
    axial_load: float = 0.0,
    radial_load: float = 0.0,
    radial_load_angle: float = 0.0,
    misalignment: float = 0.0,
    misalignment_axis: float = 0.5 * math.pi,
    misalignment_frame: str = "space",
    tilting_moment: float | None = None,
    moment_axis: float = 0.5 * math.pi,
) -> OperatingPoint:
    """An SI :class:`OperatingPoint` with the fields not named set as a case leaves them (no tilt,
    axes at 90 degrees); arguments in the field order."""
    return OperatingPoint(
        inner_ring_speed,
        outer_ring_speed,
        axial_load,
        radial_load,
        radial_load_angle,
        misalignment,
        misalignment_axis,
        misalignment_frame,
        tilting_moment,
        moment_axis,
    )
