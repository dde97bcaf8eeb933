"""Claims: the conditions that bind a lesson's qualitative sentences to its results.

A lesson's explanation is a list of sentences (docs/lessons.md). A sentence that says something
about the results ("the outer track is a thin line", "the balls skid") carries claims: each claim
quotes the words of its sentence it stands for and gives a condition over the lesson's own values,
e.g. ``outer_band_thickness < 0.2 * inner_band_thickness``. A sentence that only sets the scene is
marked descriptive and may not use the words of a finding (:data:`QUALITATIVE_WORDS`).

Conditions are a small expression language, parsed with :mod:`ast` and evaluated by walking the
tree (never ``eval``): numbers, quoted words, value names (``value`` of the lesson's first result,
``result.value`` of a named one; the names of :mod:`app.lessons.values`), ``+ - * /``, unary
``-``, ``abs``/``min``/``max``, comparisons (``< <= > >= == !=``, chained), ``and``/``or``/``not``
and parentheses. :func:`parse_condition` checks a condition's grammar and names;
:func:`evaluate` gives its truth for the values of a lesson's results, and raises
:class:`ClaimError` naming the value when one is missing or not a finite number.
"""

from __future__ import annotations

import ast
import math
import operator
import re
from dataclasses import dataclass, field

from .values import VALUE_NAMES

#: Words that state a finding about the results: a descriptive sentence may not use them (a
#: sentence with one of them carries a claim). Matched as whole words, case-insensitive.
QUALITATIVE_WORDS = frozenset(
    """
    above below higher lower larger smaller greater bigger more less fewer most least
    rise rises rising fall falls falling grow grows growing shrink shrinks up down
    same alike equal equally differ differs different unlike
    line lines band bands thin thick wide narrow long short
    skid skids skidding slide slides sliding slip slips roll rolls rolling spin spins spinning
    closer nearer farther further exceed exceeds over beyond within keeps stays still remains
    only no not never nothing none every all both
    """.split()
)

_FUNCTIONS = {"abs": abs, "min": min, "max": max}
_COMPARE = {
    ast.Lt: operator.lt,
    ast.LtE: operator.le,
    ast.Gt: operator.gt,
    ast.GtE: operator.ge,
    ast.Eq: operator.eq,
    ast.NotEq: operator.ne,
}
_ARITHMETIC = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
}
MAX_CONDITION_CHARS = 400


class ClaimError(ValueError):
    """A claim that cannot be read or evaluated; the message names the lesson, the sentence, the
    claim and the fix."""


@dataclass(frozen=True)
class Condition:
    """A parsed condition: its text, its tree and the (result, value) pairs it reads (result
    "" for the lesson's first result)."""

    text: str
    tree: ast.Expression = field(compare=False, repr=False)  # equal conditions: equal texts
    names: tuple[tuple[str, str], ...] = ()


@dataclass(frozen=True)
class Claim:
    """``says``: the words of its sentence the claim stands for (quoted exactly); ``holds``: the
    condition over the lesson's values that makes those words true."""

    says: str
    holds: Condition


@dataclass(frozen=True)
class Sentence:
    """One sentence (or a few) of a lesson's explanation: ``template`` with placeholders, its
    claims, or ``descriptive`` when it states no finding."""

    template: str
    claims: tuple[Claim, ...]
    descriptive: bool


def _dotted(node: ast.AST) -> str | None:
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
        return f"{node.value.id}.{node.attr}"
    return None


def _check_node(node: ast.AST, names: list[tuple[str, str]], results: list[str]) -> None:
    """Raise ValueError (in words) for a node the language does not have; collect value names."""
    if isinstance(node, ast.Expression):
        _check_node(node.body, names, results)
    elif isinstance(node, ast.BoolOp):
        for value in node.values:
            _check_node(value, names, results)
    elif isinstance(node, ast.UnaryOp):
        if not isinstance(node.op, ast.Not | ast.USub | ast.UAdd):
            raise ValueError("only not, - and + go before a value")
        _check_node(node.operand, names, results)
    elif isinstance(node, ast.BinOp):
        if type(node.op) not in _ARITHMETIC:
            raise ValueError("the arithmetic is + - * / (no **, //, %)")
        _check_node(node.left, names, results)
        _check_node(node.right, names, results)
    elif isinstance(node, ast.Compare):
        for op in node.ops:
            if type(op) not in _COMPARE:
                raise ValueError("the comparisons are < <= > >= == !=")
        for part in (node.left, *node.comparators):
            _check_node(part, names, results)
    elif isinstance(node, ast.Call):
        func = node.func.id if isinstance(node.func, ast.Name) else None
        if func not in _FUNCTIONS or node.keywords or not node.args:
            raise ValueError("the functions are abs(x), min(x, y, …) and max(x, y, …)")
        if func == "abs" and len(node.args) != 1:
            raise ValueError("abs takes one value")
        for arg in node.args:
            _check_node(arg, names, results)
    elif isinstance(node, ast.Constant):
        if isinstance(node.value, bool) or not isinstance(node.value, int | float | str):
            raise ValueError(f"{node.value!r}: the constants are numbers and quoted words")
    elif isinstance(node, ast.Name | ast.Attribute):
        dotted = _dotted(node)
        if dotted is None:
            raise ValueError("a value is written name or result.name")
        result, _, value = dotted.rpartition(".")
        if result and result not in results:
            raise ValueError(
                f"{dotted!r} names the result {result!r}, but this lesson's results are "
                f"{', '.join(results)}"
            )
        if value not in VALUE_NAMES:
            raise ValueError(
                f"{dotted!r}: unknown value {value!r}; the values are listed in docs/lessons.md"
            )
        names.append((result, value))
    else:
        raise ValueError(f"{type(node).__name__.lower()} is not part of the condition language")


def parse_condition(text: str, results: list[str]) -> Condition:
    """The condition ``text`` checked against the language and the lesson's ``results`` (their
    names); ValueError in words when it is not a condition over them."""
    if not isinstance(text, str) or not text.strip():
        raise ValueError("the condition is empty")
    if len(text) > MAX_CONDITION_CHARS:
        raise ValueError(f"the condition is longer than {MAX_CONDITION_CHARS} characters")
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as error:
        raise ValueError(f"not a condition ({error.msg})") from None
    names: list[tuple[str, str]] = []
    _check_node(tree, names, results)
    if not names:
        raise ValueError("the condition names no value of the lesson, so it cannot fail")
    if not isinstance(tree.body, ast.Compare | ast.BoolOp) and not (
        isinstance(tree.body, ast.UnaryOp) and isinstance(tree.body.op, ast.Not)
    ):
        raise ValueError("the condition must compare (e.g. a < 2 * b), not only compute a value")
    return Condition(text.strip(), tree, tuple(dict.fromkeys(names)))


def _value(values: dict[str, dict[str, object]], default: str, node) -> object:
    dotted = _dotted(node)
    result, _, name = dotted.rpartition(".")
    value = values[result or default].get(name)
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        raise _Missing(dotted)
    return value


class _Missing(Exception):
    """A value the result does not have (or NaN)."""


def _evaluate(node, values, default):
    if isinstance(node, ast.Expression):
        return _evaluate(node.body, values, default)
    if isinstance(node, ast.BoolOp):
        parts = (_evaluate(v, values, default) for v in node.values)
        return all(parts) if isinstance(node.op, ast.And) else any(parts)
    if isinstance(node, ast.UnaryOp):
        operand = _evaluate(node.operand, values, default)
        if isinstance(node.op, ast.Not):
            return not operand
        return -operand if isinstance(node.op, ast.USub) else +operand
    if isinstance(node, ast.BinOp):
        left = _evaluate(node.left, values, default)
        right = _evaluate(node.right, values, default)
        if isinstance(node.op, ast.Div) and right == 0:
            raise ZeroDivisionError("a division by zero")
        return _ARITHMETIC[type(node.op)](left, right)
    if isinstance(node, ast.Compare):
        left = _evaluate(node.left, values, default)
        for op, comparator in zip(node.ops, node.comparators, strict=True):
            right = _evaluate(comparator, values, default)
            if not _COMPARE[type(op)](left, right):
                return False
            left = right
        return True
    if isinstance(node, ast.Call):
        return _FUNCTIONS[node.func.id](*(_evaluate(a, values, default) for a in node.args))
    if isinstance(node, ast.Constant):
        return node.value
    return _value(values, default, node)


def evaluate(condition: Condition, values: dict[str, dict[str, object]], default: str) -> bool:
    """Whether ``condition`` holds for ``values`` (result name -> its lesson values; ``default``
    is the result a bare name reads). ClaimError (without the lesson's context: see
    :func:`check_claims`) when a value is missing or NaN, or the arithmetic fails."""
    try:
        outcome = _evaluate(condition.tree, values, default)
    except _Missing as missing:
        raise ClaimError(
            f"the value {missing.args[0]} is missing or not a number in this result; name a "
            "value the result has (a dynamic run's band thickness, a quasi-static run's "
            "gyroscopic moment)"
        ) from None
    except (TypeError, ZeroDivisionError) as error:
        raise ClaimError(f"it cannot be evaluated: {error}") from None
    if isinstance(outcome, float) and math.isnan(outcome):
        raise ClaimError("it evaluates to NaN")
    return bool(outcome)


def qualitative_words(text: str) -> list[str]:
    """The words of :data:`QUALITATIVE_WORDS` in ``text`` (placeholders left out), in order."""
    words = re.findall(r"[a-z]+", re.sub(r"\{[^}]*\}", " ", text.lower()))
    return list(dict.fromkeys(w for w in words if w in QUALITATIVE_WORDS))


def sentence_words(template: str) -> str:
    """The sentence's words as a claim quotes them: placeholders kept, whitespace collapsed."""
    return " ".join(template.split())


def short(template: str, limit: int = 60) -> str:
    """The start of a sentence, to name it in a message."""
    words = sentence_words(template)
    return words if len(words) <= limit else words[: limit - 1].rstrip() + "…"


@dataclass(frozen=True)
class Outcome:
    """One claim evaluated: where it is (sentence number from 1), the claim, and whether it
    holds."""

    sentence: int
    template: str
    claim: Claim
    holds: bool

    def describe(self, lesson_id: str) -> str:
        return (
            f"lesson {lesson_id}, sentence {self.sentence} ({short(self.template)!r}): claim "
            f"{self.claim.says!r} with condition {self.claim.holds.text!r} "
            + ("holds" if self.holds else "does not hold")
        )


def check_claims(lesson, values: dict[str, dict[str, object]]) -> list[Outcome]:
    """Every claim of ``lesson`` evaluated on ``values`` (result name -> its lesson values).
    ClaimError naming the lesson, the sentence, the claim and the fix when one cannot be
    evaluated."""
    default = lesson.results[0].name
    out = []
    for number, sentence in enumerate(lesson.sentences, start=1):
        for claim in sentence.claims:
            try:
                holds = evaluate(claim.holds, values, default)
            except ClaimError as error:
                raise ClaimError(
                    f"lesson {lesson.id}, sentence {number} ({short(sentence.template)!r}): "
                    f"claim {claim.says!r} ({claim.holds.text}): {error}"
                ) from None
            out.append(Outcome(number, sentence.template, claim, holds))
    return out


def binding_problems(sentences) -> list[str]:
    """What keeps ``sentences`` from binding every finding to a condition: a claim whose quoted
    words are not in its sentence, a sentence with neither claims nor ``descriptive``, a
    descriptive sentence using a word of a finding (:data:`QUALITATIVE_WORDS`)."""
    problems = []
    for number, sentence in enumerate(sentences, start=1):
        where = f"[[text.explain]] sentence {number} ({short(sentence.template)!r})"
        words = sentence_words(sentence.template).lower()
        for claim in sentence.claims:
            if sentence_words(claim.says).lower() not in words:
                problems.append(
                    f"{where}: the claim {claim.says!r} quotes words the sentence does not say; a "
                    "claim quotes its sentence exactly (change both together, and check the "
                    "condition still says the same)"
                )
        if sentence.descriptive and sentence.claims:
            problems.append(f"{where}: a sentence with claims is not descriptive; drop one")
        elif sentence.descriptive:
            found = qualitative_words(sentence.template)
            if found:
                problems.append(
                    f"{where}: marked descriptive, but it says {', '.join(found)}: words of a "
                    'finding; give it a claim (claim."its words" = "a condition")'
                )
        elif not sentence.claims:
            problems.append(
                f"{where}: neither a claim nor descriptive = true; a sentence that says "
                'something about the results carries a claim (claim."its words" = "a condition")'
            )
    return problems


__all__ = [
    "QUALITATIVE_WORDS",
    "Claim",
    "ClaimError",
    "Condition",
    "Outcome",
    "Sentence",
    "binding_problems",
    "check_claims",
    "evaluate",
    "parse_condition",
    "qualitative_words",
    "sentence_words",
]
