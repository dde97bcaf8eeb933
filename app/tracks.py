"""The track painter of :mod:`viz.tracks`, under the name the session fork server imports it by
(:mod:`app.services.preload` compiles its kernel before forking)."""

from viz.tracks import _paint

__all__ = ["_paint"]
