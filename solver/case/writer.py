"""Case → TOML text: readable (sections in the order of case-format.md, a help comment per key),
and exact (floats written with their shortest round-trip representation), so that loading the text
gives an equal case.
"""

from __future__ import annotations

import tomli_w

from .schema import FIELDS, MATERIAL_FIELDS, SECTION_ORDER, Estimated, format_number

_COMMENT_COLUMN = 44


def toml_value(value) -> str:
    """One TOML value: floats by repr (exact), strings quoted and escaped, dicts inline."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value)  # shortest text that reads back to the same double; finite here
    if isinstance(value, str):
        return tomli_w.dumps({"v": value}).split("=", 1)[1].strip()
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{k} = {toml_value(v)}" for k, v in value.items()) + " }"
    raise TypeError(f"cannot write {value!r} to a case file")


def _line(text: str, comment: str) -> str:
    if not comment:
        return text
    pad = max(_COMMENT_COLUMN - len(text), 1)
    return f"{text}{' ' * pad}# {comment}"


def _unit_comment(f) -> str:
    return f.help


def _section_lines(case, section: str, prefix: str = "") -> list[str]:
    """The key lines of one section (estimated values and absent optional keys as comments);
    ``prefix`` "# " writes every line as a comment."""
    obj = getattr(case, section)
    lines: list[str] = []
    subtables: dict[str, list] = {}
    for f in FIELDS:
        if f.section != section:
            continue
        if len(f.path) > 2:
            subtables.setdefault(f.path[1], []).append(f)
            if len(subtables[f.path[1]]) == 1:
                lines.append(f"@@{f.path[1]}")  # placeholder, filled below
            continue
        value = getattr(obj, f.name)
        if f.key in case.estimated:
            rule = f.default.description if isinstance(f.default, Estimated) else ""
            lines.append(
                _line(f"# {f.name} = {toml_value(value)}", f"estimated from the bearing: {rule}")
            )
        elif f.key in case.from_oil:
            oil = case.lubricant.oil
            lines.append(_line(f"# {f.name} = {toml_value(value)}", f"from the named oil {oil}"))
        elif value is None:
            lines.append(_line(f"# {f.name} =", f"optional: {f.help}"))
        else:
            lines.append(_line(f"{prefix}{f.name} = {toml_value(value)}", _unit_comment(f)))
    for name, fields in subtables.items():
        sub = getattr(obj, name)
        table = {f.name: getattr(sub, f.name) for f in fields}
        idx = lines.index(f"@@{name}")
        line = f"{prefix}{name} = {toml_value(table)}"
        if (section, name) == ("lubricant", "traction") and not case.traction_given:
            line = _line(
                f"# {name} = {toml_value(table)}",
                'default curve, read only by traction_model = "slip_curve"',
            )
        lines[idx] = line
    return lines


def case_to_toml(case) -> str:
    """Readable TOML text of a validated :class:`solver.case.model.Case`.

    A ``[lubricant]`` section the case does not give is written as comments holding the default
    oil the models use, so that loading the text gives an equal case.
    """
    lines = [f"title = {toml_value(case.title)}"]
    if case.description:
        lines.append(f"description = {toml_value(case.description)}")
    for section in SECTION_ORDER:
        if section == "materials":
            for name, table in case.materials.items():
                lines += ["", f"[materials.{name}]"]
                for m in MATERIAL_FIELDS:
                    lines.append(_line(f"{m.key} = {toml_value(table[m.key])}", m.help))
            continue
        if section == "lubricant" and not case.lubricant_given:
            lines += [
                "",
                "# [lubricant] not given: the dynamic model (and the quasi-static traction "
                "balance) use the default oil below",
            ]
            lines += _section_lines(case, section, prefix="# ")
            continue
        lines += ["", f"[{section}]", *_section_lines(case, section)]
    return "\n".join(lines) + "\n"


__all__ = ["case_to_toml", "toml_value", "format_number"]
