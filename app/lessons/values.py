"""The numbers a lesson's text may quote, computed from a results Dataset (results-schema.md).

:data:`VALUES` is the registry: each value has a name (the placeholder in a lesson template), its
unit as shown after the number, a one-line meaning (listed in docs/lessons.md, which a test keeps
true) and the function that computes it. :func:`lesson_values` evaluates all of them for one
result. They read only the Dataset, its coordinates, ``ds.racetrace.summary()`` and
``ds.racetrace.warnings()``: never the case text.

Conventions: angles in degree, loads in N, pressures in GPa, lengths of ellipses in mm, speeds in
rev/min. Averages run over loaded contacts (``contact_load`` > 0) and, for a dynamic run, over its
analysed window (from ``analysis_start_time`` on, solver.results.summary); minima and maxima over
the same samples. A value the result does not have (the gyroscopic moment of a dynamic run, the
band thickness of a quasi-static snapshot) is ``None``; the template then says so in words.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import xarray as xr

RPM = 2.0 * math.pi / 60.0  # rad/s per rev/min
RACES = ("inner", "outer")
FRAME_OF = {"inner": "inner_ring", "outer": "outer_ring"}


@dataclass(frozen=True)
class Value:
    """One quotable number (or word): ``unit`` is shown after it in docs/lessons.md."""

    name: str
    unit: str
    meaning: str
    compute: Callable[[xr.Dataset, xr.Dataset], object]  # (result, its analysed window)


# ---- reading the Dataset -------------------------------------------------------------------------
def _window(ds: xr.Dataset) -> xr.Dataset:
    """The analysed window of a dynamic result (the whole result for a quasi-static one)."""
    if "time" not in ds.dims:
        return ds
    summary = ds.racetrace.summary()
    start = float(summary["analysis_start_time"]) if "analysis_start_time" in summary else 0.0
    return ds.sel(time=ds["time"] >= start - 1e-12)


def _contacts(window: xr.Dataset, name: str, race: str, loaded_only: bool = True) -> np.ndarray:
    """Values of a per-contact variable on one race in the analysed ``window``, flattened."""
    values = np.asarray(window[name].sel(race=race).values, dtype=float).ravel()
    if loaded_only:
        load = np.asarray(window["contact_load"].sel(race=race).values, dtype=float).ravel()
        values = values[load > 0.0]
    return values[np.isfinite(values)]


def _stat(ds, name, race, how, scale=1.0, loaded_only=True):
    values = _contacts(ds, name, race, loaded_only)
    if values.size == 0:
        return None
    return float(getattr(np, how)(values)) * scale


def _summary_metric(ds, metric: str, race: str):
    summary = ds.racetrace.summary()
    value = float(summary[metric].sel(race=race, frame=FRAME_OF[race]))
    return value if math.isfinite(value) else None


def _mean_var(ds, name: str, scale=1.0):
    if name not in ds:
        return None
    values = np.asarray(ds[name].values, dtype=float)
    values = values[np.isfinite(values)]
    return float(values.mean()) * scale if values.size else None


def _coord(ds, name: str, scale=1.0):
    return float(ds.coords[name]) * scale


def epicyclic_cage_speed(ds: xr.Dataset) -> float:
    """Cage speed of pure rolling at the free contact angle alpha_0 (rad/s):
    (omega_i (1 - gamma) + omega_o (1 + gamma)) / 2 with gamma = D cos(alpha_0) / d_m."""
    gamma = (
        _coord(ds, "ball_diameter")
        * math.cos(math.radians(_coord(ds, "free_contact_angle")))
        / _coord(ds, "pitch_diameter")
    )
    inner, outer = _coord(ds, "inner_ring_speed"), _coord(ds, "outer_ring_speed")
    return 0.5 * (inner * (1.0 - gamma) + outer * (1.0 + gamma))


def _centrifugal_force(ds):
    """Mean ball centrifugal force (N): the quasi-static result's own, else m (d_m / 2) omega_c^2
    with the ball's mass from its density and diameter and the mean orbital speed."""
    if "centrifugal_force" in ds:
        return _mean_var(ds, "centrifugal_force")
    if "orbital_speed" not in ds:
        return None
    density = float(ds.coords["density"].sel(body="ball"))
    mass = density * math.pi * _coord(ds, "ball_diameter") ** 3 / 6.0
    orbital = _mean_var(ds, "orbital_speed")
    return mass * 0.5 * _coord(ds, "pitch_diameter") * orbital**2


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


def _loaded_balls(window):
    """Balls carrying load on the inner race; for a dynamic run the median count per sample."""
    load = window["contact_load"].sel(race="inner")
    if "time" in load.dims:
        counts = (load > 0.0).sum("ball").values
        return int(round(float(np.median(counts))))
    return int((load > 0.0).sum())


def _truncated_contacts(window):
    """(ball, race) contacts whose ellipse runs over the shoulder at least once."""
    if "truncation_margin" not in window:
        return 0
    over = (window["truncation_margin"] < 0.0) & (window["contact_load"] > 0.0)
    if "time" in over.dims:
        over = over.any("time")
    return int(over.sum())


def _min_margin(ds, race):
    values = _contacts(ds, "truncation_margin", race)
    return float(values.min()) if values.size else None


def _pressure_limit(ds):
    from solver import STATIC_PRESSURE_LIMIT

    return STATIC_PRESSURE_LIMIT * 1e-9


def _misalignment_frame(ds):
    frame = str(ds.coords["misalignment_frame"].values)
    return "turning with the inner ring" if frame == "ring" else "fixed in space"


def _cage_speed_rpm(ds):
    return _mean_var(ds, "cage_speed", 1.0 / RPM)


def _cage_slip(ds):
    """Percent by which the cage runs slower than the epicyclic value (negative: faster)."""
    cage = _mean_var(ds, "cage_speed")
    epicyclic = epicyclic_cage_speed(ds)
    if cage is None or epicyclic == 0.0:
        return None
    return 100.0 * (1.0 - cage / epicyclic)


def _revolutions(ds):
    if "time" not in ds.dims:
        return None
    relative = abs(_coord(ds, "inner_ring_speed") - _coord(ds, "outer_ring_speed"))
    return float(ds["time"].values[-1]) * relative / (2.0 * math.pi)


def _registry() -> dict[str, Value]:
    entries = [
        Value(
            "speed_rpm",
            "rpm",
            "inner-ring (shaft) speed",
            lambda ds, w: _coord(ds, "inner_ring_speed", 1.0 / RPM),
        ),
        Value(
            "axial_load",
            "N",
            "axial load on the inner ring",
            lambda ds, w: _coord(ds, "axial_load"),
        ),
        Value(
            "radial_load",
            "N",
            "radial load on the inner ring",
            lambda ds, w: _coord(ds, "radial_load"),
        ),
        Value(
            "misalignment",
            "deg",
            "imposed tilt of the inner ring",
            lambda ds, w: _coord(ds, "misalignment"),
        ),
        Value(
            "misalignment_frame",
            "",
            '"fixed in space" or "turning with the inner ring"',
            lambda ds, w: _misalignment_frame(ds),
        ),
        Value(
            "free_contact_angle",
            "deg",
            "contact angle of the unloaded bearing",
            lambda ds, w: _coord(ds, "free_contact_angle"),
        ),
        Value("ball_count", "", "number of balls", lambda ds, w: int(ds.coords["ball_count"])),
        Value(
            "shaft_revolutions",
            "",
            "shaft revolutions the dynamic run covers",
            lambda ds, w: _revolutions(ds),
        ),
        Value(
            "centrifugal_force",
            "N",
            "mean centrifugal force on one ball",
            lambda ds, w: _centrifugal_force(w),
        ),
        Value(
            "gyroscopic_moment",
            "mN m",
            "mean gyroscopic moment on one ball (quasi-static)",
            lambda ds, w: _mean_var(w, "gyroscopic_moment", 1e3),
        ),
        Value(
            "race_control",
            "",
            'the raceway that "controls" the ball (quasi-static)',
            lambda ds, w: _race_control(ds),
        ),
        Value(
            "loaded_balls", "", "balls carrying load (inner race)", lambda ds, w: _loaded_balls(w)
        ),
        Value("cage_speed_rpm", "rpm", "mean cage speed", lambda ds, w: _cage_speed_rpm(w)),
        Value(
            "epicyclic_cage_speed_rpm",
            "rpm",
            "cage speed of pure rolling at the free contact angle",
            lambda ds, w: epicyclic_cage_speed(ds) / RPM,
        ),
        Value(
            "cage_slip",
            "%",
            "how much slower than epicyclic the cage runs (negative: faster)",
            lambda ds, w: _cage_slip(w),
        ),
        Value(
            "max_pressure",
            "GPa",
            "highest peak contact pressure on either race",
            lambda ds, w: max(
                (
                    p
                    for p in (_stat(w, "max_pressure", r, "max", 1e-9) for r in RACES)
                    if p is not None
                ),
                default=None,
            ),
        ),
        Value(
            "pressure_limit",
            "GPa",
            "static pressure limit (ISO 76) the warnings use",
            lambda ds, w: _pressure_limit(ds),
        ),
        Value(
            "truncated_contacts",
            "",
            "ball-race contacts whose ellipse runs over the shoulder",
            lambda ds, w: _truncated_contacts(w),
        ),
        Value(
            "warning_count",
            "",
            "number of warnings the result gives",
            lambda ds, w: len(ds.racetrace.warnings()),
        ),
    ]
    for race in RACES:
        entries += [
            Value(
                f"{race}_contact_angle",
                "deg",
                f"mean {race} contact angle",
                lambda ds, w, r=race: _stat(w, "contact_angle", r, "mean"),
            ),
            Value(
                f"{race}_contact_angle_min",
                "deg",
                f"smallest {race} contact angle",
                lambda ds, w, r=race: _stat(w, "contact_angle", r, "min"),
            ),
            Value(
                f"{race}_contact_angle_max",
                "deg",
                f"largest {race} contact angle",
                lambda ds, w, r=race: _stat(w, "contact_angle", r, "max"),
            ),
            Value(
                f"{race}_load",
                "N",
                f"mean {race} contact load (loaded contacts)",
                lambda ds, w, r=race: _stat(w, "contact_load", r, "mean"),
            ),
            Value(
                f"{race}_load_max",
                "N",
                f"largest {race} contact load",
                lambda ds, w, r=race: _stat(w, "contact_load", r, "max"),
            ),
            Value(
                f"{race}_load_min",
                "N",
                f"smallest {race} contact load (0 when a ball is unloaded)",
                lambda ds, w, r=race: _stat(w, "contact_load", r, "min", loaded_only=False),
            ),
            Value(
                f"{race}_pressure",
                "GPa",
                f"highest {race} peak contact pressure",
                lambda ds, w, r=race: _stat(w, "max_pressure", r, "max", 1e-9),
            ),
            Value(
                f"{race}_semi_major",
                "mm",
                f"mean {race} ellipse semi-axis across the groove",
                lambda ds, w, r=race: _stat(w, "ellipse_semi_major", r, "mean", 1e3),
            ),
            Value(
                f"{race}_semi_minor",
                "mm",
                f"mean {race} ellipse semi-axis along the rolling direction",
                lambda ds, w, r=race: _stat(w, "ellipse_semi_minor", r, "mean", 1e3),
            ),
            Value(
                f"{race}_spin_to_roll",
                "",
                f"mean {race} spin-to-roll ratio",
                lambda ds, w, r=race: _stat(w, "spin_to_roll", r, "mean"),
            ),
            Value(
                f"{race}_excursion",
                "deg",
                f"{race} track excursion in its own ring's frame",
                lambda ds, w, r=race: _summary_metric(ds, "trajectory_excursion", r),
            ),
            Value(
                f"{race}_band_thickness",
                "deg",
                f"{race} track band thickness in its own ring's frame (dynamic)",
                lambda ds, w, r=race: _summary_metric(ds, "trajectory_band_thickness", r),
            ),
            Value(
                f"{race}_truncation_margin",
                "deg",
                f"smallest margin between the {race} ellipse and the shoulder (negative: over it)",
                lambda ds, w, r=race: _min_margin(w, r),
            ),
        ]
    return {v.name: v for v in entries}


#: name -> Value, in the order docs/lessons.md lists them.
VALUES: dict[str, Value] = _registry()
VALUE_NAMES = frozenset(VALUES)


def lesson_values(ds: xr.Dataset) -> dict[str, object]:
    """Every value of :data:`VALUES` for one result (None where the result does not have it)."""
    out = {}
    window = _window(ds)
    for name, value in VALUES.items():
        result = value.compute(ds, window)
        if isinstance(result, float) and not math.isfinite(result):
            result = None
        out[name] = result
    return out


__all__ = ["VALUES", "VALUE_NAMES", "Value", "epicyclic_cage_speed", "lesson_values"]
