"""A study built from the page's inputs: the values typed for a varied key, and the study file
(docs/study-format.md) around the case in the form. Plain text in, text or a clear error out
(no trame, no files written)."""

from __future__ import annotations

import json
import math

import numpy as np

MAX_BUILT_POINTS = 200  # points of a study built in the page
BUILD_MODELS = ("quasistatic", "dynamic", "both")


class StudyInputError(ValueError):
    """A study built in the page cannot be made: the message says what to change."""


def parse_values(text, what: str) -> list[float]:
    """Values typed for a varied key: ``0, 300, 600`` (a list) or ``start:stop:count`` (count
    values from start to stop, both included). StudyInputError naming ``what`` when unreadable."""
    text = str(text or "").strip()
    if not text:
        raise StudyInputError(f"{what}: give values, e.g. 0, 300, 600 or 0:1500:6")
    try:
        if ":" in text:
            parts = [p.strip() for p in text.split(":")]
            if len(parts) != 3:
                raise ValueError
            start, stop, count = float(parts[0]), float(parts[1]), float(parts[2])
            if count != int(count) or not 2 <= count <= MAX_BUILT_POINTS:
                raise StudyInputError(
                    f"{what}: the count in start:stop:count must be a whole number from 2 to "
                    f"{MAX_BUILT_POINTS} (got {parts[2]})"
                )
            values = np.linspace(start, stop, int(count)).tolist()
        else:
            values = [float(v) for v in text.replace(";", ",").split(",") if v.strip()]
    except StudyInputError:
        raise
    except ValueError:
        raise StudyInputError(
            f"{what}: {text!r} is not a list of numbers (0, 300, 600) nor start:stop:count "
            "(0:1500:6)"
        ) from None
    if not all(math.isfinite(v) for v in values):
        raise StudyInputError(f"{what}: values must be finite numbers")
    if len(values) > MAX_BUILT_POINTS:
        raise StudyInputError(f"{what}: at most {MAX_BUILT_POINTS} values")
    return [round(v, 12) for v in values]


def build_study_text(
    title: str,
    varied: list[tuple[str, list[float]]],
    combine: str,
    model: str,
    revolutions,
    base: str = "base.toml",
    duration_s: float | None = None,
) -> str:
    """The study file (docs/study-format.md) of a study around the case file ``base``: the keys
    of ``varied`` take their lists of values, ``combine``d; ``model`` runs at each point; the
    dynamic points run ``revolutions`` shaft revolutions. A base case with a time history runs
    for a duration in seconds, not for shaft revolutions (docs/case-format.md): give its
    ``duration_s`` and every point runs that long (``simulation.duration_s`` under ``[set]``;
    ``revolutions`` is not read). StudyInputError says what is wrong."""
    if combine not in ("grid", "zip"):
        raise StudyInputError(f"combine: {combine!r} is not grid or zip")
    if model not in BUILD_MODELS:
        raise StudyInputError(f"model: {model!r} is not one of {', '.join(BUILD_MODELS)}")
    keys = [k for k, _ in varied]
    if len(set(keys)) != len(keys):
        raise StudyInputError("the two varied keys are the same: choose another second key")
    if combine == "zip" and len({len(v) for _, v in varied}) > 1:
        lengths = " and ".join(str(len(v)) for _, v in varied)
        raise StudyInputError(
            f"zipped keys need as many values each (got {lengths}): give equal lists or use grid"
        )
    points = math.prod(len(v) for _, v in varied) if combine == "grid" else len(varied[0][1])
    if points > MAX_BUILT_POINTS:
        raise StudyInputError(
            f"{points} points: at most {MAX_BUILT_POINTS} from the page (use racetrace study for "
            "more)"
        )
    lines = [
        f"title = {json.dumps(title)}",
        f"base = {json.dumps(base)}",
        f'model = "{model}"',
        f'combine = "{combine}"',
    ]
    if model != "quasistatic" and duration_s is not None:
        seconds = float(duration_s)
        if not (math.isfinite(seconds) and seconds > 0):
            raise StudyInputError(
                f"run length: the case's simulation.duration_s = {duration_s!r} is not a "
                "duration above 0 s"
            )
        lines += ["", "[set]", f'"simulation.duration_s" = {seconds!r}']
    elif model != "quasistatic":
        try:
            revs = float(revolutions)
        except (TypeError, ValueError):
            raise StudyInputError(
                f"run length: {revolutions!r} is not a number of shaft revolutions"
            ) from None
        if not (math.isfinite(revs) and revs > 0):
            raise StudyInputError("run length: give a number of shaft revolutions above 0")
        lines += ["", "[run]", f"shaft_revolutions = {revs!r}"]
    lines += ["", "[vary]"]
    for key, values in varied:
        lines.append(f'"{key}" = [{", ".join(repr(float(v)) for v in values)}]')
    return "\n".join(lines) + "\n"
