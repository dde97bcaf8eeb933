"""The frame source of :mod:`viz.frames`, under the name :mod:`app.charts` imports it by."""

from viz.frames import RPM, TWO_PI, FrameSource, frame_source

__all__ = ["RPM", "TWO_PI", "FrameSource", "frame_source"]
