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
    if isinstance(value, list | tuple):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise TypeError(f"cannot write {value!r} to a case file")


def _line(text: str, comment: str) -> str:
    if not comment:
        return text
    pad = max(_COMMENT_COLUMN - len(text), 1)
    return f"{text}{' ' * pad}# {comment}"


def _unit_comment(f) -> str:
    return f.help


def _history_value(history, inline_files: bool):
    """The inline table of a key's history as written; a history read from a file as its table
    of points when ``inline_files``."""
    if inline_files and history.form == "file":
        table = [[t, v] for t, v in zip(history.times, history.values, strict=True)]
        out = {"table": table}
        if "interpolation" in history.spec:
            out["interpolation"] = history.spec["interpolation"]
        return out
    return history.spec


def _section_lines(case, section: str, prefix: str = "", inline_files: bool = False) -> list[str]:
    """The key lines of one section (estimated values and absent optional keys as comments);
    ``prefix`` "# " writes every line as a comment; ``inline_files``: see :func:`case_to_toml`."""
    obj = getattr(case, section)
    histories = getattr(case, "histories", {})
    kind = "history" if histories else "steady"
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
        if f.key in histories:
            history = histories[f.key]
            value = _history_value(history, inline_files)
            comment = f"time history: {history.describe(f.unit)}"
            if value is not history.spec:
                comment += f" (read from {history.spec['file']})"
            lines.append(_line(f"{prefix}{f.name} = {toml_value(value)}", comment))
        elif f.applies not in ("", kind):
            lines.append(_line(f"# {f.name} =", f"read only by a {f.applies} case: {f.help}"))
        elif f.key in case.estimated:
            rule = f.default.description if isinstance(f.default, Estimated) else ""
            source = getattr(f.default, "reads", "bearing")
            lines.append(
                _line(f"# {f.name} = {toml_value(value)}", f"estimated from the {source}: {rule}")
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


def case_to_toml(case, inline_files: bool = False) -> str:
    """Readable TOML text of a validated :class:`solver.case.model.Case`.

    A ``[lubricant]`` section the case does not give is written as comments holding the default
    oil the models use, so that loading the text gives an equal case. A time history is written
    as given, with its description as a comment; ``inline_files`` writes a history read from a
    file as the inline table of its points (text that needs no other file).
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
        lines += ["", f"[{section}]", *_section_lines(case, section, "", inline_files)]
    return "\n".join(lines) + "\n"


__all__ = ["case_to_toml", "toml_value", "format_number"]
