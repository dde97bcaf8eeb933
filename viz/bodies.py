"""The bearing's solid parts in the scene: inner ring, outer ring (cut away and drawn apart),
balls and cage, moved frame by frame by 4x4 user matrices (inertial frame, m)."""

from __future__ import annotations

import math

import numpy as np
import pyvista as pv

from .frames import rot_x
from .layout import RacewayLayout
from .meshes import RING_COLOUR, RING_PHI_POINTS, cage_mesh, marked_sphere, placement, revolve
from .palette import ball_colours
from .raceway import INNER, OUTER

BALL_OPACITY = (0.15, 0.6)  # (plain, marked) octants of a translucent ball
CAGE_OPACITY = 0.45  # the cage hoops pass in front of the inner raceway: the track shows through


class BearingBodies:
    """Rings, balls and cage of ``geometry`` in ``plotter``; ``actors`` by layer name."""

    def __init__(
        self,
        plotter: pv.Plotter,
        geometry,
        layout: RacewayLayout,
        translucent_balls: bool = True,
        dark_balls: bool = False,
    ):
        g, p = geometry, plotter
        inner = revolve(*layout.profiles[INNER])
        # a dark sector on the inner ring makes its rotation visible
        phi = np.arctan2(inner.cell_centers().points[:, 2], inner.cell_centers().points[:, 1])
        inner.cell_data["mark"] = (np.abs(phi) < math.radians(8)).astype(float)
        self.inner_ring = p.add_mesh(
            inner,
            scalars="mark",
            cmap=[RING_COLOUR, "#2f5597"],
            show_scalar_bar=False,
            smooth_shading=True,
            specular=0.4,
            name="inner_ring",
        )
        self.outer_ring = p.add_mesh(
            revolve(
                *layout.profiles[OUTER],
                n_phi=RING_PHI_POINTS[OUTER],
                phi_range=layout.ring_span(OUTER),
            ),
            color=RING_COLOUR,
            smooth_shading=True,
            specular=0.4,
            name="outer_ring",
        )
        sphere = marked_sphere(0.5 * g.ball_diameter)
        colours = ["#202020", "#6a6a6a"] if dark_balls else ["#d9d9d9", "#7a7a7a"]
        if translucent_balls:
            # see-through balls: plain octants almost clear, marked octants dark enough to read
            colours = ["#9a9a9a", "#1a1a1a"] if dark_balls else ["#d0d0d0", "#4a5560"]
        self.balls = []
        # each ball's marked octants in its own colour (viz.palette; the legend over the view)
        for j, colour in enumerate(ball_colours(g.ball_count)):
            actor = p.add_mesh(
                sphere,
                scalars="mark",
                cmap=[colours[0], colour],
                n_colors=2,
                show_scalar_bar=False,
                smooth_shading=True,
                specular=0.6,
                name=f"ball_{j}",
            )
            if translucent_balls:
                lut = actor.mapper.lookup_table
                rgba = np.array(lut.values)
                rgba[:, 3] = np.round(255 * np.asarray(BALL_OPACITY))
                lut.values = rgba
            self.balls.append(actor)
        self.cage = p.add_mesh(
            cage_mesh(0.5 * g.pitch_diameter, g.ball_diameter, g.ball_count),
            color="#c8842a",
            opacity=CAGE_OPACITY,
            smooth_shading=True,
            name="cage",
        )
        self.actors = {
            "inner_ring": [self.inner_ring],
            "outer_ring": [self.outer_ring],
            "balls": self.balls,
            "cage": [self.cage],
        }

    def move(self, f, rings) -> None:
        """Place the parts at frame ``f`` (:class:`viz.frames.Frame`); ``rings``: the (inner,
        outer) ring matrices."""
        self.inner_ring.user_matrix = rings[INNER]
        self.outer_ring.user_matrix = rings[OUTER]
        for j, actor in enumerate(self.balls):
            actor.user_matrix = placement(f.ball_rotation[j], f.ball_center[j])
        self.cage.user_matrix = placement(rot_x(f.cage_angle))

    def show_alone(self, ball: int | None, options, without_balls: bool = False) -> None:
        """Show ball ``ball`` alone, without cage and outer ring (the close-up), or (None) every
        part whose layer ``options`` shows; ``without_balls``: no ball and no cage either (the
        inner track seen past them)."""
        for k, actor in enumerate(self.balls):
            shown = options.visible("balls") and (ball is None or k == ball)
            actor.visibility = shown and not without_balls
        for name in ("cage", "outer_ring"):
            for actor in self.actors[name]:
                actor.visibility = options.visible(name) and ball is None
        for actor in self.actors["cage"]:
            actor.visibility = actor.visibility and not without_balls
