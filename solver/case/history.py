"""Operating keys given as functions of time: the case forms of a time history, their validation
and their values (case units, times in seconds).

An ``[operating]`` key whose :class:`~solver.case.schema.Field` has ``history=True`` may be a
number (steady) or an inline table of one of these forms (docs/case-format.md, "Time histories"),
values in the key's own unit:

- ``{ ramp = { from = A, to = B, start_s = 0, duration_s = T }, interpolation = "linear" }``
- ``{ step = { from = A, to = B, at_s = T } }``
- ``{ sine = { mean = M, amplitude = A, frequency_Hz = F, phase_deg = 0 } }``
- ``{ table = [[t0, v0], [t1, v1], ...], interpolation = "linear" }``
- ``{ file = "spectrum.csv", column = "radial_load_N", interpolation = "linear" }``
- ``radial_load_angle_deg`` only: ``{ rotating = "with_shaft", start_deg = 0 }`` (the load turns
  with the inner ring) or ``{ rotating_rpm = N, start_deg = 0 }`` (it turns in space at N rpm).

Each form becomes a :class:`KeyHistory`: knots (time, value) with linear or smooth segments, a
sine and a rate, in case units; :meth:`KeyHistory.channel` gives the SI
:class:`solver.history.ChannelHistory` the models read (solver.inputs). Before the first knot the
value is the first knot's, after the last the last knot's.
"""

from __future__ import annotations

import csv
import io
import math
import os
import stat
from dataclasses import dataclass
from pathlib import Path

from solver.errors import Problem
from solver.history import (
    SEGMENT_LINEAR,
    SEGMENT_SMOOTH,
    ChannelHistory,
    channel_value,
    history_record,
)

from .messages import _unknown_in_table, show
from .schema import field, format_number

#: The form keys, in the order the docs give them.
FORMS = ("ramp", "step", "sine", "table", "file", "rotating", "rotating_rpm")
#: Forms of the radial load's angle only (a load turning with the shaft or in space).
ROTATING_FORMS = ("rotating", "rotating_rpm")
#: The keys each form's table may hold besides the form key.
FORM_EXTRAS = {
    "ramp": ("interpolation",),
    "step": (),
    "sine": (),
    "table": ("interpolation",),
    "file": ("column", "interpolation"),
    "rotating": ("start_deg",),
    "rotating_rpm": ("start_deg",),
}
#: The keys inside the inline table of a form: (name, required) ; a missing optional one is 0.
FORM_PARAMETERS = {
    "ramp": (("from", True), ("to", True), ("start_s", False), ("duration_s", True)),
    "step": (("from", True), ("to", True), ("at_s", True)),
    "sine": (("mean", True), ("amplitude", True), ("frequency_Hz", True), ("phase_deg", False)),
}
INTERPOLATIONS = ("linear", "smooth")
#: The column of a history file that holds the times, in seconds.
TIME_COLUMN = "time_s"
#: Most knots of one history (a table or a file): a load spectrum of a few thousand points is
#: typical; the limit keeps a wrong file from filling the memory.
MAX_KNOTS = 100_000
#: Largest history file read, in bytes.
MAX_FILE_BYTES = 20_000_000


@dataclass(frozen=True)
class KeyHistory:
    """One operating key's history, case units (the key's unit; times in s).

    ``spec``: the inline table as written (written back by the case writer); ``times``/``values``
    the knots (times non-decreasing, two equal times = a step); ``smooth``: smooth (C1) segments
    instead of linear; ``amplitude`` [key unit], ``frequency`` [Hz], ``phase`` [rad] of a sine and
    ``rate`` [key unit / s] added to the table; ``with_shaft``: the radial load's angle is measured
    in the inner ring's frame (the load turns with the shaft). ``file``: the history file's path
    as read, "" for the other forms.
    """

    key: str
    form: str
    spec: dict
    times: tuple[float, ...]
    values: tuple[float, ...]
    smooth: bool = False
    amplitude: float = 0.0
    frequency: float = 0.0
    phase: float = 0.0
    rate: float = 0.0
    with_shaft: bool = False

    def channel(self, scale: float = 1.0) -> ChannelHistory:
        """The :class:`solver.history.ChannelHistory` of this history with its values multiplied
        by ``scale`` (the SI value of one unit of the key: ``solver.units``)."""
        kind = SEGMENT_SMOOTH if self.smooth else SEGMENT_LINEAR
        return ChannelHistory(
            tuple(float(t) for t in self.times),
            tuple(float(v) * scale for v in self.values),
            (kind,) * len(self.times),
            self.amplitude * scale,
            self.frequency,
            self.phase,
            self.rate * scale,
        )

    @property
    def knot_extremes(self) -> tuple[float, float]:
        """(lowest, highest) value of the knots widened by the sine amplitude (key unit): the range
        of the history wherever it holds no rate."""
        return (min(self.values) - self.amplitude, max(self.values) + self.amplitude)

    def value_at(self, t: float) -> float:
        """The value at time ``t`` [s] (key unit)."""
        record = history_record({0: self.channel()}, {c: 0.0 for c in range(1, 9)})
        return float(channel_value(record, 0, float(t)))

    def fingerprint(self) -> dict:
        """What a result depends on (solver.results.provenance): the knots, segments, sine, rate
        and frame, not how they were written."""
        return {
            "times": list(self.times),
            "values": list(self.values),
            "smooth": self.smooth,
            "sine": [self.amplitude, self.frequency, self.phase],
            "rate": self.rate,
            "with_shaft": self.with_shaft,
        }

    def describe(self, unit: str) -> str:
        """The history in words, engineering units: its form, its range and its events."""
        u = f" {unit}" if unit else ""
        shape = "smooth" if self.smooth else "linear"
        if self.form == "rotating":
            return f"turns with the shaft (inner ring), from {_g(self.values[0])}{u}"
        if self.form == "rotating_rpm":
            rpm = self.rate * 60.0 / 360.0
            return f"turns in space at {_g(rpm)} rpm, from {_g(self.values[0])}{u}"
        if self.form == "sine":
            return (
                f"sine: mean {_g(self.values[0])}{u}, amplitude {_g(self.amplitude)}{u}, "
                f"{_g(self.frequency)} Hz, phase {_g(math.degrees(self.phase))} deg"
            )
        low, high = self.knot_extremes
        if self.form == "step":
            text = f"step from {_g(self.values[0])} to {_g(self.values[-1])}{u}"
            return f"{text} at {_g(self.times[0])} s"
        if self.form == "ramp":
            return (
                f"{shape} ramp from {_g(self.values[0])} to {_g(self.values[-1])}{u}, "
                f"{_g(self.times[0])} s to {_g(self.times[-1])} s"
            )
        where = f"file {self.spec.get('file')}, " if self.form == "file" else ""
        steps = sum(1 for a, b in zip(self.times, self.times[1:], strict=False) if a == b)
        step_text = f", {steps} step{'s' if steps != 1 else ''}" if steps else ""
        return (
            f"{where}table of {len(self.times)} points ({shape}) from {_g(self.times[0])} s to "
            f"{_g(self.times[-1])} s, {_g(low)} to {_g(high)}{u}{step_text}"
        )


def _g(value: float) -> str:
    return f"{value:.6g}"


# ---- reading a form ------------------------------------------------------------------------------
class _Bad(Exception):
    """A problem already recorded: stop reading this history."""


def _number(problems, key: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        problems.append(
            Problem(key, f"{key} = {show(value)}: must be a number (write numbers without quotes)")
        )
        raise _Bad
    value = float(value)
    if not math.isfinite(value):
        problems.append(Problem(key, f"{key} = {show(value)}: must be a finite number"))
        raise _Bad
    return value


def _at_least(problems, key: str, value: float, low: float, strict: bool, why: str) -> None:
    if value < low or (strict and value == low):
        word = "greater than" if strict else "at least"
        problems.append(Problem(key, f"{key} = {show(value)}: must be {word} {low:g} ({why})"))
        raise _Bad


def _unknown(problems, key: str, name: str, value, allowed) -> None:
    _unknown_in_table(problems, key, name, value, list(allowed))
    raise _Bad


def _interpolation(problems, key: str, table: dict) -> bool:
    value = table.get("interpolation", "linear")
    if value not in INTERPOLATIONS:
        problems.append(
            Problem(
                f"{key}.interpolation",
                f"{key}.interpolation = {show(value)}: must be "
                + " or ".join(f'"{i}"' for i in INTERPOLATIONS)
                + " (straight segments between the points, or smooth C1 steps)",
            )
        )
        raise _Bad
    return value == "smooth"


def _parameters(problems, key: str, form: str, table) -> dict:
    """The numbers of a ramp, step or sine (missing optional ones 0)."""
    names = FORM_PARAMETERS[form]
    where = f"{key}.{form}"
    example = "{ " + ", ".join(f"{n} = ..." for n, _ in names) + " }"
    if not isinstance(table, dict):
        problems.append(
            Problem(where, f"{where} = {show(table)}: must be an inline table {example}")
        )
        raise _Bad
    allowed = [n for n, _ in names]
    for name, value in table.items():
        if name not in allowed:
            _unknown(problems, where, name, value, allowed)
    out = {}
    for name, required in names:
        if name not in table:
            if required:
                problems.append(
                    Problem(f"{where}.{name}", f"{where}.{name} is missing: give {example}")
                )
                raise _Bad
            out[name] = 0.0
            continue
        out[name] = _number(problems, f"{where}.{name}", table[name])
    return out


def _knots(problems, key: str, rows, where: str) -> tuple[tuple, tuple]:
    """Times and values of (time, value) rows: times at least 0, never decreasing, at most two
    equal (a step)."""
    if not rows:
        problems.append(Problem(key, f"{where} has no points: give at least one (time, value)"))
        raise _Bad
    if len(rows) > MAX_KNOTS:
        problems.append(
            Problem(key, f"{where} has {len(rows)} points: at most {MAX_KNOTS:,} are read")
        )
        raise _Bad
    times, values = [], []
    for i, (t, v) in enumerate(rows):
        if t < 0.0:
            problems.append(
                Problem(
                    key,
                    f"{where}: point {i + 1} is at t = {t:g} s: times start at 0 (the start of "
                    "the run)",
                )
            )
            raise _Bad
        if times and t < times[-1]:
            problems.append(
                Problem(
                    key,
                    f"{where}: the times must not decrease, but point {i + 1} (t = {t:g} s) comes "
                    f"after t = {times[-1]:g} s; sort the points by time",
                )
            )
            raise _Bad
        if len(times) >= 2 and t == times[-1] == times[-2]:
            problems.append(
                Problem(
                    key,
                    f"{where}: three points at t = {t:g} s; two points at one time are a step, a "
                    "third is ambiguous: remove one",
                )
            )
            raise _Bad
        times.append(t)
        values.append(v)
    return tuple(times), tuple(values)


def _table_rows(problems, key: str, table) -> list:
    where = f"{key}.table"
    if not isinstance(table, list):
        problems.append(
            Problem(
                where,
                f"{where} = {show(table)}: must be a list of [time_s, value] pairs, e.g. "
                "[[0, 100], [0.1, 300]]",
            )
        )
        raise _Bad
    rows = []
    for i, row in enumerate(table):
        if not isinstance(row, list) or len(row) != 2:
            problems.append(
                Problem(
                    where,
                    f"{where}: point {i + 1} = {show(row)} must be a pair [time_s, value]",
                )
            )
            raise _Bad
        rows.append(
            (
                _number(problems, f"{where}[{i + 1}][1]", row[0]),
                _number(problems, f"{where}[{i + 1}][2]", row[1]),
            )
        )
    return rows


def read_history_file(path: Path, column: str, key: str, problems) -> list:
    """(time, value) rows of the ``column`` of the CSV file at ``path`` (a header row, then one
    row per time; the times in :data:`TIME_COLUMN`). Records a problem naming the file, the row and
    the column, and raises :class:`_Bad`, for a missing or unreadable file or a bad value."""
    where = f"{key}.file"

    def bad(message: str):
        problems.append(Problem(where, f"{where} = {str(path)!r}: {message}"))
        raise _Bad

    try:
        info = os.stat(path)
    except FileNotFoundError:
        bad("file not found; a history file lies next to the case file (or give its path)")
    except OSError as error:
        bad(f"cannot read it ({error.strerror})")
    if not stat.S_ISREG(info.st_mode):
        bad("not a regular file: give a CSV file saved on disk")
    if info.st_size > MAX_FILE_BYTES:
        bad(f"larger than {MAX_FILE_BYTES // 1_000_000} MB; a history file holds a CSV table")
    try:
        raw = path.read_bytes()[: MAX_FILE_BYTES + 1]
        text = raw.decode("utf-8-sig")
    except OSError as error:
        bad(f"cannot read it ({error.strerror})")
    except UnicodeDecodeError:
        bad("not UTF-8 text; save the table as a CSV text file")
    reader = csv.reader(io.StringIO(text))
    rows = [row for row in reader if row and any(cell.strip() for cell in row)]
    if not rows:
        bad(f"the file is empty; it needs a header row ({TIME_COLUMN},{column}) and data rows")
    header = [cell.strip() for cell in rows[0]]
    for name in (TIME_COLUMN, column):
        if name not in header:
            bad(
                f"no column {name!r} in the header row ({', '.join(header)}); the first row names "
                f"the columns: {TIME_COLUMN} and the key's column (set it with column = ...)"
            )
    it, iv = header.index(TIME_COLUMN), header.index(column)
    out = []
    for number, row in enumerate(rows[1:], start=2):
        cells = []
        for index, name in ((it, TIME_COLUMN), (iv, column)):
            cell = row[index].strip() if index < len(row) else ""
            try:
                value = float(cell)
            except ValueError:
                value = math.nan
            if not math.isfinite(value):
                bad(f"row {number}, column {name}: {cell!r} is not a finite number")
            cells.append(value)
        out.append(tuple(cells))
    if not out:
        bad("the file has a header row but no data rows")
    return out


def parse_history(f, raw: dict, base_dir: Path | None, problems: list) -> KeyHistory | None:
    """The :class:`KeyHistory` of the inline table ``raw`` given for the key of the Field ``f``;
    None after recording every problem found in ``problems``. ``base_dir``: the case file's folder
    (a history file's path is relative to it; None: the case has no folder)."""
    try:
        history = _parse(f, raw, base_dir, problems)
    except _Bad:
        return None
    return history if _within_bounds(f, raw, history, problems) else None


def _parse(f, raw: dict, base_dir: Path | None, problems: list) -> KeyHistory:
    key = f.key
    forms = [name for name in FORMS if name in raw]
    allowed_forms = FORMS if f.name == "radial_load_angle_deg" else FORMS[:-2]
    shown = ", ".join(allowed_forms)
    if len(forms) != 1:
        have = "none" if not forms else " and ".join(forms)
        problems.append(
            Problem(
                key,
                f"{key} = {show(raw)}: a history gives exactly one of {shown} (it gives {have}); "
                "docs/case-format.md shows each form",
            )
        )
        raise _Bad
    form = forms[0]
    if form not in allowed_forms:
        problems.append(
            Problem(
                key,
                f"{key} = {show(raw)}: {form} is a form of operating.radial_load_angle_deg only "
                "(a rotating radial load); give this key as one of " + shown,
            )
        )
        raise _Bad
    allowed = (form,) + FORM_EXTRAS[form]
    for name, value in raw.items():
        if name not in allowed:
            _unknown(problems, key, name, value, allowed)
    spec = raw
    if form == "ramp":
        smooth = _interpolation(problems, key, raw)
        p = _parameters(problems, key, form, raw["ramp"])
        _at_least(problems, f"{key}.ramp.start_s", p["start_s"], 0.0, False, "times start at 0")
        _at_least(
            problems,
            f"{key}.ramp.duration_s",
            p["duration_s"],
            0.0,
            True,
            "a ramp takes some time; a change at once is a step",
        )
        t0, t1 = p["start_s"], p["start_s"] + p["duration_s"]
        return KeyHistory(key, form, spec, (t0, t1), (p["from"], p["to"]), smooth)
    if form == "step":
        p = _parameters(problems, key, form, raw["step"])
        _at_least(problems, f"{key}.step.at_s", p["at_s"], 0.0, False, "times start at 0")
        t = p["at_s"]
        return KeyHistory(key, form, spec, (t, t), (p["from"], p["to"]))
    if form == "sine":
        p = _parameters(problems, key, form, raw["sine"])
        _at_least(
            problems,
            f"{key}.sine.amplitude",
            p["amplitude"],
            0.0,
            False,
            "the phase sets the sign; give a non-negative amplitude",
        )
        _at_least(
            problems,
            f"{key}.sine.frequency_Hz",
            p["frequency_Hz"],
            0.0,
            True,
            "a constant value is a number, not a sine",
        )
        return KeyHistory(
            key,
            form,
            spec,
            (0.0,),
            (p["mean"],),
            amplitude=p["amplitude"],
            frequency=p["frequency_Hz"],
            phase=math.radians(p["phase_deg"]),
        )
    if form in ("table", "file"):
        smooth = _interpolation(problems, key, raw)
        if form == "table":
            rows = _table_rows(problems, key, raw["table"])
            where = f"{key}.table"
        else:
            name = raw["file"]
            column = raw.get("column", f.name)
            if not isinstance(name, str) or not name.strip():
                problems.append(
                    Problem(
                        f"{key}.file",
                        f"{key}.file = {show(name)}: must be the name of a CSV file in quotes",
                    )
                )
                raise _Bad
            if not isinstance(column, str) or not column.strip():
                problems.append(
                    Problem(
                        f"{key}.column",
                        f"{key}.column = {show(column)}: must be a column name in quotes",
                    )
                )
                raise _Bad
            path = Path(name)
            if not path.is_absolute():
                if base_dir is None:
                    problems.append(
                        Problem(
                            f"{key}.file",
                            f"{key}.file = {show(name)}: this case was not read from a file, so "
                            "there is no folder to find the history file in; load the case from "
                            "its file (racetrace CASE.toml), or give the table inline "
                            "(table = [[time_s, value], ...])",
                        )
                    )
                    raise _Bad
                path = Path(base_dir) / path
            rows = read_history_file(path, column, key, problems)
            where = f"{key}.file {name!r}, column {column!r}"
        times, values = _knots(problems, key, rows, where)
        return KeyHistory(key, form, spec, times, values, smooth)
    # the rotating forms: an angle that grows with the shaft's or at a given speed
    start = 0.0
    if "start_deg" in raw:
        start = _number(problems, f"{key}.start_deg", raw["start_deg"])
    if form == "rotating":
        if raw["rotating"] != "with_shaft":
            problems.append(
                Problem(
                    f"{key}.rotating",
                    f'{key}.rotating = {show(raw["rotating"])}: must be "with_shaft" (the load '
                    "turns with the inner ring); for a load turning in space at its own speed "
                    "give rotating_rpm = N instead",
                )
            )
            raise _Bad
        return KeyHistory(key, form, spec, (0.0,), (start,), with_shaft=True)
    rpm = _number(problems, f"{key}.rotating_rpm", raw["rotating_rpm"])
    top = field("operating.inner_ring_speed_rpm").maximum
    if abs(rpm) > top:
        problems.append(
            Problem(
                f"{key}.rotating_rpm",
                f"{key}.rotating_rpm = {show(rpm)}: must be within ±{format_number(top)} rpm, the "
                "bounds of the ring speeds",
            )
        )
        raise _Bad
    return KeyHistory(key, form, spec, (0.0,), (start,), rate=rpm * 360.0 / 60.0)


def _within_bounds(f, raw, history: KeyHistory, problems: list) -> bool:
    """Every knot (and a sine's extremes) within the key's bounds; a rotating angle's start only
    (the angle grows without bound)."""
    unit = f" {f.unit}" if f.unit else ""
    points = list(zip(history.times, history.values, strict=True))
    if history.form in ROTATING_FORMS:
        points = points[:1]
    checks = []
    for t, v in points:
        for sign in (-1.0, 1.0) if history.amplitude else (0.0,):
            checks.append((t, v + sign * history.amplitude, sign))
    for t, value, sign in checks:
        low = f.minimum is not None and (
            value < f.minimum if f.minimum_inclusive else value <= f.minimum
        )
        high = f.maximum is not None and (
            value > f.maximum if f.maximum_inclusive else value >= f.maximum
        )
        if not (low or high):
            continue
        what = (
            f"the sine reaches {format_number(value)}{unit} (mean {'-' if sign < 0 else '+'} "
            "amplitude)"
            if sign
            else f"its value at t = {t:g} s is {format_number(value)}{unit}"
        )
        if low:
            word = "at least" if f.minimum_inclusive else "greater than"
            bound, reason = f.minimum, f.reason
        else:
            word = "at most" if f.maximum_inclusive else "less than"
            bound, reason = f.maximum, f.reason_high or f.reason
        why = f" ({reason})" if reason else ""
        problems.append(
            Problem(
                f.key,
                f"{f.key} = {show(raw)}: {what}; the value must be {word} "
                f"{format_number(bound)}{unit} at every time of the history{why}",
            )
        )
        return False
    return True


__all__ = [
    "FORMS",
    "INTERPOLATIONS",
    "TIME_COLUMN",
    "KeyHistory",
    "parse_history",
    "read_history_file",
]
