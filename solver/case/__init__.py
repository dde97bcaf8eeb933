"""Case files (TOML): schema, validation, the :class:`Case` dataclasses and writing back to TOML.

Public: :func:`load_case` (a case file), :func:`parse_case` (TOML text), :class:`Case`,
:func:`dynamic_problems` (why the dynamic model cannot run a valid case), :data:`FIELDS` (the schema
table the app builds its form from), :data:`MATERIAL_FIELDS`, :class:`Field`. The format is
documented in docs/case-format.md.
"""

from solver.errors import CaseError, Problem

from .io import load_case, parse_case
from .model import Bearing, Cage, Case, Lubricant, Operating, Simulation, Traction
from .schema import FIELDS, MATERIAL_FIELDS, OPTIONAL, REQUIRED, Estimated, Field
from .validate import dynamic_problems

__all__ = [
    "FIELDS",
    "MATERIAL_FIELDS",
    "OPTIONAL",
    "REQUIRED",
    "Bearing",
    "Cage",
    "Case",
    "CaseError",
    "Estimated",
    "Field",
    "Lubricant",
    "Operating",
    "Problem",
    "Simulation",
    "Traction",
    "dynamic_problems",
    "load_case",
    "parse_case",
]
