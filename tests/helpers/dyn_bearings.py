"""Test bearings for the dynamic model, built directly as SI Inputs (no case file needed)."""

from __future__ import annotations

import math
from dataclasses import replace

from solver.geometry import BearingGeometry
from solver.inputs import (
    CageInputs,
    Inputs,
    LubricantInputs,
    OperatingPoint,
    SimulationInputs,
)
from solver.materials import BUILTIN_MATERIALS


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


def default_oil() -> LubricantInputs:
    """The case schema's default oil (a case without [lubricant]), SI."""
    from solver.case import FIELDS
    from solver.case.model import Lubricant, Traction
    from solver.inputs import lubricant_inputs

    def defaults(path):
        n = len(path)
        return {f.name: f.default for f in FIELDS if f.path[:-1] == path and len(f.path) == n + 1}

    lubricant = Lubricant(
        **defaults(("lubricant",)), traction=Traction(**defaults(("lubricant", "traction")))
    )
    return lubricant_inputs(lubricant, given=False)


def spindle_inputs(rpm=20000.0, axial=500.0, radial=0.0, **operating_changes) -> Inputs:
    """The spindle bearing at ``rpm`` under ``axial`` and ``radial`` loads [N]; other
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
    return Inputs(
        geometry=spindle_geometry(),
        operating=replace(operating, **operating_changes),
        cage=CageInputs(
            guidance="outer_ring",
            pocket_clearance=0.20e-3,
            guide_clearance=0.30e-3,
            mass=6.0e-3,
            pocket_friction=0.08,
            guide_land_width=3.0e-3,
            land_flooding=1.0,
        ),
        lubricant=default_oil(),
        simulation=SimulationInputs(
            shaft_revolutions=2.0,
            samples_per_revolution=90,
            traction=True,
            damping_ratio=0.05,
            gravity=9.81,
            tolerance=1e-4,
            cage=True,
        ),
    )


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
