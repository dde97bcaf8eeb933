"""The length of a case's dynamic run in words, and its size before it runs.

A steady case runs ``[simulation] shaft_revolutions`` sampled ``samples_per_revolution`` times
each; a case with a time history runs ``duration_s`` seconds sampled ``samples_per_second`` times
each (docs/case-format.md, "Time histories"). The views, the run titles and the note under Run
read the run length through these functions, so neither kind of case shows the other's keys.
"""

from __future__ import annotations


def has_history(case) -> bool:
    """True when an operating key of ``case`` is a time history (the run is a duration in s)."""
    return bool(getattr(case, "histories", None))


def run_length_words(case) -> str:
    """The run length as a title says it: "10 rev" (steady) or "0.4 s" (a time history); ""
    when the case gives none."""
    sim = getattr(case, "simulation", None)
    if has_history(case):
        duration = getattr(sim, "duration_s", None)
        return f"{duration:g} s" if duration else ""
    revolutions = getattr(sim, "shaft_revolutions", None)
    return f"{revolutions:g} rev" if revolutions else ""


def run_size_text(case) -> str:
    """What Run will compute for ``case``, e.g. "dynamic run: 0.4 s at 20 000 samples per
    second: 8 000 samples, result file about 48 MB" ("" for a case without a run length).

    Sizes are the solver's estimates (``solver.dynamic_run_size``, of every bearing's balls for a
    bearing set)."""
    from solver import dynamic_ball_count, dynamic_run_size

    sim = getattr(case, "simulation", None)
    balls = dynamic_ball_count(case)
    if has_history(case):
        duration, rate = getattr(sim, "duration_s", None), getattr(sim, "samples_per_second", None)
        if not duration or not rate:
            return ""
        size = dynamic_run_size(float(duration), float(rate), balls)
        length = f"{duration:g} s at {_number(rate)} samples per second"
    else:
        revolutions = getattr(sim, "shaft_revolutions", None)
        per_revolution = getattr(sim, "samples_per_revolution", None)
        if not revolutions or not per_revolution:
            return ""
        size = dynamic_run_size(float(revolutions), int(per_revolution), balls)
        length = f"{revolutions:g} shaft revolutions at {per_revolution} samples per revolution"
    return (
        f"dynamic run: {length}: {_number(size.samples)} samples, "
        f"result file about {_megabytes(size.file_bytes)}"
    )


def _number(value: float) -> str:
    """A count or rate with thin groups of thousands: 20 000, 0.5."""
    value = float(value)
    if value == int(value):
        return f"{int(value):,}".replace(",", " ")
    return f"{value:.3g}"


def _megabytes(size: int) -> str:
    mb = size / 1e6
    return f"{mb:.2g} MB" if mb < 10 else f"{mb:.0f} MB"
