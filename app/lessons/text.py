"""Filling a lesson's text templates with the values of its results (app.lessons.values).

A placeholder is ``{value}`` (the lesson's first result) or ``{result.value}`` (a named result),
with an optional number format after a colon: ``{rest.outer_contact_angle:.1f}``. Values that are
words are written as they are; a value the result does not have is written in words, never as
"nan". Line breaks inside a paragraph are joined (:func:`paragraphs`).
"""

from __future__ import annotations

from .format import Lesson, placeholders


def fill(template: str, values: dict[str, dict[str, object]], default: str) -> str:
    """``template`` with each placeholder replaced; ``values`` maps result name -> its values
    (lesson_values), ``default`` is the result a bare ``{value}`` reads. The template was checked
    when its lesson was read (format.parse_lesson)."""
    import string

    parts = []
    for literal, field, spec, _ in string.Formatter().parse(template):
        parts.append(literal)
        if field is None:
            continue
        result, _, name = field.rpartition(".")
        value = values[result or default].get(name)
        if value is None:
            parts.append(f"(no {name.replace('_', ' ')} in this result)")
        elif isinstance(value, str):
            parts.append(value)
        else:
            parts.append(format(value, spec or "g"))
    return paragraphs("".join(parts))


def paragraphs(text: str) -> str:
    """Text with the line breaks of a TOML multi-line string joined: lines within a paragraph
    become one line; paragraphs stay separated by one blank line."""
    blocks = [" ".join(block.split()) for block in text.strip().split("\n\n")]
    return "\n\n".join(block for block in blocks if block)


def lesson_text(lesson: Lesson, values: dict[str, dict[str, object]]) -> tuple[str, str]:
    """(explanation, try-this prompt) of ``lesson`` filled from ``values`` (result name -> values
    of that result)."""
    default = lesson.results[0].name
    return fill(lesson.explain, values, default), fill(lesson.try_this, values, default)


__all__ = ["fill", "lesson_text", "paragraphs", "placeholders"]
