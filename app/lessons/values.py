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


def _input(ds, name: str, scale=1.0, at_start=False):
    """An operating input of the result: its coordinate (a steady result, or an input a history
    holds), else its data variable over ``time`` (an input that varies: results-schema.md) at the
    end of the run, or at t = 0 with ``at_start``."""
    if name in ds.coords:
        return float(ds.coords[name]) * scale
    values = np.asarray(ds[name].values, dtype=float).ravel()
    return float(values[0 if at_start else -1]) * scale


def _coord(ds, name: str, scale=1.0):
    return _input(ds, name, scale)


def _phase_metric(ds, name: str, which: int, race: str | None = None, scale: float = 1.0):
    """Metric ``name`` over the first (``which`` = 0) or the last (-1) phase of the result
    (solver.results.phases: a run along a history is cut at its event times; a steady result has
    one phase, its analysed window), times ``scale``; None when NaN or not dynamic."""
    if "time" not in ds.dims:
        return None
    value = ds.racetrace.phase_metric(name).isel(phase=which)
    if race is not None:
        value = value.sel(race=race)
    value = float(value)
    return value * scale if math.isfinite(value) else None


def _phase_edge(ds, which: int, edge: str):
    """Start or end time [s] of the first (0) or last (-1) phase of a dynamic result."""
    if "time" not in ds.dims:
        return None
    phase = ds.racetrace.phases()[which]
    return phase.start if edge == "start" else phase.end


def _skid(ds, field: str, scale: float = 1.0):
    """A field of the run's skid extent (solver.results.skidding.skid_extent over the whole run:
    samples at more than a tenth of its top rolling speed); None for a quasi-static result, or
    when the cage never lags by more than the skidding threshold (the times of the skid)."""
    if "time" not in ds.dims:
        return None
    extent = ds.racetrace.skid_extent()
    value = None if extent is None else getattr(extent, field)
    return None if value is None else float(value) * scale


def _min_skidding_ratio(ds):
    """1 - the largest instantaneous cage slip of the run's skid extent (None: not dynamic)."""
    peak = _skid(ds, "peak")
    return None if peak is None else 1.0 - peak


def _skid_warnings(ds):
    return sum(1 for w in ds.racetrace.warnings() if w.startswith("the cage skids"))


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
            "start_speed_rpm",
            "rpm",
            "inner-ring (shaft) speed at t = 0 (a run along a history)",
            lambda ds: _input(ds, "inner_ring_speed", 1.0 / RPM, at_start=True),
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
            "start_radial_load",
            "N",
            "radial load on the inner ring at t = 0 (a run along a history)",
            lambda ds: _input(ds, "radial_load", at_start=True),
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
            "first_phase_cage_slip",
            "%",
            "mean instantaneous cage slip over the first phase (dynamic; a steady run: its window)",
            lambda ds: _phase_metric(ds, "mean_instantaneous_cage_slip", 0, scale=100.0),
        ),
        Value(
            "last_phase_cage_slip",
            "%",
            "mean instantaneous cage slip over the last phase (dynamic; a steady run: its window)",
            lambda ds: _phase_metric(ds, "mean_instantaneous_cage_slip", -1, scale=100.0),
        ),
        Value(
            "first_phase_end_time",
            "s",
            "end of the first phase: the first event time of the history (dynamic)",
            lambda ds: _phase_edge(ds, 0, "end"),
        ),
        Value(
            "last_phase_start_time",
            "s",
            "start of the last phase: the last event time of the history (dynamic)",
            lambda ds: _phase_edge(ds, -1, "start"),
        ),
        Value(
            "min_skidding_ratio",
            "",
            "smallest skidding ratio of the run (cage speed / rolling cage speed; dynamic)",
            _min_skidding_ratio,
        ),
        Value(
            "min_skidding_ratio_time",
            "s",
            "time of the smallest skidding ratio (dynamic)",
            lambda ds: _skid(ds, "peak_time"),
        ),
        Value(
            "skid_start_time",
            "s",
            "first time the cage lags its rolling speed by more than the skidding threshold",
            lambda ds: _skid(ds, "start"),
        ),
        Value(
            "skid_end_time",
            "s",
            "last time the cage lags its rolling speed by more than the skidding threshold",
            lambda ds: _skid(ds, "end"),
        ),
        Value(
            "skid_warnings",
            "",
            'number of "the cage skids" warnings the result gives',
            _skid_warnings,
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
        entries += [
            Value(
                f"{race}_band_thickness_{which}_phase",
                "deg",
                f"{race} track band thickness over the {which} phase of the run (dynamic)",
                lambda ds, r=race, k=index: _phase_metric(ds, "band_thickness", k, r),
            )
            for which, index in (("first", 0), ("last", -1))
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
