"""The ``[set]`` table of a case: bearings on a rigid shaft (docs/case-format.md, "Bearing sets").

A case with a ``[set]`` table describes a set of bearings on one rigid shaft: each
``[[set.bearing]]`` (or each bearing of a named ``arrangement``) has an axial position [mm] of its
ball-centre plane and a ``direction``, the axial direction ``"+x"`` or ``"-x"`` of the shaft thrust
it carries; its geometry is the case's ``[bearing]``, a catalogue bearing (``catalogue = NAME``) or
an inline ``bearing = {...}`` table of ``[bearing]`` keys. ``[set.load]`` holds the external force
``force_N = [x, y, z]`` and moment ``moment_Nm = [y, z]`` on the shaft at ``position_mm``
(``[operating]`` gives no loads in a set case); the ring speeds are those of ``[operating]`` for
every bearing.
``[set.preload]`` holds the preload: ``"none"``, a fixed position given by the preload force at
assembly (``"force"``, N) or the axial offset of the rings (``"offset"``, µm), or a spring force on
the outer rings of the bearings of one direction (``"spring"``).

This module reads and checks the table (:func:`read_set`), and writes it back
(:meth:`BearingSet.to_toml`); the defaults of its keys are defined here, once.
"""

from __future__ import annotations

import copy
import difflib
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

import tomli_w

import assets
from solver.errors import CaseError, Problem

#: The named arrangements: the directions of their bearings in order along +x. The letters follow
#: the matched-set designations of spindle-bearing catalogues: D/T/Q = two, three, four bearings;
#: B = back-to-back (O: the contact lines diverge towards the axis, so the pressure centres lie
#: outside the set), F = face-to-face (X: they converge), T = tandem (all carry thrust one way).
#: A bearing with direction "+x" has its contact line pointing from the axis towards +x, and its
#: pressure centre on its -x side: the first bearing of DB carries +x thrust, the last -x.
ARRANGEMENTS = {
    "DB": ("+x", "-x"),
    "DF": ("-x", "+x"),
    "DT": ("+x", "+x"),
    "TBT": ("+x", "+x", "-x"),  # a tandem pair back-to-back with one bearing
    "TFT": ("-x", "-x", "+x"),  # a tandem pair face-to-face with one bearing
    "QBC": ("+x", "+x", "-x", "-x"),  # two tandem pairs back-to-back
    "QFC": ("-x", "-x", "+x", "+x"),  # two tandem pairs face-to-face
}
DIRECTIONS = ("+x", "-x")
PRELOAD_KINDS = ("none", "force", "offset", "spring")

# ---- defaults of the [set] keys (docs/case-format.md) ---------------------------------------
DEFAULT_LOAD_POSITION_MM = 0.0  # the [operating] loads act at the shaft origin
DEFAULT_PRELOAD_KIND = "none"
DEFAULT_FORCE_N = (0.0, 0.0, 0.0)  # no external force
DEFAULT_MOMENT_NM = (0.0, 0.0)  # no external moment
MAX_MISALIGNMENT_DEG = 1.0  # largest imposed tilt of the shaft in the housing, per axis

_SET_KEYS = (
    "arrangement",
    "width_mm",
    "spacing_mm",
    "misalignment_deg",
    "load",
    "preload",
    "bearing",
)
_LOAD_KEYS = ("position_mm", "force_N", "moment_Nm")
_BEARING_KEYS = ("name", "position_mm", "direction", "catalogue", "bearing")
_PRELOAD_KEYS = ("kind", "force_N", "offset_um", "spring_side")
_LARGEST_SET = 8  # bearings in one set


@dataclass(frozen=True)
class SetBearing:
    """One bearing of the set. ``position_mm``: axial position of its ball-centre plane on the
    shaft [mm]; ``direction``: "+x" or "-x", the shaft thrust it carries; ``case``: the validated
    single-bearing :class:`solver.case.Case` of this bearing (its ``[bearing]`` and the set case's
    other sections); ``source``: "case", "catalogue NAME" or "inline"."""

    name: str
    position_mm: float
    direction: str
    case: object
    source: str

    @property
    def sign(self) -> float:
        """+1.0 for direction "+x", -1.0 for "-x"."""
        return 1.0 if self.direction == "+x" else -1.0


@dataclass(frozen=True)
class BearingSet:
    """A validated ``[set]`` table. ``table`` is the table as written (for writing it back)."""

    bearings: tuple[SetBearing, ...]
    arrangement: str | None
    width_mm: float
    load_position_mm: float
    load_force_N: tuple[float, float, float]
    load_moment_Nm: tuple[float, float]
    preload_kind: str
    preload_force_N: float | None
    preload_offset_um: float | None
    spring_side: str | None
    table: dict
    #: the shaft's tilt (y, z) [deg] relative to the housing bores (every outer ring), imposed
    #: instead of solved; None: the tilt is solved from the moment balance
    misalignment_deg: tuple[float, float] | None = None

    def to_dict(self) -> dict:
        """The ``[set]`` table as written."""
        return copy.deepcopy(self.table)

    def to_toml(self) -> str:
        """The ``[set]`` table as case-file text (its sub-tables and ``[[set.bearing]]``)."""
        return tomli_w.dumps({"set": self.to_dict()})

    @property
    def directions(self) -> tuple[str, ...]:
        return tuple(b.direction for b in self.bearings)

    def describe(self) -> str:
        """The set in words: ``DB pair of 2 bearings, preload force 150 N``."""
        head = self.arrangement or "set"
        kind = self.preload_kind
        if kind == "force":
            preload = f"preload force {self.preload_force_N:g} N at assembly"
        elif kind == "offset":
            preload = f"preload offset {self.preload_offset_um:g} µm"
        elif kind == "spring":
            preload = (
                f"spring preload {self.preload_force_N:g} N on the outer rings of the "
                f"{self.spring_side} bearings"
            )
        else:
            preload = "no preload"
        text = f"{head} of {len(self.bearings)} bearing(s), {preload}"
        if self.misalignment_deg is not None:
            y, z = self.misalignment_deg
            text += f", shaft tilted [{y:g}, {z:g}] deg in the housing"
        return text


def _number(problems, key, value, positive=False, non_negative=False):
    """``value`` as a finite float, or None with a problem filed under ``key``."""
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        problems.append(Problem(key, f"{key} = {value!r}: give a finite number"))
        return None
    value = float(value)
    if positive and value <= 0.0:
        problems.append(Problem(key, f"{key} = {value:g}: must be greater than 0"))
        return None
    if non_negative and value < 0.0:
        problems.append(Problem(key, f"{key} = {value:g}: must not be negative"))
        return None
    return value


def _vector(problems, key, value, size):
    """``value`` as a tuple of ``size`` finite floats (a problem under ``key`` otherwise)."""
    if not isinstance(value, list | tuple) or len(value) != size:
        problems.append(
            Problem(
                key,
                f"{key} = {value!r}: give {size} numbers ["
                + ", ".join(("x", "y", "z") if size == 3 else ("y", "z"))
                + "]",
            )
        )
        return (0.0,) * size
    numbers = [_number(problems, key, item) for item in value]
    return tuple(0.0 if n is None else n for n in numbers)


def _unknown(problems, where, table, allowed):
    for name in table:
        if name not in allowed:
            problems.append(
                Problem(
                    f"{where}.{name}",
                    f"unknown key {where}.{name}: allowed keys are " + ", ".join(allowed),
                )
            )


def catalogue_bearing_files() -> dict[str, Path]:
    """The shipped catalogue bearings (``assets/bearings/*.toml``) by name (the file name without
    ``.toml``, as :func:`solver.catalogue.catalogue` names them)."""
    found = {}
    for folder in assets.__path__:
        bearings = Path(folder) / "bearings"
        if bearings.is_dir():
            found.update({path.stem: path for path in sorted(bearings.glob("*.toml"))})
    return found


def _catalogue_bearing(name: str, key: str, problems) -> dict | None:
    """The ``[bearing]`` (and ``[materials]``) tables of the catalogue bearing ``name``."""
    files = catalogue_bearing_files()
    path = files.get(name) if isinstance(name, str) else None
    if path is None:
        close = difflib.get_close_matches(str(name), list(files), n=3, cutoff=0.5)
        hint = f"did you mean {', '.join(close)}? " if close else ""
        problems.append(
            Problem(
                key,
                f"{key} = {name!r}: not a catalogue bearing; {hint}the catalogue bearings are "
                + ", ".join(sorted(files)),
            )
        )
        return None
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    return {"bearing": data["bearing"], "materials": data.get("materials", {})}


def _bearing_case(case_data: dict, where: str, entry: dict, problems, build_case):
    """(validated single-bearing Case, source) of one set bearing, or (None, "")."""
    data = copy.deepcopy(case_data)
    source = "case"
    if "catalogue" in entry and "bearing" in entry:
        problems.append(
            Problem(
                f"{where}.catalogue",
                f"{where} gives both catalogue and bearing: give one (a catalogue bearing or an "
                "inline [bearing]-like table), or neither to use the case's [bearing]",
            )
        )
        return None, ""
    if "catalogue" in entry:
        found = _catalogue_bearing(entry["catalogue"], f"{where}.catalogue", problems)
        if found is None:
            return None, ""
        data["bearing"] = found["bearing"]
        if found["materials"]:
            data["materials"] = {**found["materials"], **data.get("materials", {})}
        source = f"catalogue {entry['catalogue']}"
    elif "bearing" in entry:
        if not isinstance(entry["bearing"], dict):
            problems.append(
                Problem(f"{where}.bearing", f"{where}.bearing must be a table of [bearing] keys")
            )
            return None, ""
        data["bearing"] = entry["bearing"]
        source = "inline"
    try:
        return build_case(data), source
    except CaseError as error:
        for p in error.problems:
            key = f"{where}.{p.key}" if source != "case" else p.key
            problems.append(Problem(key, f"{where} ({source}): {p.message}"))
        return None, ""


def read_set(table, case_data: dict, build_case) -> BearingSet:
    """The :class:`BearingSet` of the ``[set]`` table ``table``; ``case_data`` is the rest of the
    case (as read from TOML, without ``set``): each set bearing's case is it with that bearing's
    ``[bearing]``, validated by ``build_case(data) -> Case`` (CaseError). Raises CaseError listing
    every problem."""
    problems: list[Problem] = []
    if not isinstance(table, dict):
        raise CaseError(Problem("set", "[set] must be a table (see docs/case-format.md)"))
    _unknown(problems, "set", table, _SET_KEYS)
    arrangement = table.get("arrangement")
    entries = table.get("bearing", [])
    if isinstance(entries, dict):
        entries = [entries]
    if not isinstance(entries, list) or not all(isinstance(e, dict) for e in entries):
        raise CaseError(Problem("set.bearing", "set.bearing must be an array of [[set.bearing]]"))
    if arrangement is not None:
        if arrangement not in ARRANGEMENTS:
            problems.append(
                Problem(
                    "set.arrangement",
                    f"set.arrangement = {arrangement!r}: unknown arrangement; use one of "
                    + ", ".join(ARRANGEMENTS)
                    + " or list the bearings as [[set.bearing]] with their direction",
                )
            )
            raise CaseError(problems)
        count = len(ARRANGEMENTS[arrangement])
        if entries and len(entries) != count:
            problems.append(
                Problem(
                    "set.bearing",
                    f"set.arrangement = {arrangement!r} has {count} bearings but "
                    f"{len(entries)} [[set.bearing]] are given: give one per bearing (to set "
                    "their catalogue bearing or position) or none",
                )
            )
            raise CaseError(problems)
        entries = entries or [{} for _ in range(count)]
    if not entries:
        raise CaseError(
            Problem(
                "set",
                "[set] needs an arrangement (" + ", ".join(ARRANGEMENTS) + ") or at least one "
                "[[set.bearing]]",
            )
        )
    if len(entries) > _LARGEST_SET:
        raise CaseError(
            Problem("set.bearing", f"a set has at most {_LARGEST_SET} bearings ({len(entries)})")
        )
    width = table.get("width_mm")
    if width is None:
        problems.append(
            Problem(
                "set.width_mm",
                "set.width_mm is missing: give the bearings' width B [mm] (the overlap check "
                "and the default spacing of an arrangement need it)",
            )
        )
    else:
        width = _number(problems, "set.width_mm", width, positive=True)
    spacing = table.get("spacing_mm")
    if spacing is not None:
        spacing = _number(problems, "set.spacing_mm", spacing, positive=True)
    elif width is not None:
        spacing = width  # matched sets: the rings' faces touch
    load = table.get("load", {})
    if not isinstance(load, dict):
        problems.append(
            Problem("set.load", "set.load must be a table (position_mm, force_N, moment_Nm)")
        )
        load = {}
    _unknown(problems, "set.load", load, _LOAD_KEYS)
    load_position = _number(
        problems, "set.load.position_mm", load.get("position_mm", DEFAULT_LOAD_POSITION_MM)
    )
    force = _vector(problems, "set.load.force_N", load.get("force_N", DEFAULT_FORCE_N), 3)
    moment = _vector(problems, "set.load.moment_Nm", load.get("moment_Nm", DEFAULT_MOMENT_NM), 2)
    misalignment = None
    if "misalignment_deg" in table:
        misalignment = _vector(problems, "set.misalignment_deg", table["misalignment_deg"], 2)
        if any(abs(angle) > MAX_MISALIGNMENT_DEG for angle in misalignment):
            problems.append(
                Problem(
                    "set.misalignment_deg",
                    f"set.misalignment_deg = {list(misalignment)}: each tilt must lie within "
                    f"±{MAX_MISALIGNMENT_DEG:g} deg (a bearing's misalignment, not a bend)",
                )
            )
        if any(moment):
            problems.append(
                Problem(
                    "set.load.moment_Nm",
                    "set.load.moment_Nm is not read when set.misalignment_deg imposes the shaft's "
                    "tilt (the moment that holds the tilt comes from outside the set and is a "
                    "result, misalignment_moment): remove one of them",
                    ("set.misalignment_deg",),
                )
            )
    preload = table.get("preload", {})
    if not isinstance(preload, dict):
        problems.append(Problem("set.preload", "set.preload must be a table"))
        preload = {}
    _unknown(problems, "set.preload", preload, _PRELOAD_KEYS)
    kind = preload.get("kind", DEFAULT_PRELOAD_KIND)
    preload_force = offset = side = None
    if kind not in PRELOAD_KINDS:
        problems.append(
            Problem(
                "set.preload.kind",
                f"set.preload.kind = {kind!r}: use one of " + ", ".join(PRELOAD_KINDS),
            )
        )
    wanted = {"none": (), "force": ("force_N",), "offset": ("offset_um",)}
    wanted["spring"] = ("force_N", "spring_side")
    for name in _PRELOAD_KEYS[1:]:
        if name in preload and kind in wanted and name not in wanted[kind]:
            problems.append(
                Problem(
                    f"set.preload.{name}",
                    f"set.preload.{name} is not read with set.preload.kind = {kind!r}: remove it "
                    "or change the kind",
                )
            )
    for name in wanted.get(kind, ()):
        if name not in preload:
            problems.append(
                Problem(
                    f"set.preload.{name}",
                    f"set.preload.{name} is missing: set.preload.kind = {kind!r} needs it",
                )
            )
    if "force_N" in preload:
        preload_force = _number(problems, "set.preload.force_N", preload["force_N"], positive=True)
    if "offset_um" in preload:
        offset = _number(problems, "set.preload.offset_um", preload["offset_um"])
    if "spring_side" in preload:
        side = preload["spring_side"]
        if side not in DIRECTIONS:
            problems.append(
                Problem(
                    "set.preload.spring_side",
                    f'set.preload.spring_side = {side!r}: give "+x" or "-x", the direction '
                    "of the bearings whose outer rings the spring pushes",
                )
            )
    bearings = []
    for index, entry in enumerate(entries):
        where = f"set.bearing[{index + 1}]"
        _unknown(problems, where, entry, _BEARING_KEYS)
        direction = entry.get(
            "direction", ARRANGEMENTS[arrangement][index] if arrangement else None
        )
        if direction is None:
            problems.append(
                Problem(
                    f"{where}.direction",
                    f'{where}.direction is missing: give "+x" or "-x" (the axial direction of '
                    "the shaft thrust the bearing carries), or name a set.arrangement",
                )
            )
        elif direction not in DIRECTIONS:
            problems.append(
                Problem(
                    f"{where}.direction",
                    f'{where}.direction = {direction!r}: give "+x" or "-x"',
                )
            )
        if "position_mm" in entry:
            position = _number(problems, f"{where}.position_mm", entry["position_mm"])
        elif arrangement is not None or len(entries) == 1:
            position = None if spacing is None else index * spacing
        else:
            problems.append(
                Problem(
                    f"{where}.position_mm",
                    f"{where}.position_mm is missing: give the axial position of the bearing's "
                    "ball-centre plane [mm], or name a set.arrangement",
                )
            )
            position = None
        name = entry.get("name", f"bearing {index + 1}")
        if not isinstance(name, str) or not name.strip():
            problems.append(Problem(f"{where}.name", f"{where}.name must be a non-empty text"))
        bearing_case, source = _bearing_case(case_data, where, entry, problems, build_case)
        bearings.append((name, position, direction, bearing_case, source))
    names = [b[0] for b in bearings]
    if len(set(names)) != len(names):
        problems.append(Problem("set.bearing", "the set's bearing names must differ"))
    if problems:
        raise CaseError(problems)
    result = BearingSet(
        bearings=tuple(SetBearing(*b) for b in bearings),
        arrangement=arrangement,
        width_mm=width,
        load_position_mm=load_position,
        load_force_N=force,
        load_moment_Nm=moment,
        preload_kind=kind,
        preload_force_N=preload_force,
        preload_offset_um=offset,
        spring_side=side,
        table=copy.deepcopy(table),
        misalignment_deg=misalignment,
    )
    _check_rules(result, case_data, problems)
    if problems:
        raise CaseError(problems)
    return result


def _check_rules(bearing_set: BearingSet, case_data: dict, problems) -> None:
    """Rules between the set's keys: no overlapping bearings, thrust carried both ways when
    the preload or the load asks, no loads or misalignment in [operating]."""
    ordered = sorted(bearing_set.bearings, key=lambda b: b.position_mm)
    for left, right in zip(ordered, ordered[1:], strict=False):
        gap = right.position_mm - left.position_mm
        if gap < bearing_set.width_mm - 1e-9:
            problems.append(
                Problem(
                    "set.bearing",
                    f"bearings {left.name!r} at {left.position_mm:g} mm and {right.name!r} at "
                    f"{right.position_mm:g} mm overlap: their ball-centre planes are "
                    f"{gap:g} mm apart, less than the width set.width_mm = "
                    f"{bearing_set.width_mm:g} mm; move them apart (set.spacing_mm or "
                    "position_mm)",
                    ("set.width_mm",),
                )
            )
    directions = set(bearing_set.directions)
    axial = bearing_set.load_force_N[0]
    for sign, name in ((1.0, "+x"), (-1.0, "-x")):
        if axial * sign > 0.0 and name not in directions:
            problems.append(
                Problem(
                    "set.load.force_N",
                    f"set.load.force_N has an axial force of {axial:g} N towards {name} but no "
                    f"bearing of the set carries thrust towards {name} (directions "
                    + ", ".join(bearing_set.directions)
                    + "): turn a bearing round or change the load's sign",
                    ("set.bearing",),
                )
            )
    if bearing_set.preload_kind in ("force", "offset") and len(directions) < 2:
        problems.append(
            Problem(
                "set.preload.kind",
                f"set.preload.kind = {bearing_set.preload_kind!r} needs bearings facing both "
                "ways (an arrangement such as DB or DF): in this set every bearing carries thrust "
                f"towards {bearing_set.directions[0]}, so a fixed-position preload has nothing to "
                "press against",
            )
        )
    if bearing_set.preload_kind == "spring" and bearing_set.spring_side not in directions:
        problems.append(
            Problem(
                "set.preload.spring_side",
                f"set.preload.spring_side = {bearing_set.spring_side!r}: no bearing of the set "
                "carries thrust that way; name the direction of the bearings the spring pushes",
            )
        )
    if bearing_set.preload_kind == "spring" and len(directions) < 2:
        problems.append(
            Problem(
                "set.preload.kind",
                "a spring preload needs bearings facing both ways: the spring side's bearings "
                "are preloaded against the others",
            )
        )
    operating = case_data.get("operating", {}) if isinstance(case_data, dict) else {}
    if not isinstance(operating, dict):
        return
    for key in ("axial_load_N", "radial_load_N", "misalignment_deg", "tilting_moment_Nm"):
        value = operating.get(key)
        if value not in (None, 0, 0.0):
            problems.append(
                Problem(
                    f"operating.{key}",
                    f"operating.{key} is not read for a bearing set: the loads on the shaft are "
                    "set.load.force_N = [x, y, z] and set.load.moment_Nm = [y, z] at "
                    "set.load.position_mm, and the shaft's tilt is solved (or imposed by "
                    "set.misalignment_deg = [y, z]); remove it",
                    ("set.load.force_N",),
                )
            )
