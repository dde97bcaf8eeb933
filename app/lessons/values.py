"""The numbers a lesson's text may quote, computed from a results Dataset (results-schema.md).

:data:`VALUES` is the registry: each value has a name (the placeholder in a lesson template), its
unit as shown after the number, a one-line meaning (listed in docs/lessons.md, which a test keeps
true) and the function that computes it. :func:`lesson_values` evaluates all of them for one
result. They read only the Dataset's coordinates, its metrics by name (``ds.racetrace.metric``:
the metrics table, solver.results.metrics, defines every statistic, its loaded contacts and the
analysed window of a dynamic run) and ``ds.racetrace.warnings()``: never the case text. Here the
metrics are only converted to the units a lesson shows.

Conventions: angles in degree, loads in N, pressures in GPa, lengths of ellipses in mm, speeds in
rev/min. A value the result does not have (the gyroscopic moment of a dynamic run, the band
thickness of a quasi-static snapshot) is ``None``; the template then says so in words.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import xarray as xr

from solver import RPM

RACES = ("inner", "outer")


@dataclass(frozen=True)
class Value:
    """One quotable number (or word): ``unit`` is shown after it in docs/lessons.md."""

    name: str
    unit: str
    meaning: str
    compute: Callable[[xr.Dataset], object]


# ---- reading the Dataset -------------------------------------------------------------------------
def _metric(ds, name: str, race: str | None = None, scale: float = 1.0):
    """Metric ``name`` of the metrics table (of ``race``), times ``scale``; None when NaN."""
    value = ds.racetrace.metric(name)
    if race is not None:
        value = value.sel(race=race)
    value = float(value)
    return value * scale if math.isfinite(value) else None


def _count(ds, name: str, race: str | None = None):
    value = _metric(ds, name, race)
    return None if value is None else int(value)


def _coord(ds, name: str, scale=1.0):
    return float(ds.coords[name]) * scale


def _race_control(ds):
    if "race_control" not in ds:
        return None
    words = [str(v) for v in np.asarray(ds["race_control"].values).ravel()]
    if not set(words) <= set(RACES):
        return None  # ball speeds from a traction balance: no controlling race
    inner = words.count("inner")
    if inner == len(words):
        return "inner"
    if inner == 0:
        return "outer"
    return f"inner for {inner} balls, outer for {len(words) - inner}"


def _ellipse_arc(ds, race: str):
    """The mean semi-axis across the groove as the groove arc it spans, degree."""
    semi_major = _metric(ds, "mean_semi_major", race)
    if semi_major is None:
        return None
    return math.degrees(semi_major / float(ds.coords["groove_radius"].sel(race=race)))


def _pressure_limit(ds):
    from solver import STATIC_PRESSURE_LIMIT

    return STATIC_PRESSURE_LIMIT * 1e-9


def _misalignment_frame(ds):
    frame = str(ds.coords["misalignment_frame"].values)
    return "turning with the inner ring" if frame == "ring" else "fixed in space"


def _registry() -> dict[str, Value]:
    entries = [
        Value(
            "speed_rpm",
            "rpm",
            "inner-ring (shaft) speed",
            lambda ds: _coord(ds, "inner_ring_speed", 1.0 / RPM),
        ),
        Value(
            "axial_load", "N", "axial load on the inner ring", lambda ds: _coord(ds, "axial_load")
        ),
        Value(
            "radial_load",
            "N",
            "radial load on the inner ring",
            lambda ds: _coord(ds, "radial_load"),
        ),
        Value(
            "misalignment",
            "deg",
            "imposed tilt of the inner ring",
            lambda ds: _coord(ds, "misalignment"),
        ),
        Value(
            "misalignment_frame",
            "",
            '"fixed in space" or "turning with the inner ring"',
            _misalignment_frame,
        ),
        Value(
            "free_contact_angle",
            "deg",
            "contact angle of the unloaded bearing",
            lambda ds: _coord(ds, "free_contact_angle"),
        ),
        Value("ball_count", "", "number of balls", lambda ds: int(ds.coords["ball_count"])),
        Value(
            "shaft_revolutions",
            "",
            "shaft revolutions the dynamic run covers",
            lambda ds: _metric(ds, "shaft_revolutions"),
        ),
        Value(
            "settled",
            "",
            "1 when the dynamic run settled, 0 when it is too short to settle (a transient)",
            lambda ds: _count(ds, "settled"),
        ),
        Value(
            "centrifugal_force",
            "N",
            "mean centrifugal force on one ball",
            lambda ds: _metric(ds, "mean_centrifugal_force"),
        ),
        Value(
            "gyroscopic_moment",
            "mN m",
            "mean gyroscopic moment on one ball (quasi-static)",
            lambda ds: _metric(ds, "mean_gyroscopic_moment", scale=1e3),
        ),
        Value(
            "race_control",
            "",
            'the raceway that "controls" the ball (quasi-static)',
            _race_control,
        ),
        Value(
            "loaded_balls",
            "",
            "balls carrying load (inner race)",
            lambda ds: _count(ds, "loaded_balls", "inner"),
        ),
        Value(
            "cage_speed_rpm",
            "rpm",
            "mean cage speed",
            lambda ds: _metric(ds, "mean_cage_speed", scale=1.0 / RPM),
        ),
        Value(
            "epicyclic_cage_speed_rpm",
            "rpm",
            "cage speed of pure rolling at the free contact angle",
            lambda ds: float(ds.racetrace.metric("epicyclic_cage_speed")) / RPM,
        ),
        Value(
            "cage_slip",
            "%",
            "how much slower than epicyclic the cage runs (negative: faster)",
            lambda ds: _metric(ds, "cage_slip", scale=100.0),
        ),
        Value(
            "max_pressure",
            "GPa",
            "highest peak contact pressure on either race",
            lambda ds: max(
                (
                    p
                    for p in (_metric(ds, "peak_pressure", r, 1e-9) for r in RACES)
                    if p is not None
                ),
                default=None,
            ),
        ),
        Value(
            "pressure_limit",
            "GPa",
            "static pressure limit (ISO 76) the warnings use",
            _pressure_limit,
        ),
        Value(
            "truncated_contacts",
            "",
            "ball-race contacts whose ellipse runs over the shoulder",
            lambda ds: _count(ds, "truncated_contacts"),
        ),
        Value(
            "warning_count",
            "",
            "number of warnings the result gives",
            lambda ds: len(ds.racetrace.warnings()),
        ),
    ]
    # (value name suffix, unit, meaning, metric, scale): each race's values from the metrics table
    per_race = (
        ("contact_angle", "deg", "mean {race} contact angle", "mean_contact_angle", 1.0),
        ("contact_angle_min", "deg", "smallest {race} contact angle", "min_contact_angle", 1.0),
        ("contact_angle_max", "deg", "largest {race} contact angle", "max_contact_angle", 1.0),
        ("load", "N", "mean {race} contact load (loaded contacts)", "mean_load", 1.0),
        ("load_max", "N", "largest {race} contact load", "largest_load", 1.0),
        (
            "load_min",
            "N",
            "smallest {race} contact load (0 when a ball is unloaded)",
            "smallest_load",
            1.0,
        ),
        ("pressure", "GPa", "highest {race} peak contact pressure", "peak_pressure", 1e-9),
        (
            "semi_major",
            "mm",
            "mean {race} ellipse semi-axis across the groove",
            "mean_semi_major",
            1e3,
        ),
        (
            "semi_minor",
            "mm",
            "mean {race} ellipse semi-axis along the rolling direction",
            "mean_semi_minor",
            1e3,
        ),
        ("spin_to_roll", "", "mean {race} spin-to-roll ratio", "mean_spin_to_roll", 1.0),
        (
            "excursion",
            "deg",
            "{race} track excursion in its own ring's frame",
            "excursion",
            1.0,
        ),
        (
            "band_thickness",
            "deg",
            "{race} track band thickness in its own ring's frame (dynamic)",
            "band_thickness",
            1.0,
        ),
        (
            "truncation_margin",
            "deg",
            "smallest margin between the {race} ellipse and the shoulder (negative: over it)",
            "min_truncation_margin",
            1.0,
        ),
    )
    for race in RACES:
        entries += [
            Value(
                f"{race}_{suffix}",
                unit,
                meaning.format(race=race),
                lambda ds, r=race, m=metric, k=scale: _metric(ds, m, r, k),
            )
            for suffix, unit, meaning, metric, scale in per_race
        ]
        entries.append(
            Value(
                f"{race}_ellipse_arc",
                "deg",
                f"mean {race} ellipse semi-axis across the groove as groove arc",
                lambda ds, r=race: _ellipse_arc(ds, r),
            )
        )
    return {v.name: v for v in entries}


#: name -> Value, in the order docs/lessons.md lists them.
VALUES: dict[str, Value] = _registry()
VALUE_NAMES = frozenset(VALUES)


def lesson_values(ds: xr.Dataset) -> dict[str, object]:
    """Every value of :data:`VALUES` for one result (None where the result does not have it)."""
    out = {}
    for name, value in VALUES.items():
        result = value.compute(ds)
        if isinstance(result, float) and not math.isfinite(result):
            result = None
        out[name] = result
    return out


__all__ = ["VALUES", "VALUE_NAMES", "Value", "lesson_values"]
