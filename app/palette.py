"""The colours of :mod:`viz.palette`, under the name :mod:`app.charts` imports them by."""

from viz.palette import MAX_COMPARED, ball_colours, run_colours, run_style, run_tag

__all__ = ["MAX_COMPARED", "ball_colours", "run_colours", "run_style", "run_tag"]
