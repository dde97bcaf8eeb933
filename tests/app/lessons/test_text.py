"""Filling lesson templates."""

from __future__ import annotations

from app.lessons.text import fill, paragraphs

VALUES = {"a": {"x": 12.345, "w": "outer", "n": None}, "b": {"x": 2.0}}


def test_fill_formats_default_and_named_results():
    assert fill("{x:.1f} and {b.x:.2f}; {{x}}", VALUES, "a") == "12.3 and 2.00; {x}"


def test_words_and_missing_values():
    assert fill("the {w} race, {n:.1f} N", VALUES, "a") == "the outer race, (no n in this result) N"


def test_default_format_is_general():
    assert fill("{x}", VALUES, "a") == "12.345"


def test_paragraphs_join_lines():
    assert paragraphs("\n one\ntwo  \n\n three\n") == "one two\n\nthree"
