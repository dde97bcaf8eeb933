"""Test bearings for the dynamic model, built directly as DynamicInputs (no case file needed)."""

from __future__ import annotations

import math
from dataclasses import replace

from solver.geometry import BearingGeometry
from solver.materials import BUILTIN_MATERIALS
from solver.models.dynamic.inputs import DEFAULT_OIL, DynamicInputs


def spindle_geometry() -> BearingGeometry:
    """7008C-class hybrid spindle bearing (case-format.md example)."""
    return BearingGeometry(
        ball_count=18,
        ball_diameter=7.144e-3,
        pitch_diameter=54.0e-3,
        inner_conformity=0.54,
        outer_conformity=0.53,
        free_contact_angle=math.radians(15.0),
        ball_material=BUILTIN_MATERIALS["silicon_nitride"],
        ring_material=BUILTIN_MATERIALS["bearing_steel"],
        inner_shoulder_diameter=49.0e-3,
        outer_shoulder_diameter=59.0e-3,
    )


def spindle_inputs(rpm=20000.0, axial=500.0, radial=0.0, **changes) -> DynamicInputs:
    g = changes.pop("geometry", spindle_geometry())
    base = DynamicInputs(
        geometry=g,
        inner_speed=rpm * math.pi / 30.0,
        outer_speed=0.0,
        axial_load=axial,
        radial_load=radial,
        radial_load_angle=0.0,
        misalignment=0.0,
        misalignment_axis=math.radians(90.0),
        misalignment_frame="space",
        tilting_moment=None,
        moment_axis=math.radians(90.0),
        cage_guidance="outer_ring",
        pocket_clearance=0.20e-3,
        guide_clearance=0.30e-3,
        cage_mass=6.0e-3,
        pocket_friction=0.08,
        guide_land_width=3.0e-3,
        viscosity=DEFAULT_OIL["viscosity"],
        pressure_viscosity=DEFAULT_OIL["pressure_viscosity"],
        traction_curve=DEFAULT_OIL["traction"],
        default_lubricant=True,
        shaft_revolutions=2.0,
        samples_per_revolution=90,
    )
    return replace(base, **changes)
