"""The teaching overlay of the scene: names of the raceways, the shaft's rotation, the radial load
direction and the tilt axis as labels and arrows, and a legend of the marks.

Drawn in the inertial frame (m); the tilt axis turns with the inner ring when the misalignment
does. The operating point is read from an object with the attributes ``inner_ring_speed``,
``outer_ring_speed`` (rad/s), ``radial_load`` (N), ``radial_load_angle``, ``misalignment``,
``misalignment_axis`` (rad) and ``misalignment_turns`` (bool), as the app's ``Facts``.
"""

from __future__ import annotations

import math

import numpy as np
import pyvista as pv

from .layout import RacewayLayout
from .meshes import ring_profile
from .raceway import INNER, OUTER

LABEL_FONT_PX = 14
ARROW_COLOURS = {"rotation": "#1f6f3f", "load": "#b01c1c", "tilt": "#6a3d9a"}
LEGEND = (  # (text, colour) of the marks the view draws; the ellipses' entry names their scale
    ("contact ellipses now", "#0096c7"),
    ("shoulder edges", "#1b1b1b"),
    ("groove bottom", "#2f5597"),
)
ELLIPSE_ENTRY = 0  # the legend's entry of the contact ellipses


def ellipse_legend_words(ellipse_scale: float) -> str:
    """The legend's entry of the contact ellipses drawn ``ellipse_scale`` times their size:
    'contact ellipses now ×5', or '... (to scale)' at 1."""
    if ellipse_scale == 1.0:
        return f"{LEGEND[ELLIPSE_ENTRY][0]} (to scale)"
    return f"{LEGEND[ELLIPSE_ENTRY][0]} ×{ellipse_scale:g}"


def ring_words(facts) -> tuple[str, str]:
    """Labels of the (inner, outer) raceway that say which ring turns and which is held: the
    inner ring is on the shaft, the outer in the housing; either is said 'fixed' when its speed
    is zero."""
    held = "fixed" if facts.inner_ring_speed == 0.0 else "turning"
    inner = f"inner raceway ({held}, shaft)"
    outer = (
        "outer raceway (fixed, housing)"
        if facts.outer_ring_speed == 0.0
        else "outer raceway (turning)"
    )
    return inner, outer


def misalignment_words(facts) -> str:
    """'tilt axis, fixed in space' / 'tilt axis, turning with the ring' ('' without a tilt)."""
    if facts.misalignment == 0.0:
        return ""
    where = "turning with the ring" if facts.misalignment_turns else "fixed in space"
    return f"tilt axis, {where}"


class TeachingOverlay:
    """Labels, arrows and legend in ``plotter``; ``actors``: all of them (the labels layer)."""

    def __init__(self, plotter: pv.Plotter, geometry, layout: RacewayLayout):
        self.plotter = plotter
        self.geometry = geometry
        self.layout = layout
        self._legend = None  # the legend's actor (its ellipses' entry names their scale)
        self.actors: list = []
        self._tilt_actor = None
        self.label_words: list[str] = []  # the labels' words, as drawn (after show)

    def show(self, facts, view_azimuth: float, visible: bool, ellipse_scale: float = 1.0) -> None:
        """Replace the overlay by that of the operating point ``facts``, facing ``view_azimuth``
        (rad), with the contact ellipses drawn ``ellipse_scale`` times their size; shown when
        ``visible``."""
        p, g = self.plotter, self.geometry
        for actor in self.actors:
            p.remove_actor(actor)
        self.actors.clear()
        self._tilt_actor = None
        self._legend = None
        grooves = self.layout.grooves
        D = g.ball_diameter
        face = max(float(np.max(ring_profile(grooves[INNER], D, np.nan)[0])), 0.95 * D)
        bore = 0.5 * g.pitch_diameter - 1.2 * D  # inside the inner ring's bore
        side = view_azimuth
        # raceway names: at the middle of each painted half, on the groove bottom
        inner_pt = grooves[INNER].point(side + 0.35, 0.0)
        shift = self.layout.outer_shift
        outer_pt = grooves[OUTER].point(side + math.pi - 0.35, 0.0) + [shift, 0, 0]
        inner_words, outer_words = ring_words(facts)
        labels = [(inner_words, inner_pt), (outer_words, outer_pt)]
        # shaft rotation: an arc round +x on the inner ring's face, arrow head in the turning sense
        sense = 1.0 if facts.inner_ring_speed >= 0 else -1.0
        if facts.inner_ring_speed != facts.outer_ring_speed:
            ang = side + sense * np.linspace(-0.9, 0.6, 40)
            arc = np.column_stack(
                [np.full(ang.size, face * 1.02), bore * np.cos(ang), bore * np.sin(ang)]
            )
            tip = arc[-1]
            heading = arc[-1] - arc[-3]
            self._add_mesh(
                pv.merge(
                    [
                        pv.Spline(arc, 60).tube(radius=0.06 * D),
                        pv.Cone(
                            center=tip + 0.25 * D * heading / np.linalg.norm(heading),
                            direction=heading,
                            height=0.5 * D,
                            radius=0.2 * D,
                        ),
                    ]
                ),
                ARROW_COLOURS["rotation"],
            )
            labels.append(("shaft turns", arc[0]))
        # radial load on the inner ring: from the centre towards the load azimuth
        if facts.radial_load != 0.0:
            a = facts.radial_load_angle
            direction = np.array([0.0, math.cos(a), math.sin(a)])
            start = np.array([face * 1.02, 0.0, 0.0])
            self._add_mesh(
                pv.Arrow(
                    start=start,
                    direction=direction,
                    scale=0.8 * bore,
                    tip_radius=0.12,
                    shaft_radius=0.04,
                ),
                ARROW_COLOURS["load"],
            )
            labels.append(
                (f"radial load {facts.radial_load:.0f} N", start + 0.6 * bore * direction)
            )
        # tilt axis through the centre, on the inner ring's face
        words = misalignment_words(facts)
        if words:
            a = facts.misalignment_axis
            direction = np.array([0.0, math.cos(a), math.sin(a)])
            centre = np.array([face * 1.04, 0.0, 0.0])
            line = pv.Line(centre - 0.9 * bore * direction, centre + 0.9 * bore * direction)
            actor = self._add_mesh(line.tube(radius=0.05 * D), ARROW_COLOURS["tilt"])
            if facts.misalignment_turns:
                self._tilt_actor = actor  # turns with the inner ring (move)
            labels.append((words, centre + 0.9 * bore * direction))
        self.label_words = [text for text, _ in labels]
        points = np.array([pt for _, pt in labels], float)
        self._label_points = pv.PolyData(points)
        self._label_base = points.copy()
        self._label_tilt = len(labels) - 1 if self._tilt_actor is not None else None
        self.actors.append(
            p.add_point_labels(
                self._label_points,
                [text for text, _ in labels],
                font_size=LABEL_FONT_PX,
                point_size=1,
                shape_opacity=0.7,
                always_visible=True,
                show_points=False,
                name="labels",
            )
        )
        entries = [[text, colour] for text, colour in LEGEND]
        entries[ELLIPSE_ENTRY][0] = ellipse_legend_words(ellipse_scale)
        legend = p.add_legend(
            entries,
            bcolor="white",
            border=False,
            size=(0.3, 0.1),  # legible in a laptop's view (about 500 px wide)
            loc="lower left",
            face="rectangle",
        )
        self.actors.append(legend)
        self._legend = legend
        for actor in self.actors:
            actor.visibility = visible

    def set_ellipse_scale(self, ellipse_scale: float) -> None:
        """Name the contact ellipses' drawing scale in the legend (:func:`ellipse_legend_words`)."""
        if self._legend is not None:
            self._legend.SetEntryString(ELLIPSE_ENTRY, ellipse_legend_words(ellipse_scale))

    def legend_words(self) -> list[str]:
        """The legend's entries as drawn (empty before :meth:`show`)."""
        if self._legend is None:
            return []
        return [self._legend.GetEntryString(i) for i in range(self._legend.GetNumberOfEntries())]

    def _add_mesh(self, mesh, colour: str):
        actor = self.plotter.add_mesh(mesh, color=colour, lighting=True, reset_camera=False)
        self.actors.append(actor)
        return actor

    def move(self, inner_matrix: np.ndarray) -> None:
        """Turn a tilt axis that turns with the inner ring (``inner_matrix``: its 4x4 matrix)."""
        if self._tilt_actor is None:
            return
        self._tilt_actor.user_matrix = inner_matrix
        i = self._label_tilt
        pts = self._label_base.copy()
        pts[i] = pts[i] @ inner_matrix[:3, :3].T
        self._label_points.points = pts
