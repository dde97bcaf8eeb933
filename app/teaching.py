"""What the 3-D view says in words: the operating point, revolution counter, slow motion, a note.

Pure functions of a result's coordinates (results-schema.md) and of the animation settings; no
rendering. Angles in rad, speeds in rad/s, times in s, loads in N.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class Facts:
    """The operating point of a result, as the teaching overlay needs it."""

    model: str  # "quasistatic" | "dynamic"
    inner_ring_speed: float  # rad/s about +x
    outer_ring_speed: float  # rad/s about +x
    axial_load: float  # N
    radial_load: float  # N
    radial_load_angle: float  # rad, from +y towards +z
    misalignment: float  # rad
    misalignment_axis: float  # rad, azimuth of the tilt axis (at t = 0 when turning)
    misalignment_frame: str  # "space" | "ring"

    @property
    def shaft_period(self) -> float:
        """Seconds per revolution of the inner ring relative to the outer ring (inf at rest)."""
        w = abs(self.inner_ring_speed - self.outer_ring_speed)
        return TWO_PI / w if w > 0 else math.inf

    @property
    def misalignment_turns(self) -> bool:
        return self.misalignment_frame == "ring"


#: Fields of :class:`Facts` whose coordinates are in degree (results-schema.md).
_DEGREE_FIELDS = frozenset({"radial_load_angle", "misalignment", "misalignment_axis"})


def facts_from_result(ds) -> Facts:
    """:class:`Facts` from a results Dataset's describing coordinates, one per field of the same
    name; an input that varies along a time history is a data variable over ``time``
    (results-schema.md) and gives its value at the end of the run, as the lessons quote it
    (ValueError naming what is missing)."""
    names = [f.name for f in fields(Facts) if f.name != "model"]
    missing = [n for n in names if n not in ds.coords and n not in ds.data_vars]
    if missing:
        raise ValueError(
            f"the result lacks the coordinates {', '.join(missing)} (results-schema.md); "
            "run the case again with this version"
        )

    def value(name):
        if name in ds.coords:
            values = ds.coords[name].values
            scalar = values.flat[0] if values.ndim else values.item()
        else:
            scalar = ds[name].values.flat[-1]  # varies in time: the end of the run
        if name == "misalignment_frame":
            return str(scalar)
        return math.radians(float(scalar)) if name in _DEGREE_FIELDS else float(scalar)

    model = str(ds.attrs.get("model", "dynamic" if "time" in ds.dims else "quasistatic"))
    return Facts(model=model, **{name: value(name) for name in names})


def _duration_words(seconds: float) -> str:
    """'1 ms', '250 us', '2.5 s': a duration with a unit that keeps the number readable."""
    for unit, scale in (("s", 1.0), ("ms", 1e-3), ("µs", 1e-6)):
        shown = float(f"{seconds / scale:.3g}")  # as printed: 999.99 µs is printed as 1 ms
        if shown >= 1.0 or unit == "µs":
            return f"{shown:g} {unit}"
    return f"{seconds:.3g} s"  # pragma: no cover


def slow_motion_words(bearing_seconds_per_screen_second: float) -> str:
    """'1 s on screen = 1.2 ms of bearing time' for a playback rate (bearing s per screen s)."""
    if not bearing_seconds_per_screen_second > 0:
        return ""
    return f"1 s on screen = {_duration_words(bearing_seconds_per_screen_second)} of bearing time"


def playback_rate(frame_step_s: float, frames_per_tick: int, ticks_per_second: float) -> float:
    """Bearing seconds shown per screen second: time per frame x frames per tick x ticks/s."""
    return float(frame_step_s) * int(frames_per_tick) * float(ticks_per_second)


def revolution_words(time: float, facts: Facts, total_time: float | None = None) -> str:
    """'revolution 2.4 of 6' (shaft revolutions relative to the outer ring since t = 0)."""
    period = facts.shaft_period
    if not math.isfinite(period):
        return "rings at rest"
    done = time / period
    if total_time is None:
        return f"revolution {done:.1f}"
    return f"revolution {done:.1f} of {total_time / period:.3g}"


def what_you_see(facts: Facts, exaggeration: float = 1.0, ellipse_scale: float = 1.0) -> str:
    """A short note on what the 3-D view shows for this operating point."""
    parts = [
        "Each raceway is painted where the contact ellipses (blue) ran: the colour is how long "
        "a point spent under a ball (dwell) or the highest pressure it saw. Black lines: the "
        "shoulder edges; blue line: the groove bottom. The outer ring is drawn apart and opened "
        "so that its raceway shows from inside."
    ]
    if facts.model == "quasistatic":
        parts.append(
            "This is the quasi-static preview: every ball repeats the steady load zone, so tracks "
            "are ideal lines; run the dynamic model to see the real spread."
        )
    fixed_to_inner = facts.misalignment != 0.0 and facts.misalignment_turns
    fixed_in_space = facts.radial_load != 0.0 or (
        facts.misalignment != 0.0 and not facts.misalignment_turns
    )
    if fixed_to_inner and not fixed_in_space:
        parts.append(
            "The tilt turns with the inner ring: the inner track is a thin line that wanders "
            "across its groove, the outer track a band."
        )
    elif fixed_in_space and not fixed_to_inner:
        parts.append(
            "The load (or tilt) is fixed in space: the outer track is a thin line, the inner "
            "track, which turns under the load, a band."
        )
    elif not fixed_to_inner and not fixed_in_space:
        parts.append("Pure axial load: every ball runs on the same circle on both raceways.")
    if exaggeration != 1.0:
        parts.append(f"Across-groove deviations are drawn {exaggeration:g}x larger than true.")
    if ellipse_scale != 1.0:
        parts.append(f"Ellipses are drawn {ellipse_scale:g}x their true size.")
    return " ".join(parts)
