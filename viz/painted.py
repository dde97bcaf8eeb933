"""The painted raceways: each groove coloured where the contact ellipses ran (:mod:`viz.tracks`).

One mesh per groove on the ring's own facets (ring frame, m), coloured by a texture of the painted
track: one texel per cell of the fields, the ring's colour where no ellipse has run, the colour
map over the painted cells' range with its colour bar beside the bearing.
"""

from __future__ import annotations

import numpy as np
import pyvista as pv

from .layout import MARK_LIFT, RacewayLayout
from .meshes import GROOVE_ARC_POINTS, RING_COLOUR, RING_PHI_POINTS
from .raceway import INNER, OUTER
from .tracks import (
    QUANTITIES,
    QUANTITY_LABELS,
    QUANTITY_SCALE,
    TrackPainter,
    groove_surface_arrays,
    track_colours,
)

TRACK_CMAP = "YlOrRd"  # pale where a point was run over briefly, dark red where longest
SCALAR_BAR = {  # vertical, in the strip right of the bearing (viz.camera.SCALAR_BAR_STRIP)
    "title": QUANTITY_LABELS["dwell"],
    "vertical": True,
    "position_x": 0.86,
    "position_y": 0.2,
    "width": 0.12,
    "height": 0.6,
    "title_font_size": 13,
    "label_font_size": 12,
    "n_labels": 5,
    "fmt": "%.3g",
    "color": "#202020",
}


class PaintedRaceways:
    """The two painted groove meshes in ``plotter``, their fields and their colour bar."""

    def __init__(self, plotter: pv.Plotter, layout: RacewayLayout):
        self.plotter = plotter
        self.layout = layout
        self.painter: TrackPainter | None = None
        self.track_range = None  # (lo, hi) of the colour bar, in its units, once painted
        self.actors: list = []
        self._meshes, self._texels = [], []
        for race in (INNER, OUTER):
            self._add(race)
        self._bar = None

    def _add(self, race: int) -> None:
        """A mesh of a quad per cell would look the same and render about 7 ms a frame slower in
        software than the texture on the ring's facets."""
        layout = self.layout
        groove, grid = layout.grooves[race], layout.grids[race]
        pts, faces, tcoords = groove_surface_arrays(
            groove,
            grid,
            np.linspace(*layout.ring_span(race), RING_PHI_POINTS[race]),
            GROOVE_ARC_POINTS,
            lift=0.5 * MARK_LIFT * groove.r,
        )
        mesh = pv.PolyData(pts, faces=faces)
        mesh.active_texture_coordinates = tcoords
        mesh.cell_data["track"] = np.full(mesh.n_cells, np.nan)  # gives the colour bar
        self._meshes.append(mesh)
        actor = self.plotter.add_mesh(
            mesh,
            scalars="track",
            cmap=TRACK_CMAP,
            clim=(0.0, 1.0),
            nan_color=RING_COLOUR,
            show_scalar_bar=race == INNER,
            scalar_bar_args=SCALAR_BAR,
            smooth_shading=True,
            specular=0.2,
            name=f"tracks_{race}",
        )
        actor.mapper.scalar_visibility = False  # coloured by the texture instead
        actor.prop.color = "white"  # the texture's colours, lit
        image = pv.ImageData(dimensions=(grid.n_phi, grid.n_alpha, 1))
        image.point_data["rgba"] = np.zeros((grid.n_phi * grid.n_alpha, 4), np.uint8)
        texture = pv.Texture(image)
        texture.interpolate = False  # each cell one colour, as on the colour bar
        texture.repeat = True  # the outer half shell runs past phi = 2 pi
        actor.texture = texture
        self._texels.append(pv.wrap(texture.GetInput()))
        self.actors.append(actor)

    def label_colour_bar(self, quantity: str) -> None:
        """Title the colour bar (the plotter's) for ``quantity`` (:data:`viz.tracks.QUANTITIES`)."""
        if quantity not in QUANTITIES:
            raise ValueError(
                f"unknown track colouring {quantity!r}; use one of {', '.join(QUANTITIES)}"
            )
        if self._bar is None:
            self._bar = self.plotter.scalar_bar
            self._bar.SetVerticalTitleSeparation(10)  # pixels between the title and top label
        self._bar.SetTitle(QUANTITY_LABELS[quantity])

    def use_source(self, source, exaggeration: float, ellipse_scale: float) -> None:
        """Footprints of every sample of ``source`` (:class:`viz.frames.FrameSource`; None:
        nothing to paint) at the display options, the fields emptied."""
        if source is None:
            self.painter = None
            return
        self.painter = TrackPainter(
            source,
            self.layout.grooves,
            self.layout.grids,
            self.layout.reference,
            exaggeration=exaggeration,
            ellipse_scale=ellipse_scale,
        )

    def paint(self, stop: int, quantity: str) -> None:
        """Colour both raceways by ``quantity`` over frames ``[0, stop)``."""
        if self.painter is None:
            return
        self.painter.accumulate(stop)
        scale = QUANTITY_SCALE[quantity]
        lo, hi = self.painter.value_range(quantity)
        lo, hi = lo * scale, hi * scale
        if not hi > lo:
            hi = lo + max(abs(lo), 1.0) * 1e-3
        lut = self.actors[INNER].mapper.lookup_table
        for race in (INNER, OUTER):
            texels = self._texels[race]
            texels.point_data["rgba"][:] = track_colours(
                self.painter.field(race, quantity) * scale,
                self.painter.painted(race),
                lo,
                hi,
                lut.values,
                lut.nan_color.int_rgba,
            )
            texels.Modified()
            self.actors[race].mapper.scalar_range = (lo, hi)
        self.track_range = (lo, hi)

    def move(self, rings) -> None:
        """Turn each painted groove with its ring (``rings``: (inner, outer) 4x4 matrices)."""
        for race in (INNER, OUTER):
            self.actors[race].user_matrix = rings[race]
