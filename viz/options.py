"""The drawing options of the bearing scene (:class:`viz.scene.BearingScene`), set by the user."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from .layers import LAYERS

DEFAULT_HIDDEN = ("traces",)  # layers off unless asked for: the painted tracks show the paths


@dataclass
class SceneOptions:
    """User-controlled drawing options."""

    exaggeration: float = 1.0  # across-groove deviation factor for traces and ellipse centres
    trace_ball: int | None = None  # None: all balls
    layers: dict = field(
        default_factory=lambda: {name: name not in DEFAULT_HIDDEN for name in LAYERS}
    )
    ellipse_scale: float = 1.0  # drawn size of the contact ellipses / true size
    track_quantity: str = "dwell"  # colour of the painted tracks: "dwell" or "peak_pressure"
    track_whole_run: bool = False  # paint the whole run (True) or up to the current frame
    # Outer ring drawn apart from the inner one along -x (ball diameters), so that its raceway is
    # seen from the camera side past the inner ring; 0 draws the bearing assembled.
    explode: float = 2.2
    closeup_ball: int = 0  # the ball the "close-up" camera follows
    # Outer ring sector cut away (rad, ring-frame azimuth from +y towards +z), centred on the side
    # the isometric camera looks at, so the balls, cage and raceways show; an opaque cut-away ring
    # renders ~2x faster than a translucent one in software.
    outer_cutaway: tuple = (math.radians(-90.0), math.radians(90.0))
    # Balls drawn see-through (their marking stays opaque enough to read the spin) so the contact
    # ellipses and traces under them show.
    translucent_balls: bool = True
    # Side (rad, azimuth from +y towards +z) the isometric and radial cameras face: the radial-load
    # direction of the shipped cases, where the load zone is.
    view_azimuth: float = 0.0

    def visible(self, layer: str) -> bool:
        """Whether ``layer`` (:data:`viz.layers.LAYERS`) is shown."""
        return bool(self.layers.get(layer, True))
