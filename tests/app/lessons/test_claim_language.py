"""The condition language of lesson claims: what it reads, what it refuses (in words, never by
running Python), and how a missing or NaN value is reported."""

from __future__ import annotations

import math
import re

import pytest

from app.lessons.claims import (
    Claim,
    ClaimError,
    Sentence,
    binding_problems,
    evaluate,
    parse_condition,
    qualitative_words,
)

RESULTS = ["inner", "outer"]
VALUES = {
    "inner": {"inner_band_thickness": 12.0, "outer_band_thickness": 0.3, "race_control": "outer"},
    "outer": {"inner_band_thickness": 0.02, "outer_band_thickness": 5.0, "cage_slip": None},
}


def _holds(text: str) -> bool:
    return evaluate(parse_condition(text, RESULTS), VALUES, "inner")


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("inner_band_thickness > 5 * outer_band_thickness", True),
        ("inner.inner_band_thickness > 5 * inner.outer_band_thickness", True),
        ("outer.inner_band_thickness > 5 * outer.outer_band_thickness", False),
        ("0 < outer_band_thickness < 1", True),
        ("0 < outer_band_thickness < 0.1", False),
        ("abs(outer_band_thickness - 1) < 1 and not inner_band_thickness < 1", True),
        ("min(inner_band_thickness, 3) == 3 or max(1, 2) > 5 + outer_band_thickness", True),
        ("-inner_band_thickness / 2 <= -6", True),
        ("race_control == 'outer'", True),
        ("race_control != 'outer'", False),
    ],
)
def test_conditions_evaluate(text, expected):
    assert _holds(text) is expected


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("__import__('os').system('true') == 0", "functions are abs"),
        ("inner_band_thickness.real > 0", "names the result 'inner_band_thickness'"),
        ("inner.inner_band_thickness.real > 0", "a value is written name or result.name"),
        ("inner_band_thickness ** 2 > 0", "no **"),
        ("inner_band_thickness in [1, 2]", "comparisons are"),
        ("[x for x in ()] == 1", "not part of the condition language"),
        ("lambda: 1", "not part of the condition language"),
        ("inner_band_thickness > True", "constants are numbers"),
        ("abs(inner_band_thickness, 2) > 0", "abs takes one value"),
        ("max(inner_band_thickness, key=abs) > 0", "functions are abs"),
        ("inner_band_thickness >", "not a condition"),
        ("inner_band_thickness + 1", "must compare"),
        ("1 < 2", "names no value"),
        ("", "empty"),
        ("bogus_value > 1", "unknown value 'bogus_value'"),
        ("other.inner_band_thickness > 1", "names the result 'other'"),
    ],
)
def test_conditions_outside_the_language_are_refused_in_words(text, expected):
    with pytest.raises(ValueError, match=re.escape(expected)):
        parse_condition(text, RESULTS)


def test_a_missing_or_nan_value_is_named():
    with pytest.raises(ClaimError, match="outer.cage_slip is missing or not a number"):
        _holds("outer.cage_slip > 0")
    values = {"inner": {"inner_band_thickness": math.nan}}
    with pytest.raises(ClaimError, match="inner_band_thickness is missing or not a number"):
        evaluate(parse_condition("inner_band_thickness > 0", RESULTS), values, "inner")
    with pytest.raises(ClaimError, match="division by zero"):
        _holds("inner_band_thickness / (outer.outer_band_thickness - 5) > 0")


def _sentence(text, claims=(), descriptive=False):
    parsed = tuple(Claim(says, parse_condition(cond, RESULTS)) for says, cond in claims)
    return Sentence(text, parsed, descriptive)


def test_binding_a_claim_to_its_sentence():
    claim = [("the inner track is a band", "inner_band_thickness > 5 * outer_band_thickness")]
    good = _sentence("So the inner track is a band {inner_band_thickness:.1f}° thick.", claim)
    assert binding_problems([good]) == []
    swapped = _sentence("So the inner track is a thin line {inner_band_thickness:.1f}°.", claim)
    (problem,) = binding_problems([swapped])
    assert "sentence 1" in problem and "quotes words the sentence does not say" in problem
    bare = _sentence("So the inner track is a band.")
    assert "neither a claim nor descriptive" in binding_problems([bare])[0]
    hidden = _sentence("The balls do not skid.", descriptive=True)
    assert "says not, skid" in binding_problems([hidden])[0]
    assert binding_problems([_sentence("The cage holds the balls.", descriptive=True)]) == []


def test_qualitative_words_leave_placeholders_out():
    assert qualitative_words("A {inner_band_thickness} band, not {thin}.") == ["band", "not"]
