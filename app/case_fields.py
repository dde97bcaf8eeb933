"""The case form: case-file fields as form inputs, and form values back to a validated case.

The field list, the defaults and every validation rule come from the case module
(``solver.case.FIELDS``, ``Case.with_values``), so the app validates exactly like case files do.
This module only converts between form text and typed values, and routes each problem message to
the form field whose case-file key it names. A field's form name is the last segment of its
dotted key (unique), which is also the element id ``field-<name>`` in the page.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass

from solver import CaseError

INLINE_TABLE = "(inline table)"  # shown for a material given as an inline table (not editable here)
#: The hint of a field whose key the case gives as a time history (shown, not edited, in the form).
HISTORY_HINT = "time history: shown here, not edited; edit the case file to change it"


@dataclass(frozen=True)
class FormField:
    """One input of the case form."""

    key: str  # dotted case-file key, e.g. "operating.axial_load_N"
    name: str  # last key segment, e.g. "axial_load_N"
    kind: str  # "int" | "float" | "str" | "bool" | "choice" | "material"
    label: str  # with the unit, e.g. "Axial load (N)"
    unit: str
    help: str
    choices: tuple = ()
    section: str = ""
    required: bool = False
    default_text: str = ""  # value used when the field is left empty, with its unit ("" if none)


def default_text(spec) -> str:
    """What the solver uses when the field ``spec`` (a schema Field) is left empty, in words.

    A plain default with its unit ("0.01 Pa s", "outer_ring"); an estimated default as its rule
    ("estimated: 0.028 D", see :func:`estimated_default_texts` for the value of a given case);
    "" for a required key or one with no default (an absent shoulder, the free contact angle).
    Every value is the schema's default (``spec.default``).
    """
    from solver import OPTIONAL, REQUIRED, Estimated, format_number

    if spec.default is REQUIRED or spec.default is OPTIONAL:
        return ""
    if isinstance(spec.default, Estimated):
        return f"estimated: {spec.default.description}"
    if isinstance(spec.default, str):
        value = spec.default
    else:
        value = format_number(spec.default)
    if not value:
        return ""
    return f"{value} {spec.unit}" if spec.unit and spec.type in ("float", "int") else value


def form_fields() -> list[FormField]:
    """Form fields for every case-file key, in the case module's order (``solver.case.FIELDS``)
    (the case form adds the bearing set's, :func:`set_form_fields`)."""
    from solver import BUILTIN_MATERIALS, FIELDS, REQUIRED

    fields = []
    for spec in FIELDS:
        kind = (
            spec.type
            if spec.type in ("int", "float", "str", "bool", "choice", "material")
            else "str"
        )
        choices = tuple(spec.choices) if kind == "choice" else ()
        if kind == "material":
            choices = tuple(BUILTIN_MATERIALS)
        label = f"{spec.label} ({spec.unit})" if spec.unit else spec.label
        fields.append(
            FormField(
                key=spec.key,
                name=spec.name,
                kind=kind,
                label=label,
                unit=spec.unit,
                help=spec.help,
                choices=choices,
                section=spec.section,
                required=spec.default is REQUIRED,
                default_text=default_text(spec),
            )
        )
    return fields


def set_form_fields() -> list[FormField]:
    """Form fields of a bearing set's ``[set]`` table that the app edits: the named arrangement
    and the preload (its kind and the value each kind reads); the choices and defaults are the
    case module's (:mod:`solver.case.bearing_set`), the rules too (``Case.with_values``). Their
    section is ``"set"``: the form shows them for a set case only."""
    from solver import (
        ARRANGEMENTS,
        DEFAULT_PRELOAD_KIND,
        DIRECTIONS,
        PRELOAD_KINDS,
    )

    def field(key, name, kind, label, unit, help, choices=(), default=""):
        shown = f"{label} ({unit})" if unit else label
        return FormField(key, name, kind, shown, unit, help, tuple(choices), "set", False, default)

    return [
        field(
            "set.arrangement",
            "set_arrangement",
            "choice",
            "Arrangement",
            "",
            "The named arrangement: DB back-to-back (O), DF face-to-face (X), DT tandem; TBT, TFT "
            "of three, QBC, QFC of four bearings (docs/case-format.md, Bearing sets)",
            tuple(ARRANGEMENTS),
        ),
        field(
            "set.preload.kind",
            "preload_kind",
            "choice",
            "Preload",
            "",
            "none; force: the preload force at assembly (fixed position); offset: the axial "
            "offset of the rings; spring: a spring force on the outer rings of one side",
            PRELOAD_KINDS,
            DEFAULT_PRELOAD_KIND,
        ),
        field(
            "set.preload.force_N",
            "preload_force_N",
            "float",
            "Preload force",
            "N",
            "The preload force at assembly (preload force) or the spring force (preload spring)",
        ),
        field(
            "set.preload.offset_um",
            "preload_offset_um",
            "float",
            "Preload offset",
            "µm",
            "The axial offset of the rings at assembly (preload offset)",
        ),
        field(
            "set.preload.spring_side",
            "preload_spring_side",
            "choice",
            "Spring side",
            "",
            "The direction of the bearings whose outer rings the spring pushes (preload spring)",
            DIRECTIONS,
        ),
    ]


def estimated_default_texts(case, fields: list[FormField]) -> dict[str, str]:
    """{field name: text} for the estimated fields of ``case``: the value the solver estimates
    from its bearing, with its unit and rule, e.g. "0.2 mm (estimated: 0.028 D)"."""
    from solver import fields_by_key

    specs = fields_by_key()
    out = {}
    for f in fields:
        spec = specs.get(f.key)
        if spec is None or not spec.estimated:
            continue
        if spec.default.reads != "bearing":  # estimated from a time history: the case's value
            value = getattr(getattr(case, spec.section, None), spec.name, None)
            if value is None:  # a steady case: the key is not read
                continue
            value = float(value)
        else:
            value = float(spec.default.function(case.bearing))
        unit = f" {spec.unit}" if spec.unit else ""
        out[f.name] = f"{value:.3g}{unit} ({f.default_text})"
    return out


def history_texts(case) -> dict[str, str]:
    """{dotted key: the history in words} for the operating keys ``case`` gives as time
    histories, as ``racetrace check`` prints them (e.g. "smooth ramp from 0 to 20000 rpm, 0 s to
    0.3 s"); {} for a steady case."""
    from solver import fields_by_key

    histories = getattr(case, "histories", None) or {}
    specs = fields_by_key()
    return {key: history.describe(specs[key].unit) for key, history in histories.items()}


def case_form_values(case, fields: list[FormField]) -> dict[str, object]:
    """Form values (by field name) of ``case`` as written in its file; absent keys give ``None``.

    Values the case module estimates (cage defaults) are not written, so they show as empty
    fields that keep following the bearing. A key given as a time history gives the history in
    words (:func:`history_texts`): the form shows it and :func:`apply_form` keeps the history.
    """
    data = case.to_dict() if hasattr(case, "to_dict") else tomllib.loads(case.to_toml())
    histories = history_texts(case)
    values = {}
    for f in fields:
        if f.key in histories:
            values[f.name] = histories[f.key]
            continue
        node = data
        for part in f.key.split("."):
            node = node.get(part) if isinstance(node, dict) else None
        if isinstance(node, dict):
            node = INLINE_TABLE if f.kind == "material" else None
        values[f.name] = node
    return values


def form_text(value) -> str:
    """Text of a typed value in a form input ("true"/"false" as in case files for booleans)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def parse_value(field: FormField, raw):
    """Typed value of a form entry, ``None`` for an empty entry; ValueError with a message."""
    if raw is None or (isinstance(raw, str) and raw.strip() == ""):
        return None
    if field.kind == "bool":
        if isinstance(raw, bool):
            return raw
        text = str(raw).strip().lower()
        if text in ("true", "yes", "1", "on"):
            return True
        if text in ("false", "no", "0", "off"):
            return False
        raise ValueError(f"{field.key} = {raw!r}: must be true or false")
    if field.kind in ("str", "choice", "material"):
        return str(raw).strip()
    text = str(raw).strip()
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"{field.key} = {text!r}: must be a number") from None
    if field.kind == "int":
        if not math.isfinite(value) or value != int(value):
            raise ValueError(f"{field.key} = {text!r}: must be a whole number")
        return int(value)
    return value


@dataclass(frozen=True)
class FormResult:
    """Outcome of :func:`apply_form`: the case (None when invalid) and messages by field name."""

    case: object
    errors: dict  # field name -> message
    general: tuple = ()  # messages that name no form field

    @property
    def valid(self) -> bool:
        return self.case is not None and not self.errors and not self.general


def apply_form(base_case, fields: list[FormField], values: dict) -> FormResult:
    """Validate form ``values`` (by field name) as changes to ``base_case``.

    A key ``base_case`` gives as a time history is not read from the form: the history is kept
    as it is (the form shows it in words and does not edit it)."""
    errors, changes = {}, {}
    current = case_form_values(base_case, fields)
    histories = getattr(base_case, "histories", None) or {}
    for f in fields:
        if f.name not in values or f.key in histories:
            continue
        try:
            value = parse_value(f, values[f.name])
        except ValueError as error:
            errors[f.name] = str(error)
            continue
        if value == INLINE_TABLE or value == current.get(f.name):
            continue
        changes[f.key] = value
    if errors:
        return FormResult(None, errors)
    if not changes:
        return FormResult(base_case, {})
    try:
        case = base_case.with_values(changes)
    except CaseError as error:
        errors, general = route_problems(error.problems, fields)
        return FormResult(None, errors, general)
    return FormResult(case, {})


def route_problems(problems, fields: list[FormField]) -> tuple[dict, tuple]:
    """({field name: message}, general messages) for a list of :class:`solver.errors.Problem`.

    A problem reaches every field it concerns: its own key and its related keys (a rule between
    two keys shows at both fields). Problems that name no form field are general.
    """
    by_key = {f.key: f.name for f in fields}
    errors: dict[str, str] = {}
    general: list[str] = []
    for problem in problems:
        names = [by_key[k] for k in problem.keys if k in by_key]
        if not names:
            general.append(problem.message)
        for name in names:
            if name not in errors:
                errors[name] = problem.message
            elif problem.message not in errors[name]:
                errors[name] = f"{errors[name]}; {problem.message}"
    return errors, tuple(general)
