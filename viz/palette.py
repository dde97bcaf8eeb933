"""The colour palettes, defined once: per-ball colours (3-D balls and traces, the raceway map
coloured by ball, the ball legend) and per-run colours (compared runs in the app).

Colours are CSS hex strings. No rendering, no trame.
"""

from __future__ import annotations

import colorsys

# The first 20 balls get these (dark shades first, then their light partners); more balls get
# hues spaced by the golden angle, so that no two balls of a bearing share a colour.
BALL_PALETTE = (
    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
    "#bcbd22", "#17becf", "#aec7e8", "#ffbb78", "#98df8a", "#ff9896", "#c5b0d5", "#c49c94",
    "#f7b6d2", "#c7c7c7", "#dbdb8d", "#9edae5",
)  # fmt: skip
_GOLDEN = 0.381966  # 1 - 1/phi: successive hues as far apart as possible


def _hex(rgb) -> str:
    return "#" + "".join(f"{round(255 * c):02x}" for c in rgb)


def ball_colour(j: int) -> str:
    """Colour of ball ``j`` (0-based, as the results' ``ball`` coordinate)."""
    if j < 0:
        raise ValueError(f"ball number {j} is negative; balls are numbered from 0")
    if j < len(BALL_PALETTE):
        return BALL_PALETTE[j]
    k = j - len(BALL_PALETTE)
    hue = (0.07 + k * _GOLDEN) % 1.0
    value = (0.55, 0.8)[k % 2]
    return _hex(colorsys.hsv_to_rgb(hue, 0.75, value))


def ball_colours(n: int) -> list[str]:
    """Colours of balls 0 .. n-1, all different."""
    return [ball_colour(j) for j in range(n)]


def ball_legend(n: int) -> list[dict]:
    """The ball legend of a bearing with ``n`` balls: ``[{"ball": j, "colour": "#..."}]``."""
    return [{"ball": j, "colour": c} for j, c in enumerate(ball_colours(n))]


# Compared runs: A (the run on show) blue, then orange, green, purple ... (the inner race in the
# run's colour, the outer race in a darker shade of it).
RUN_PALETTE = (
    "#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#d62728", "#8c564b", "#e377c2", "#17becf",
    "#bcbd22", "#7f7f7f",
)  # fmt: skip
RUN_SYMBOLS = ("circle", "x", "diamond", "square", "triangle-up", "star", "cross", "pentagon")
RUN_DASHES = ("solid", "dash", "dot", "dashdot", "longdash", "longdashdot")
MAX_COMPARED = len(RUN_PALETTE)  # runs drawn at once (the one on show included)


def run_tag(i: int) -> str:
    """Tag of the ``i``-th compared run: A (the run on show), B, C ..."""
    return chr(ord("A") + i)


def darker(colour: str, factor: float = 0.55) -> str:
    """``colour`` with its brightness times ``factor``."""
    rgb = [int(colour[k : k + 2], 16) / 255 for k in (1, 3, 5)]
    h, s, v = colorsys.rgb_to_hsv(*rgb)
    return _hex(colorsys.hsv_to_rgb(h, s, v * factor))


def run_colours(i: int) -> dict:
    """Colours of the ``i``-th compared run: ``{"run": c, 0: inner race, 1: outer race}``."""
    base = RUN_PALETTE[i % len(RUN_PALETTE)]
    return {"run": base, 0: base, 1: darker(base)}


def run_style(i: int) -> dict:
    """Marker symbol and line dash of the ``i``-th compared run."""
    return {
        "symbol": RUN_SYMBOLS[i % len(RUN_SYMBOLS)],
        "dash": RUN_DASHES[i % len(RUN_DASHES)],
        "size": 5 if i == 0 else 6,
    }
