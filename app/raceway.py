"""The race indices of :mod:`viz.raceway`, under the name :mod:`app.charts` imports them by."""

from viz.raceway import INNER, OUTER, RACES

__all__ = ["INNER", "OUTER", "RACES"]
