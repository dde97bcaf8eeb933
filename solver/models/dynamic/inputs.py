"""Everything the dynamic model reads from a case, converted to SI, in one plain dataclass.

Keeping the case access here isolates the model from the case-file format (solver.case): tests can
build :class:`DynamicInputs` directly.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import MappingProxyType

from solver.geometry import BearingGeometry

#: Oil used when a case has no [lubricant] table: the ADORE example data set of physics.md §2.6.4
#: (MIL-L-23699-class turbine oil) with a viscosity typical of a spindle at operating temperature.
DEFAULT_OIL = MappingProxyType(
    {
        "viscosity": 0.01,  # Pa s
        "pressure_viscosity": 20.0e-9,  # 1/Pa
        "traction": (0.0, 0.05, 1.0, 0.036),  # mu_zero, mu_max, slip_at_max [m/s], mu_infinity
    }
)
DEFAULT_OIL_NOTE = (
    "no [lubricant] in the case: default oil used (viscosity 0.01 Pa s, pressure-viscosity 20 "
    "/GPa, traction mu_zero 0, mu_max 0.05 at 1 m/s, mu_infinity 0.036; ADORE example data, "
    "physics.md §2.6.4)"
)


@dataclass(frozen=True)
class DynamicInputs:
    """Case data used by the dynamic model, SI units (rad, rad/s, N, N m, m, kg, Pa s)."""

    geometry: BearingGeometry
    inner_speed: float  # rad/s
    outer_speed: float  # rad/s
    axial_load: float  # N, on the inner ring along +x
    radial_load: float  # N
    radial_load_angle: float  # rad (azimuth of the radial load)
    misalignment: float  # rad, imposed tilt
    misalignment_axis: float  # rad, azimuth of the tilt axis
    misalignment_frame: str  # "space" | "ring"
    tilting_moment: float | None  # N m; None = tilt imposed (misalignment)
    moment_axis: float  # rad
    cage_guidance: str  # "outer_ring" | "inner_ring" | "ball"
    pocket_clearance: float  # m, diametral
    guide_clearance: float  # m, diametral
    cage_mass: float  # kg
    pocket_friction: float
    guide_land_width: float  # m
    viscosity: float  # Pa s
    pressure_viscosity: float  # 1/Pa
    traction_curve: tuple[float, float, float, float]  # mu_zero, mu_max, slip_at_max, mu_infinity
    default_lubricant: bool
    shaft_revolutions: float
    samples_per_revolution: int
    case_text: str = ""


def _get(obj, name, default=None):
    value = getattr(obj, name, default) if obj is not None else default
    return default if value is None else value


def _traction_tuple(traction):
    if traction is None:
        return DEFAULT_OIL["traction"]
    names = ("mu_zero", "mu_max", "slip_at_max_m_s", "mu_infinity")
    if isinstance(traction, dict):
        return tuple(float(traction[n]) for n in names)
    return tuple(float(getattr(traction, n)) for n in names)


def inputs_from_case(case) -> DynamicInputs:
    """Read a :class:`solver.case.Case` (or any object with the same attributes) into SI inputs.

    Missing optional [cage] values are estimated from the bearing (documented here): pocket
    diametral clearance 0.028 D, guide diametral clearance 0.0055 d_m, cage mass from a polymer
    ring (1400 kg/m^3) of width D and radial thickness 0.3 D on the pitch circle, friction 0.08,
    land width 0.5 D, outer-ring guidance.
    """
    geometry = BearingGeometry.from_case(case)
    op = case.operating
    rpm = 2.0 * math.pi / 60.0
    D, dm = geometry.ball_diameter, geometry.pitch_diameter
    cage = getattr(case, "cage", None)
    est_mass = 1400.0 * math.pi * dm * D * 0.3 * D
    lub = getattr(case, "lubricant", None)
    sim = getattr(case, "simulation", None)
    moment = getattr(op, "tilting_moment_Nm", None)
    text = ""
    to_toml = getattr(case, "to_toml", None)
    if callable(to_toml):
        try:
            text = to_toml()
        except Exception:  # noqa: BLE001 - the text is informational only
            text = ""
    return DynamicInputs(
        geometry=geometry,
        inner_speed=float(op.inner_ring_speed_rpm) * rpm,
        outer_speed=float(_get(op, "outer_ring_speed_rpm", 0.0)) * rpm,
        axial_load=float(_get(op, "axial_load_N", 0.0)),
        radial_load=float(_get(op, "radial_load_N", 0.0)),
        radial_load_angle=math.radians(float(_get(op, "radial_load_angle_deg", 0.0))),
        misalignment=math.radians(float(_get(op, "misalignment_deg", 0.0))),
        misalignment_axis=math.radians(float(_get(op, "misalignment_axis_deg", 90.0))),
        misalignment_frame=str(_get(op, "misalignment_frame", "space")),
        tilting_moment=None if moment is None else float(moment),
        moment_axis=math.radians(float(_get(op, "moment_axis_deg", 90.0))),
        cage_guidance=str(_get(cage, "guidance", "outer_ring")),
        pocket_clearance=float(_get(cage, "pocket_diametral_clearance_mm", 0.028 * D * 1e3)) * 1e-3,
        guide_clearance=float(_get(cage, "guide_diametral_clearance_mm", 0.0055 * dm * 1e3)) * 1e-3,
        cage_mass=float(_get(cage, "mass_g", est_mass * 1e3)) * 1e-3,
        pocket_friction=float(_get(cage, "pocket_friction", 0.08)),
        guide_land_width=float(_get(cage, "guide_land_width_mm", 0.5 * D * 1e3)) * 1e-3,
        viscosity=float(_get(lub, "viscosity_Pas", DEFAULT_OIL["viscosity"])),
        pressure_viscosity=float(_get(lub, "pressure_viscosity_per_GPa", 20.0)) * 1e-9,
        traction_curve=_traction_tuple(getattr(lub, "traction", None) if lub is not None else None),
        default_lubricant=lub is None,
        shaft_revolutions=float(_get(sim, "shaft_revolutions", 10.0)),
        samples_per_revolution=int(_get(sim, "samples_per_revolution", 180)),
        case_text=text,
    )
