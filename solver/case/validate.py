"""Validation of a parsed case (nested dict): every rule a case must satisfy, in one place.

:func:`validate` checks a nested dict (as :func:`tomllib.loads` returns) and returns its values,
every one filled in from the schema (:class:`CaseValues`); :meth:`solver.case.model.Case.from_dict`
builds the :class:`~solver.case.model.Case` from them. Every problem is collected (not just the
first) and raised together as one :class:`solver.errors.CaseError`; each :class:`Problem` names the
dotted key, the value and what is allowed. Checks run in three passes: structure (unknown sections
and keys), each key on its own (type, finiteness, bounds, choices), then rules between keys
(geometry that cannot be built, loads that hold nothing, traction curves that contradict
themselves). A rule is only checked when the keys it reads passed the earlier passes, so one mistake
gives one message.

Rules that only one model needs are here too: :func:`dynamic_problems` lists why the dynamic model
cannot run a valid case (the quasi-static model can).
"""

from __future__ import annotations

import dataclasses
import math
import re
from dataclasses import dataclass
from types import SimpleNamespace

from solver.errors import CaseError, Problem
from solver.lubricants import lubricant_table
from solver.materials import BUILTIN_MATERIALS

from .history import parse_history
from .messages import _suggest, _unknown_in_table, _unknown_key_message, show
from .schema import (
    FIELDS,
    MATERIAL_FIELDS,
    METHOD_KEYS,
    METHOD_NEEDS,
    OPTIONAL,
    OPTIONAL_SECTIONS,
    REQUIRED,
    SECTION_ORDER,
    Estimated,
    Field,
    format_number,
)

_MATERIAL_NAME = re.compile(r"^[A-Za-z0-9_-]+$")
_MISSING = object()


def _problem(
    problems: list[Problem], key: str, message: str, related: tuple[str, ...] = ()
) -> None:
    """Record a problem filed under ``key``; ``related`` names the other keys the rule involves."""
    problems.append(Problem(key, message, tuple(related)))


# ---- pass 1: structure -------------------------------------------------------------------------
def _known_names(prefix: tuple[str, ...]) -> list[str]:
    """Valid next segments under ``prefix`` (from FIELDS)."""
    names: list[str] = []
    for f in FIELDS:
        path = f.path if f.section else ("", f.name)
        if prefix == ("",):
            if len(f.path) == 1 and f.name not in names:
                names.append(f.name)
            continue
        if (
            path[: len(prefix)] == prefix
            and len(path) > len(prefix)
            and path[len(prefix)] not in names
        ):
            names.append(path[len(prefix)])
    return names


def _elsewhere(name: str) -> str | None:
    """Full key of a field whose last segment is ``name`` (a key put in the wrong section)."""
    for f in FIELDS:
        if f.name == name:
            return f.key
    return None


def _check_structure(data: dict, problems: list[Problem]) -> None:
    sections = list(SECTION_ORDER)
    top_keys = _known_names(("",))
    for key, value in data.items():
        if key in top_keys:
            continue
        if key in sections:
            if not isinstance(value, dict):
                _problem(
                    problems,
                    key,
                    f"{key} = {show(value)}: must be a section, not a single value: "
                    f"a [{key}] header followed by its keys",
                )
            continue
        if isinstance(value, dict):
            suggestion = _suggest(key, sections)
            hint = (
                f"did you mean [{suggestion}]?"
                if suggestion
                else "valid sections: " + ", ".join(f"[{s}]" for s in sections)
            )
            _problem(
                problems,
                key,
                f"unknown section [{key}]: {hint} "
                "(unknown sections are rejected so that a typo is not ignored)",
            )
            continue
        home = _elsewhere(key)
        if home:
            _problem(
                problems,
                key,
                f"unknown top-level key {key} = {show(value)}: it belongs in "
                f"[{home.split('.')[0]}] (as {home}), after the section header",
            )
            continue
        suggestion = _suggest(key, top_keys)
        _problem(
            problems,
            key,
            _unknown_key_message(key, value, suggestion, top_keys + [f"[{s}]" for s in sections]),
        )

    for section in sections:
        table = data.get(section)
        if not isinstance(table, dict) or section == "materials":
            continue
        allowed = _known_names((section,))
        for name, value in table.items():
            key = f"{section}.{name}"
            if name in allowed:
                sub_allowed = _known_names((section, name))
                if sub_allowed and isinstance(value, dict):
                    for sub, sub_value in value.items():
                        if sub not in sub_allowed:
                            _unknown_in_table(problems, key, sub, sub_value, sub_allowed)
                continue
            suggestion = _suggest(name, allowed)
            if suggestion:
                _problem(
                    problems,
                    key,
                    _unknown_key_message(key, value, f"{section}.{suggestion}", allowed),
                )
                continue
            home = _elsewhere(name)
            if home:
                _problem(
                    problems,
                    key,
                    f"unknown key {key} = {show(value)}: it belongs in "
                    f"[{home.split('.')[0]}] (as {home})",
                )
                continue
            _problem(problems, key, _unknown_key_message(key, value, None, allowed))


# ---- pass 2: one key at a time -----------------------------------------------------------------
def _lookup(data: dict, path: tuple[str, ...]):
    node = data
    for part in path:
        if not isinstance(node, dict) or part not in node:
            return _MISSING
        node = node[part]
    return node


def _check_bounds(f: Field, key: str, value, problems: list[Problem]) -> bool:
    unit = f" {f.unit}" if f.unit else ""
    if f.minimum is not None:
        low = value < f.minimum if f.minimum_inclusive else value <= f.minimum
        if low:
            word = "at least" if f.minimum_inclusive else "greater than"
            reason = f" ({f.reason})" if f.reason else ""
            _problem(
                problems,
                key,
                f"{key} = {show(value)}: must be {word} {format_number(f.minimum)}{unit}{reason}",
            )
            return False
    if f.maximum is not None:
        high = value > f.maximum if f.maximum_inclusive else value >= f.maximum
        if high:
            word = "at most" if f.maximum_inclusive else "less than"
            why = f.reason_high or f.reason
            reason = f" ({why})" if why else ""
            _problem(
                problems,
                key,
                f"{key} = {show(value)}: must be {word} {format_number(f.maximum)}{unit}{reason}",
            )
            return False
    return True


def check_value(f: Field, key: str, value, problems: list[Problem]):
    """Converted value, or _MISSING after recording a problem. Materials are checked later."""
    if f.type in ("float", "int"):
        if isinstance(value, bool) or not isinstance(value, int | float):
            kind = (
                "text"
                if isinstance(value, str)
                else "a table"
                if isinstance(value, dict)
                else "a list"
                if isinstance(value, list)
                else type(value).__name__
            )
            _problem(
                problems,
                key,
                f"{key} = {show(value)}: must be {f.allowed_text()} "
                f"(got {kind}; write numbers without quotes)",
            )
            return _MISSING
        if isinstance(value, float) and not math.isfinite(value):
            _problem(
                problems,
                key,
                f"{key} = {show(value)}: must be a finite number ({f.allowed_text()})",
            )
            return _MISSING
        if f.type == "int":
            if isinstance(value, float):
                if value != int(value):
                    _problem(
                        problems,
                        key,
                        f"{key} = {show(value)}: must be a whole number ({f.allowed_text()})",
                    )
                    return _MISSING
                value = int(value)
        elif isinstance(value, int):
            try:
                value = float(value)
            except OverflowError:  # an integer beyond the range of a float
                _problem(
                    problems,
                    key,
                    f"{key} = {show(value)}: far too large ({f.allowed_text()})",
                )
                return _MISSING
        return value if _check_bounds(f, key, value, problems) else _MISSING
    if f.type in ("str", "choice"):
        if not isinstance(value, str):
            _problem(
                problems,
                key,
                f"{key} = {show(value)}: must be {f.allowed_text()} (text in double quotes)",
            )
            return _MISSING
        if f.type == "choice" and value not in f.choices:
            s = _suggest(value, f.choices)
            hint = f'; did you mean "{s}"?' if s else ""
            _problem(problems, key, f"{key} = {show(value)}: must be {f.allowed_text()}{hint}")
            return _MISSING
        return value
    if f.type == "bool":
        if not isinstance(value, bool):
            _problem(problems, key, f"{key} = {show(value)}: must be true or false")
            return _MISSING
        return value
    if f.type == "material":
        if isinstance(value, str):
            return value
        if isinstance(value, dict):
            return _check_material_table(key, value, problems)
        _problem(
            problems,
            key,
            f"{key} = {show(value)}: must be a material name in quotes or an "
            "inline table { youngs_modulus_GPa = ..., poisson_ratio = ..., "
            "density_kg_m3 = ... }",
        )
        return _MISSING
    raise AssertionError(f"unknown field type {f.type!r} for {f.key}")  # schema bug


def _check_material_table(prefix: str, table: dict, problems: list[Problem]):
    names = [m.key for m in MATERIAL_FIELDS]
    ok = True
    for name, value in table.items():
        if name not in names:
            _unknown_in_table(problems, prefix, name, value, names)
            ok = False
    out = {}
    for m in MATERIAL_FIELDS:
        key = f"{prefix}.{m.key}"
        if m.key not in table:
            _problem(
                problems,
                key,
                f"{key} is missing: a material needs {m.label.lower()} ({m.allowed_text()})",
            )
            ok = False
            continue
        value = check_value(m, key, table[m.key], problems)
        if value is _MISSING:
            ok = False
        else:
            out[m.key] = value
    return out if ok else _MISSING


# ---- pass 3: rules between keys ----------------------------------------------------------------
def _max_balls(ball_diameter: float, pitch_diameter: float) -> int:
    """Largest Z with d_m sin(pi/Z) > D (0 if not even 3 fit)."""
    z = 2
    while math.sin(math.pi / (z + 1)) * pitch_diameter > ball_diameter and z < 100000:
        z += 1
    return z if z >= 3 else 0


def _check_bearing_rules(v: dict, given: set, problems: list[Problem]) -> None:
    angle_k, clear_k = "bearing.free_contact_angle_deg", "bearing.diametral_clearance_mm"
    has_angle, has_clear = angle_k in given, clear_k in given
    if has_angle and has_clear:
        _problem(
            problems,
            angle_k,
            f"{angle_k} = {show(v.get(angle_k, '?'))} and {clear_k} = "
            f"{show(v.get(clear_k, '?'))}: give exactly one of the two (the "
            "clearance fixes the free contact angle); remove one",
            related=(clear_k,),
        )
    elif not has_angle and not has_clear:
        _problem(
            problems,
            angle_k,
            f"{angle_k} / {clear_k} missing: give exactly one of them "
            "(the free contact angle in degrees, or the diametral "
            "clearance in mm; 0 mm for a zero-clearance deep-groove bearing)",
            related=(clear_k,),
        )

    D, dm, Z = (
        v.get(k)
        for k in ("bearing.ball_diameter_mm", "bearing.pitch_diameter_mm", "bearing.ball_count")
    )
    fi, fo = v.get("bearing.inner_groove_radius_ratio"), v.get("bearing.outer_groove_radius_ratio")
    geometry_ok = D is not None and dm is not None
    if geometry_ok and dm <= D:
        _problem(
            problems,
            "bearing.pitch_diameter_mm",
            f"bearing.pitch_diameter_mm = {show(dm)}: must be larger than the ball diameter "
            f"({show(D)} mm); the pitch circle runs through the ball centres, so the inner ring "
            "would have no material left",
            related=("bearing.ball_diameter_mm",),
        )
        geometry_ok = False
    if geometry_ok and Z is not None:
        chord = dm * math.sin(math.pi / Z)
        if chord <= D:
            zmax = _max_balls(D, dm)
            fit = f"at most {zmax} fit" if zmax else "not even 3 fit"
            _problem(
                problems,
                "bearing.ball_count",
                f"bearing.ball_count = {Z}: {Z} balls of diameter {show(D)} mm do not fit on a "
                f"{show(dm)} mm pitch circle (neighbouring centres would be {chord:.4g} mm "
                f"apart, less than the ball diameter; {fit})",
                related=("bearing.ball_diameter_mm", "bearing.pitch_diameter_mm"),
            )
            geometry_ok = False
    if D is None or fi is None or fo is None:
        return
    a0_len = (fi + fo - 1.0) * D  # A_0, mm
    alpha0 = None
    if has_angle and not has_clear and angle_k in v:
        alpha0 = math.radians(v[angle_k])
    elif has_clear and not has_angle and clear_k in v:
        pd = v[clear_k]
        if pd >= a0_len:
            angle = (
                "beyond 90"
                if pd > 2 * a0_len
                else format(math.degrees(math.acos(1.0 - pd / (2 * a0_len))), ".3g")
            )
            _problem(
                problems,
                clear_k,
                f"{clear_k} = {show(pd)}: must be less than {a0_len:.4g} mm for these grooves, "
                "A_0 = (f_i + f_o - 1) D, the distance between the groove curvature centres; "
                f"this clearance gives a free contact angle of {angle} degrees, and the free "
                "contact angle must be below 60 degrees",
                related=(
                    "bearing.inner_groove_radius_ratio",
                    "bearing.outer_groove_radius_ratio",
                    "bearing.ball_diameter_mm",
                ),
            )
        else:
            alpha0 = math.acos(1.0 - pd / (2 * a0_len))
    if alpha0 is None or not geometry_ok:
        return
    _check_lands(v, D, dm, fi, fo, alpha0, problems)


def _groove_bottom_diameters_mm(
    D: float, dm: float, fi: float, fo: float, alpha0: float
) -> tuple[float, float]:
    """Inner and outer groove-bottom diameters [mm] of the unloaded bearing (alpha0 in rad).

    d_i = d_m + 2 (f_i - 1/2) D cos(alpha0) - 2 f_i D and d_o = d_m - 2 (f_o - 1/2) D cos(alpha0)
    + 2 f_o D: each groove's curvature centre lies (f - 1/2) D from the ball centre along the free
    contact line, and the groove bottom one groove radius f D beyond it (docs/case-format.md).
    """
    inner = dm + 2.0 * (fi - 0.5) * D * math.cos(alpha0) - 2.0 * fi * D
    outer = dm - 2.0 * (fo - 0.5) * D * math.cos(alpha0) + 2.0 * fo * D
    return inner, outer


def _check_lands(v: dict, D, dm, fi, fo, alpha0: float, problems: list[Problem]) -> None:
    """Shoulder (land) diameters against the pitch circle: an error beyond it.

    A land sits between its groove bottom and the pitch circle: inner groove bottom < inner land <
    d_m < outer land < outer groove bottom (so the inner land is always below the outer one). A land
    at or beyond the pitch diameter would cut through the circle of ball centres, which no ring can
    do: that is an error. A land on the wrong side of its groove bottom is accepted (the contract
    example has such lands): Case.warnings() reports it and the truncation margins show every
    contact of that race as truncated.
    """
    inner_bottom, outer_bottom = _groove_bottom_diameters_mm(D, dm, fi, fo, alpha0)
    pitch_k = "bearing.pitch_diameter_mm"
    inner_k, outer_k = "bearing.inner_shoulder_diameter_mm", "bearing.outer_shoulder_diameter_mm"
    inner, outer = v.get(inner_k), v.get(outer_k)
    if inner is not None and inner >= dm:
        _problem(
            problems,
            inner_k,
            f"{inner_k} = {show(inner)}: must be less than the pitch diameter {show(dm)} mm, "
            f"normally between the inner groove-bottom diameter {inner_bottom:.4g} mm and "
            f"{show(dm)} mm; an inner land at or beyond the pitch circle would cut through the "
            "balls",
            related=(pitch_k,),
        )
    if outer is not None and outer <= dm:
        _problem(
            problems,
            outer_k,
            f"{outer_k} = {show(outer)}: must be greater than the pitch diameter {show(dm)} mm, "
            f"normally between {show(dm)} mm and the outer groove-bottom diameter "
            f"{outer_bottom:.4g} mm; an outer land at or inside the pitch circle would cut "
            "through the balls",
            related=(pitch_k,),
        )


def _check_materials(data: dict, v: dict, problems: list[Problem]) -> dict:
    """Validated user materials {name: table}; checks the bearing's material references."""
    users: dict = {}
    section = data.get("materials", {})
    if isinstance(section, dict):
        for name, table in section.items():
            key = f"materials.{name}"
            if not _MATERIAL_NAME.match(name):
                _problem(
                    problems,
                    key,
                    f"[materials.{name}]: material names may contain only letters, digits, _ and -",
                )
                continue
            if name in BUILTIN_MATERIALS:
                _problem(
                    problems,
                    key,
                    f"[materials.{name}]: {name} is a built-in material; "
                    "choose another name for your own",
                )
                continue
            if not isinstance(table, dict):
                _problem(
                    problems,
                    key,
                    f"{key} = {show(table)}: must be a table: a [materials.{name}] header "
                    "followed by youngs_modulus_GPa, poisson_ratio and density_kg_m3",
                )
                continue
            checked = _check_material_table(key, table, problems)
            if checked is not _MISSING:
                users[name] = checked
    known = list(BUILTIN_MATERIALS) + list(section if isinstance(section, dict) else {})
    for key in ("bearing.ball_material", "bearing.ring_material"):
        name = v.get(key)
        if isinstance(name, str) and name not in known:
            s = _suggest(name, known)
            hint = f'did you mean "{s}"? ' if s else ""
            _problem(
                problems,
                key,
                f"{key} = {show(name)}: unknown material; {hint}known materials: "
                f"{', '.join(known)}; define others under [materials.NAME] or "
                "give an inline table",
            )
            v.pop(key)
    return users


def _check_operating_rules(
    data: dict, v: dict, given: set, problems: list[Problem], bearing_set: bool = False
) -> None:
    mis_k, mom_k = "operating.misalignment_deg", "operating.tilting_moment_Nm"
    if mis_k in given and mom_k in given:
        _problem(
            problems,
            mom_k,
            f"{mis_k} = {show(v.get(mis_k, '?'))} and {mom_k} = "
            f"{show(v.get(mom_k, '?'))}: give at most one of the two (an "
            "imposed tilt, or a moment from which the tilt is solved)",
            related=(mis_k,),
        )
    # absent loads default to 0; loads given but invalid are already reported
    loads = [
        v[k] if k in v else (None if k in given else 0.0)
        for k in ("operating.axial_load_N", "operating.radial_load_N")
    ]
    if loads == [0.0, 0.0] and "operating" in data and not bearing_set:
        tilt = [k for k in (mis_k, mom_k) if v.get(k) not in (None, 0.0)]
        invalid = [k for k in (mis_k, mom_k) if k in given and k not in v]
        if not tilt and not invalid:
            _problem(
                problems,
                "operating.axial_load_N",
                "operating.axial_load_N = 0 and operating.radial_load_N = 0, no misalignment "
                "and no tilting moment: nothing holds the balls; give an axial load (e.g. a "
                "preload), a radial load, or both",
                related=("operating.radial_load_N",),
            )


def history_times(histories: dict) -> list[float]:
    """Every knot time of the ``histories`` ({key: KeyHistory}) and 0, sorted, distinct [s]."""
    return sorted({0.0, *(t for h in histories.values() for t in h.times)})


def key_value_at(values: dict, histories: dict, key: str, t: float, default: float = 0.0):
    """The value of ``key`` at time ``t`` [s]: its history's, else its (steady) value, else
    ``default``."""
    if key in histories:
        return histories[key].value_at(t)
    return values.get(key, default)


def top_relative_speed_rpm(values: dict, histories: dict) -> float:
    """The highest |inner - outer| ring speed [rpm] along the histories: at every knot time, and
    widened by the speed sines' amplitudes (0 for a case without histories)."""
    if not histories:
        return 0.0
    inner, outer = "operating.inner_ring_speed_rpm", "operating.outer_ring_speed_rpm"
    top = max(
        abs(key_value_at(values, histories, inner, t) - key_value_at(values, histories, outer, t))
        for t in history_times(histories)
    )
    return top + sum(histories[k].amplitude for k in (inner, outer) if k in histories)


def _check_history_loads(v: dict, given: set, histories: dict, problems: list[Problem]) -> None:
    """Something holds the balls at every knot time of the histories: the axial and the radial
    load (at their lowest, under a sine) are not both 0 there without a tilt."""
    load_keys = ("operating.axial_load_N", "operating.radial_load_N")
    if not any(k in histories for k in load_keys):
        return
    if any(k in given and k not in v for k in load_keys):  # reported already
        return
    tilt = [
        k
        for k in ("operating.misalignment_deg", "operating.tilting_moment_Nm")
        if k in given and (k in histories or v.get(k) not in (None, 0.0))
    ]
    if tilt:
        return
    for t in history_times(histories):
        lowest = []
        for k in load_keys:
            value = key_value_at(v, histories, k, t)
            if k in histories:
                value -= histories[k].amplitude
            lowest.append(value)
        if max(lowest) <= 0.0:
            keys = [k for k in load_keys if k in histories]
            _problem(
                problems,
                keys[0],
                f"at t = {t:g} s the axial and the radial load are both 0 (operating."
                "axial_load_N and operating.radial_load_N along their histories), with no "
                "misalignment and no tilting moment: nothing holds the balls then; keep a load "
                "(e.g. a preload) at every time",
                related=tuple(k for k in load_keys if k != keys[0]),
            )
            return


def _check_run_length_keys(
    data: dict, v: dict, given: set, histories, problems: list[Problem]
) -> None:
    """A case with a time history runs for ``simulation.duration_s`` (required) and is sampled per
    second; a steady case runs for shaft revolutions. A key of the other kind of case is an
    error (``Field.applies``). ``histories``: the keys given as history tables (an invalid one
    still makes the case a history case, so that one mistake gives one message)."""
    kind = "history" if histories else "steady"
    if histories and "simulation.duration_s" not in given:
        names = ", ".join(sorted(histories))
        _problem(
            problems,
            "simulation.duration_s",
            f"simulation.duration_s is missing: {names} "
            f"{'is a time history' if len(histories) == 1 else 'are time histories'}, so the run "
            "length is a duration in seconds (e.g. duration_s = 0.5 under [simulation]); "
            "shaft revolutions are for steady cases",
            related=tuple(sorted(histories)),
        )
    for f in FIELDS:
        if f.applies in ("", kind) or f.key not in v:  # an invalid value was reported already
            continue
        raw = _lookup(data, f.path)
        if kind == "history":
            other = {
                "simulation.shaft_revolutions": "simulation.duration_s",
                "simulation.samples_per_revolution": "simulation.samples_per_second",
            }.get(f.key, "")
            verb = "is a time history" if len(histories) == 1 else "are time histories"
            _problem(
                problems,
                f.key,
                f"{f.key} = {show(raw)} is read only by a steady case, and "
                f"{', '.join(sorted(histories))} {verb}: give {other} instead (remove {f.name})",
                related=tuple(sorted(histories)),
            )
        else:
            other = {
                "simulation.duration_s": "simulation.shaft_revolutions",
                "simulation.samples_per_second": "simulation.samples_per_revolution",
            }.get(f.key, "")
            _problem(
                problems,
                f.key,
                f"{f.key} = {show(raw)} is read only by a case with a time history, and no "
                f"operating key of this case is one: give {other} instead (remove {f.name}), "
                "or give an operating key as a history (docs/case-format.md)",
            )


def _check_traction(v: dict, given: set, problems: list[Problem]) -> None:
    """The traction curve rises from mu_zero to its peak mu_max and falls towards mu_infinity.

    Keys that are not given take their schema default here, so the rule holds for the curve the
    dynamic model uses; a key given with an invalid value was reported already and is skipped.
    """
    p = "lubricant.traction."
    curve = {}
    for name in ("mu_zero", "mu_max", "mu_infinity"):
        key = p + name
        if key in v:
            curve[name] = (v[key], "")
        elif key not in given:
            curve[name] = (_default(key), " (the default)")
    if "mu_max" not in curve:
        return
    mumax, max_note = curve["mu_max"]
    for name, direction in (
        ("mu_zero", "rises from mu_zero to its peak"),
        ("mu_infinity", "falls from its peak towards mu_infinity"),
    ):
        if name not in curve or curve[name][0] <= mumax:
            continue
        value, note = curve[name]
        _problem(
            problems,
            p + name,
            f"{p}{name} = {show(value)}{note}: must be at most mu_max = {show(mumax)}{max_note} "
            f"(the curve {direction})",
            related=(p + "mu_max",),
        )


def _check_lubrication_method(v: dict, given: set, problems: list[Problem]) -> None:
    """Each method's own keys only with that method, and the key a method needs to size its oil
    supply (unless ``oil_volume_fraction`` gives the mixture directly). A method given with an
    invalid value was reported already: its keys are not checked against it."""
    method_key = "lubricant.method"
    if method_key in given and method_key not in v:
        return
    method = v.get(method_key)
    p = "lubricant."
    for name in sorted({k for keys in METHOD_KEYS.values() for k in keys}):
        key = p + name
        if key not in v or name in METHOD_KEYS.get(method, ()):
            continue
        readers = " or ".join(f'"{m}"' for m, keys in METHOD_KEYS.items() if name in keys)
        now = f'lubricant.method = "{method}"' if method else "the case names no lubricant.method"
        _problem(
            problems,
            key,
            f"{key} = {show(v.get(key, '?'))} is read only with lubricant.method = {readers}, "
            f"and {now}; set the method that supplies it or remove the key",
            related=(method_key,),
        )
    need = METHOD_NEEDS.get(method)
    fraction = p + "oil_volume_fraction"
    if need and p + need not in given and fraction not in given:
        f = next(f for f in FIELDS if f.key == p + need)
        _problem(
            problems,
            p + need,
            f'{p}{need} is missing: lubricant.method = "{method}" needs it to size the oil in the '
            f"bearing ({f.allowed_text()}: {f.help}); or give {fraction} directly",
            related=(method_key,),
        )


def _default(key: str):
    """Schema default of a key with a plain default value."""
    return next(f.default for f in FIELDS if f.key == key)


# ---- driver ------------------------------------------------------------------------------------
@dataclass(frozen=True)
class CaseValues:
    """The values of a valid case, every one filled in from the schema (case units).

    ``histories`` maps each operating key given as a time history to its
    :class:`~solver.case.history.KeyHistory` (its value at t = 0 is in ``sections``).
    ``sections`` maps each section of :data:`SECTION_ORDER` except ``materials`` to its values
    ``{name: value}`` (the inline ``traction`` table as a nested dict); absent optional keys are
    None. ``materials`` holds the user material tables as written. ``estimated`` lists the dotted
    keys whose values were estimated from the bearing; ``absent_sections`` the optional sections the
    input did not have (their values are all defaults). ``traction_given`` says whether the input
    had a ``lubricant.traction`` table (whole or partial). ``from_oil`` lists the dotted keys
    whose values came from the named oil ``lubricant.oil`` (solver.lubricants).
    """

    title: str
    sections: dict
    materials: dict
    estimated: frozenset
    absent_sections: frozenset
    traction_given: bool = False
    from_oil: frozenset = frozenset()
    description: str = ""
    histories: dict = dataclasses.field(default_factory=dict)


def validate(data, base_dir=None, bearing_set: bool = False) -> CaseValues:
    """Values of a valid case from a nested dict; raises CaseError listing every problem.

    ``base_dir``: the case file's folder, where a history file (``{ file = ... }``) is looked for
    (None: the case has no folder). An operating key given as a time history has its value at
    t = 0 among the values, and its :class:`~solver.case.history.KeyHistory` in ``histories``.
    ``bearing_set``: the case has a ``[set]`` table (its loads are in ``[set.load]``, so
    ``[operating]`` may give none)."""
    if not isinstance(data, dict):
        raise CaseError(Problem("", f"a case must be a table of keys, not {type(data).__name__}"))
    problems: list[Problem] = []
    _check_structure(data, problems)

    values: dict = {}  # dotted key -> validated value (keys that passed pass 2)
    given: set = set()  # dotted keys present in the input
    histories: dict = {}  # dotted key -> KeyHistory of the keys given as time histories
    history_given: set = set()  # dotted keys given as a history table, valid or not
    missing_sections = set()
    for section in ("bearing", "operating"):
        if section not in data:
            missing_sections.add(section)
            needed = [f.name for f in FIELDS if f.section == section and f.required]
            _problem(
                problems,
                section,
                f"the [{section}] section is missing; it needs at least: " + ", ".join(needed),
            )
    for f in FIELDS:
        raw = _lookup(data, f.path)
        if raw is _MISSING:
            parent = _lookup(data, f.path[:-1]) if len(f.path) > 2 else data
            if len(f.path) > 2 and parent is not _MISSING and not isinstance(parent, dict):
                if f.name == _known_names(f.path[:-1])[0]:
                    key = ".".join(f.path[:-1])
                    _problem(
                        problems,
                        key,
                        f"{key} = {show(parent)}: must be an inline table "
                        "{ " + ", ".join(f"{n} = ..." for n in _known_names(f.path[:-1])) + " }",
                    )
                continue
            if f.required and f.section not in missing_sections:
                _problem(
                    problems,
                    f.key,
                    f"{f.key} is missing: it is required, {f.allowed_text()}. {f.help}",
                )
            continue
        given.add(f.key)
        if f.history and isinstance(raw, dict):
            history_given.add(f.key)
            history = parse_history(f, raw, base_dir, problems)
            if history is not None:
                histories[f.key] = history
                values[f.key] = history.value_at(0.0)
            continue
        value = check_value(f, f.key, raw, problems)
        if value is not _MISSING:
            values[f.key] = value

    users = _check_materials(data, values, problems)
    _check_bearing_rules(values, given, problems)
    _check_operating_rules(data, values, given, problems, bearing_set)
    _check_history_loads(values, given, histories, problems)
    _check_run_length_keys(data, values, given, history_given, problems)
    _check_traction(values, given, problems)
    _check_lubrication_method(values, given, problems)
    if problems:
        raise CaseError(problems)
    return _fill(data, values, users, histories)


def _fill(data: dict, values: dict, users: dict, histories: dict) -> CaseValues:
    """Every key's value: as given, else the schema default, else estimated from the bearing (or
    from the histories); a key read only by the other kind of case (``Field.applies``) is None
    when not given."""
    bearing = SimpleNamespace(
        **{f.name: values.get(f.key) for f in FIELDS if f.section == "bearing"}
    )
    run = SimpleNamespace(top_relative_speed_rpm=top_relative_speed_rpm(values, histories))
    kind = "history" if histories else "steady"
    sections: dict = {name: {} for name in SECTION_ORDER if name != "materials"}
    estimated = set()
    oil_values = {}
    if values.get("lubricant.oil") is not None:
        named = lubricant_table(values["lubricant.oil"])
        oil_values = {f"lubricant.{name}": value for name, value in named.items()}
    for f in FIELDS:
        if not f.section:
            continue
        if f.key in values:
            value = values[f.key]
        elif f.key in oil_values:
            value = oil_values[f.key]
        elif f.default is OPTIONAL or f.applies not in ("", kind):
            value = None
        elif isinstance(f.default, Estimated):
            value = float(f.default.function(run if f.default.reads == "history" else bearing))
            estimated.add(f.key)
        else:
            assert f.default is not REQUIRED, f.key  # required keys are in values here
            value = f.default
        target = sections[f.section]
        for part in f.path[1:-1]:
            target = target.setdefault(part, {})
        target[f.name] = value
    absent = frozenset(s for s in OPTIONAL_SECTIONS if s != "materials" and s not in data)
    lubricant = data.get("lubricant")
    return CaseValues(
        title=values.get("title", ""),
        description=values.get("description", ""),
        sections=sections,
        materials=users,
        estimated=frozenset(estimated),
        absent_sections=absent,
        traction_given=isinstance(lubricant, dict) and "traction" in lubricant,
        from_oil=frozenset(key for key in oil_values if key not in values),
        histories=dict(histories),
    )


# ---- rules of one model ------------------------------------------------------------------------
#: Memory a dynamic run holds per ball and output sample, in bytes (state, observations and the
#: result Dataset, at the peak while the Dataset is built).
RUN_BYTES_PER_BALL_SAMPLE = 1_500
#: Most output samples times balls a dynamic run may store (about 3 GB of memory).
MAX_DYNAMIC_BALL_SAMPLES = 2_000_000
#: Size of a dynamic result file: bytes per ball and output sample, plus a fixed part (the
#: per-ball variables, the case text and the file's own structure).
RESULT_FILE_BYTES_PER_BALL_SAMPLE = 400
RESULT_FILE_BASE_BYTES = 150_000


@dataclass(frozen=True)
class RunSize:
    """Output of a dynamic run: ``samples`` output samples after the start (the result holds
    ``samples + 1`` times), the memory the run holds at its peak and the size of its result file,
    in bytes (estimates)."""

    samples: int
    memory_bytes: int
    file_bytes: int


def dynamic_run_size(revolutions: float, samples_per_revolution: int, ball_count: int) -> RunSize:
    """The :class:`RunSize` of a dynamic run of ``revolutions`` shaft revolutions."""
    samples = int(round(revolutions * samples_per_revolution))
    ball_samples = (samples + 1) * ball_count
    return RunSize(
        samples,
        ball_samples * RUN_BYTES_PER_BALL_SAMPLE,
        RESULT_FILE_BASE_BYTES + ball_samples * RESULT_FILE_BYTES_PER_BALL_SAMPLE,
    )


def run_length_problems(
    revolutions: float,
    samples_per_revolution: int,
    ball_count: int,
    names: tuple[str, str] = ("simulation.shaft_revolutions", "simulation.samples_per_revolution"),
) -> list[Problem]:
    """Why a dynamic run of this length cannot be done: fewer than one output sample after the
    start, or more ball-samples than :data:`MAX_DYNAMIC_BALL_SAMPLES`. ``names`` are how the two
    values are named in messages (case keys, or command-line options)."""
    revolutions_name, samples_name = names
    size = dynamic_run_size(revolutions, samples_per_revolution, ball_count)
    given = (
        f"{revolutions_name} = {format_number(revolutions)} at "
        f"{samples_name} = {samples_per_revolution}"
    )
    related = (samples_name, "bearing.ball_count")
    if size.samples < 1:
        shortest = f"{1.0 / samples_per_revolution:.3g}"
        return [
            Problem(
                revolutions_name,
                f"{given}: the run would end before its first output sample; give at least "
                f"{shortest} revolutions (one sample), and several revolutions for the "
                "trajectory metrics",
                related,
            )
        ]
    if size.samples * ball_count > MAX_DYNAMIC_BALL_SAMPLES:
        return [
            Problem(
                revolutions_name,
                f"{given}: {size.samples} samples of {ball_count} balls exceed the "
                f"{MAX_DYNAMIC_BALL_SAMPLES:,} ball-samples a run can keep in memory (about 3 GB); "
                "give fewer revolutions or samples per revolution, or split the run",
                related,
            )
        ]
    return []


def history_run_length_problems(
    duration: float, samples_per_second: float, ball_count: int
) -> list[Problem]:
    """Why a dynamic run of a history case of ``duration`` [s] sampled ``samples_per_second``
    cannot be done: fewer than one output sample, or more ball-samples than
    :data:`MAX_DYNAMIC_BALL_SAMPLES`."""
    samples = int(round(duration * samples_per_second))
    given = (
        f"simulation.duration_s = {format_number(duration)} at simulation.samples_per_second = "
        f"{format_number(samples_per_second)}"
    )
    related = ("simulation.samples_per_second", "bearing.ball_count")
    if samples < 1:
        return [
            Problem(
                "simulation.duration_s",
                f"{given}: the run would end before its first output sample; give a duration of "
                f"at least {1.0 / samples_per_second:.3g} s",
                related,
            )
        ]
    if (samples + 1) * ball_count > MAX_DYNAMIC_BALL_SAMPLES:
        return [
            Problem(
                "simulation.duration_s",
                f"{given}: {samples} samples of {ball_count} balls exceed the "
                f"{MAX_DYNAMIC_BALL_SAMPLES:,} ball-samples a run can keep in memory (about 3 GB); "
                "give a shorter duration or fewer samples per second, or split the run",
                related,
            )
        ]
    return []


def dynamic_problems(case) -> list[Problem]:
    """Why the dynamic model cannot run the valid ``case`` (empty when it can).

    A steady case (no ``simulation.duration_s``: its run length is a number of shaft revolutions
    of the inner ring relative to the outer ring) needs the rings to turn relative to each other:
    at equal ring speeds a revolution never ends. The model itself runs a bearing at rest and
    through low speed (docs/numerics.md, "Low entrainment speed"), so a case whose speeds are
    histories and whose run length is a duration may start or stay at rest. Every run stores at
    least one output sample after the start, and keeps every output sample of every ball in
    memory, at most :data:`MAX_DYNAMIC_BALL_SAMPLES` (:func:`run_length_problems`). The
    quasi-static model needs none of these rules: it solves a bearing at rest too, and stores one
    sample. A bearing set has its own rules (:func:`set_dynamic_problems`).
    """
    if getattr(case, "bearing_set", None) is not None:
        return set_dynamic_problems(case)
    op = case.operating
    sim = case.simulation
    histories = getattr(case, "histories", {})
    if histories:
        found = history_run_length_problems(
            sim.duration_s, sim.samples_per_second, case.bearing.ball_count
        )
    else:
        found = run_length_problems(
            sim.shaft_revolutions, sim.samples_per_revolution, case.bearing.ball_count
        )
    speed_keys = ("operating.inner_ring_speed_rpm", "operating.outer_ring_speed_rpm")
    if histories:
        values = {speed_keys[0]: op.inner_ring_speed_rpm, speed_keys[1]: op.outer_ring_speed_rpm}
        if top_relative_speed_rpm(values, histories) == 0.0:
            found.append(
                Problem(
                    "operating.inner_ring_speed_rpm",
                    "operating.inner_ring_speed_rpm and operating.outer_ring_speed_rpm are equal "
                    "at every point of their histories: the rings never turn relative to each "
                    "other, so nothing runs; give the speeds that the run should follow",
                    ("operating.outer_ring_speed_rpm",),
                )
            )
    elif op.inner_ring_speed_rpm == op.outer_ring_speed_rpm:
        found.append(equal_speeds_problem(op.inner_ring_speed_rpm))
    return found


def dynamic_ball_count(case) -> int:
    """The balls a dynamic run of the valid ``case`` stores at every sample: every bearing's of a
    bearing set, else the bearing's."""
    bearing_set = getattr(case, "bearing_set", None)
    if bearing_set is not None:
        return sum(int(b.case.bearing.ball_count) for b in bearing_set.bearings)
    return int(case.bearing.ball_count)


def set_dynamic_problems(case) -> list[Problem]:
    """Why the dynamic model of a bearing set cannot run the valid set ``case`` (empty when it
    can). The set's dynamic model runs a steady operating point (a set case gives no time
    histories: the case refuses them), with any preload the case gives (a spring preload floats
    the outer rings of its side), the rings turning relative to each other; its run length is
    checked against the balls of every bearing of the set."""
    found = []
    sim = case.simulation
    found += run_length_problems(
        sim.shaft_revolutions, sim.samples_per_revolution, dynamic_ball_count(case)
    )
    op = case.operating
    if op.inner_ring_speed_rpm == op.outer_ring_speed_rpm:
        speed = format_number(op.inner_ring_speed_rpm)
        found.append(
            Problem(
                "operating.inner_ring_speed_rpm",
                f"operating.inner_ring_speed_rpm = operating.outer_ring_speed_rpm = {speed}: the "
                "dynamic run of a bearing set lasts simulation.shaft_revolutions revolutions of "
                "the inner rings relative to the outer rings, so they must turn relative to each "
                "other; give different ring speeds. The quasi-static model solves this case as "
                "it is.",
                ("operating.outer_ring_speed_rpm",),
            )
        )
    return found


def equal_speeds_problem(speed_rpm: float) -> Problem:
    """Why a steady dynamic run at equal ring speeds ``speed_rpm`` [rpm] cannot be made, and what
    to give instead (:func:`dynamic_problems`)."""
    speed = format_number(speed_rpm)
    return Problem(
        "operating.inner_ring_speed_rpm",
        f"operating.inner_ring_speed_rpm = operating.outer_ring_speed_rpm = {speed}: a steady "
        "dynamic run needs the rings to turn relative to each other, since it lasts "
        "simulation.shaft_revolutions revolutions of the inner ring relative to the outer ring "
        "(at equal speeds it would never end). To simulate a bearing at rest or starting from "
        "rest, give the ring speed as a history (a ramp or a table from 0 rpm) and the run "
        "length in seconds as simulation.duration_s (docs/case-format.md); otherwise give "
        "different ring speeds. The quasi-static model solves this case as it is.",
        ("operating.outer_ring_speed_rpm", "simulation.duration_s"),
    )


__all__ = [
    "CaseValues",
    "RunSize",
    "check_value",
    "dynamic_ball_count",
    "dynamic_problems",
    "dynamic_run_size",
    "equal_speeds_problem",
    "history_run_length_problems",
    "history_times",
    "key_value_at",
    "run_length_problems",
    "set_dynamic_problems",
    "top_relative_speed_rpm",
    "show",
    "validate",
]
