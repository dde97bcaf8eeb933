"""Texts of validation messages: a value as a case file writes it, and the message for an unknown
key with the closest known name (shared by :mod:`.validate` and :mod:`.history`)."""

from __future__ import annotations

import difflib

from solver.errors import Problem

from .schema import format_number

#: Longest value text quoted in a message; longer values are cut (a message stays readable).
_SHOWN_LENGTH = 80


def show(value) -> str:
    """A value as it would appear in a case file (strings quoted, numbers short), cut to at most
    about 80 characters."""
    if isinstance(value, str):
        text = '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    elif isinstance(value, bool | int | float):
        text = format_number(value)
    elif isinstance(value, dict):
        text = "{ " + ", ".join(f"{k} = {show(v)}" for k, v in value.items()) + " }"
    elif isinstance(value, list):
        text = "[" + ", ".join(show(v) for v in value) + "]"
    else:
        text = str(value)
    if len(text) > _SHOWN_LENGTH:
        text = text[: _SHOWN_LENGTH - 5] + " ..." + text[-1]
    return text


def _suggest(name: str, candidates) -> str | None:
    matches = difflib.get_close_matches(name, list(candidates), n=1, cutoff=0.6)
    return matches[0] if matches else None


def _unknown_in_table(problems: list[Problem], table: str, name: str, value, allowed) -> None:
    """Record the unknown key ``name`` of the inline table ``table`` (a dotted key), with the
    closest of the ``allowed`` names as a suggestion."""
    suggestion = _suggest(name, allowed)
    key = f"{table}.{name}"
    problems.append(
        Problem(
            key, _unknown_key_message(key, value, suggestion and f"{table}.{suggestion}", allowed)
        )
    )


def _unknown_key_message(key: str, value, suggestion: str | None, allowed: list[str]) -> str:
    head = f"unknown key {key} = {show(value)}"
    if suggestion:
        return (
            f"{head}: did you mean {suggestion}? "
            "(unknown keys are rejected so that a typo is not ignored)"
        )
    return f"{head}: not a case key; valid keys here: {', '.join(allowed)}"


__all__ = ["show"]
