"""The 3-D bearing scene (pyvista): rings, balls, cage, painted contact tracks, ellipses, traces.

No trame here: :class:`BearingScene` draws into any ``pyvista.Plotter`` and is driven frame by frame
from a :class:`viz.frames.FrameSource`. Everything is built once; a frame only moves actors (4x4
user matrices) and rewrites the points of the ellipse and trace meshes. The scene composes parts
with one job each: the painted raceways (:mod:`viz.painted`), the rings, balls and cage
(:mod:`viz.bodies`), the marks on the raceways (:mod:`viz.marks`), the close-up of one ball
(:mod:`viz.closeup`), the teaching overlay (:mod:`viz.overlay`) and the camera presets
(:mod:`viz.camera`), placed by one :class:`viz.layout.RacewayLayout`.

Frames: the scene is in the inertial frame of case-format.md (x = bearing axis), lengths in m.
Marks on a raceway (painted tracks, ellipses, traces, shoulder edges and groove bottom) are built
in that ring's own frame and share the ring's transform, so inner-raceway marks turn with the inner
ring. The painted tracks (:mod:`viz.tracks`) colour the groove where the contact ellipses ran, by
dwell or by peak pressure. Across-groove positions of marks can be exaggerated about the run's mean
contact angle (``exaggeration``), clipped at the shoulders so that marks never leave the groove;
the contact ellipses of the frame on show are to scale unless ``ellipse_scale`` enlarges them
(the legend names the scale); the painted tracks are their footprints at true size, so that a
line stays a line and a band a band at any ellipse scale.

Both raceways are in view at once: by default the outer ring is drawn apart from the inner one
along the bearing axis (``explode``, in ball diameters, away from the camera side) and opened as a
shell facing the camera (``outer_cutaway``): its raceway is seen from inside, past the inner ring.
"""

from __future__ import annotations

import pyvista as pv

from .bodies import BearingBodies
from .camera import CAMERA_PRESETS, SceneCamera, outline_points
from .closeup import CloseUp
from .frames import FrameSource, rot_x
from .layers import LAYERS
from .layout import RacewayLayout
from .marks import RacewayMarks
from .meshes import placement
from .options import SceneOptions
from .overlay import TeachingOverlay
from .painted import PaintedRaceways
from .raceway import INNER, OUTER

# Three lights that follow the camera, (position in camera coordinates: x right, y up, z towards
# the viewer; intensity): from the eye, a key light from the upper left and a fill light from the
# lower right, which lights the outer raceway seen from inside. Software rendering pays for every
# light at every pixel: three cost about 10 ms a frame less than pyvista's five-light kit at
# 820 x 670, with much the same shading.
LIGHTS = (((0.0, 0.0, 1.0), 0.5), ((-0.5, 1.0, 0.8), 0.5), ((0.5, -1.0, 0.5), 0.4))
# the camera preset that shows the inner raceway past where the balls and the cage stand: they are
# not drawn while it is on (whatever the layer switches say)
INNER_TRACK_CLEAR = "inner track"


class BearingScene:
    """Builds the bearing into ``plotter`` and moves it to a frame of a :class:`FrameSource`.

    ``actors`` holds the actors of each layer of :data:`viz.layers.LAYERS`."""

    def __init__(
        self,
        plotter: pv.Plotter,
        geometry,
        options: SceneOptions | None = None,
        dark_balls: bool = False,
    ):
        self.plotter = plotter
        self.geometry = geometry
        self.options = options or SceneOptions()
        self.source: FrameSource | None = None
        self.frame_index = 0
        self._track_clear = False  # balls and cage hidden: the "inner track" preset
        g, p = geometry, plotter
        p.set_background("white")
        p.remove_all_lights()
        for position, intensity in LIGHTS:
            p.add_light(pv.Light(position=position, light_type="camera light", intensity=intensity))
        # The see-through balls and cage are blended in drawing order: order-independent
        # translucency looks the same here (a few hundred pixels differ) and costs about 8 ms a
        # frame in software.
        p.renderer.SetUseOIT(False)
        self.layout = RacewayLayout(geometry, self.options)
        # The painted tracks lie just above the groove: drawn first, they hide the groove under them
        # before it is shaded (the depth test drops those pixels), which saves a shading pass there.
        self.tracks = PaintedRaceways(p, self.layout)
        self.bodies = BearingBodies(
            p, g, self.layout, self.options.translucent_balls, dark_balls=dark_balls
        )
        self.marks = RacewayMarks(p, g.ball_count, self.layout)
        self.overlay = TeachingOverlay(p, g, self.layout)
        self.actors: dict[str, list] = {
            "tracks": self.tracks.actors,
            **self.bodies.actors,
            **self.marks.actors,
            "labels": self.overlay.actors,
        }
        for name in LAYERS:
            for actor in self.actors[name]:
                actor.visibility = self.options.visible(name)
        self.closeup = CloseUp(p, g.ball_diameter, self.layout)
        self.tracks.label_colour_bar(self.options.track_quantity)
        self.camera = SceneCamera(
            p,
            self.layout,
            outline_points(
                *self.layout.profiles,
                cutaway=self.options.outer_cutaway,
                ball_top=0.5 * (g.pitch_diameter + g.ball_diameter),
                outer_shift=self.layout.outer_shift,
            ),
        )
        self.set_camera("isometric")

    @property
    def grids(self):
        """(inner, outer) :class:`viz.tracks.TrackGrid` of the painted tracks."""
        return self.layout.grids

    @property
    def track_range(self):
        """(lo, hi) of the painted tracks' colour bar, in its units."""
        return self.tracks.track_range

    # ---- data -----------------------------------------------------------------------------------
    def show_source(self, source: FrameSource, frame_index: int = 0) -> None:
        """Use ``source`` for the following frames (sets the colour range and reference angles)."""
        if source.ball_count != self.geometry.ball_count:
            raise ValueError(
                f"the result has {source.ball_count} balls, the scene {self.geometry.ball_count}"
            )
        self.source = source
        self.layout.reference = [source.reference_contact_angle(r) for r in (INNER, OUTER)]
        self._use_source()
        self.set_frame(frame_index)

    def _use_source(self) -> None:
        # footprints at their true size: the ellipse scale enlarges the marks of the frame only
        self.tracks.use_source(self.source, self.options.exaggeration, ellipse_scale=1.0)

    def set_frame(self, frame_index: int) -> None:
        """Move everything to frame ``frame_index`` of the current source (no render)."""
        if self.source is None:
            return
        f = self.source.frame(frame_index)
        self.frame_index = f.index
        rings = [
            placement(rot_x(f.ring_angle[INNER])),
            placement(rot_x(f.ring_angle[OUTER]), (self.layout.outer_shift, 0.0, 0.0)),
        ]
        self.bodies.move(f, rings)
        for race in (INNER, OUTER):
            self.marks.update_ellipses(race, f, self.options.ellipse_scale)
            self.marks.update_traces(race, self.source, f.index + 1, self.options)
        self.marks.move(rings)
        self.tracks.move(rings)
        self.overlay.move(rings[INNER])
        on = self.closeup.on
        self.closeup.show(on)
        ball = int(min(max(self.options.closeup_ball, 0), self.geometry.ball_count - 1))
        self.bodies.show_alone(ball if on else None, self.options, self._track_clear)
        if on:
            self.closeup.update(f, ball, rings, self.source, self.options.ellipse_scale)
            self.camera.follow_ball(f, ball, self.geometry.ball_diameter)
        whole = self.options.track_whole_run
        self.tracks.paint(
            self.source.n_frames if whole else f.index + 1, self.options.track_quantity
        )

    # ---- teaching overlay -----------------------------------------------------------------------
    def show_facts(self, facts) -> None:
        """Labels and arrows for the operating point ``facts`` (see :mod:`viz.overlay`): names of
        the raceways, the shaft's rotation, the radial load direction and the tilt axis ("fixed in
        space" or "turning with the ring"), which ring is fixed, and a legend of the marks (naming
        the contact ellipses' drawing scale)."""
        self.overlay.show(
            facts,
            self.options.view_azimuth,
            self.options.visible("labels"),
            self.options.ellipse_scale,
        )

    # ---- options --------------------------------------------------------------------------------
    def set_layer(self, name: str, visible: bool) -> None:
        """Show or hide one of :data:`LAYERS`."""
        if name not in LAYERS:
            raise ValueError(f"unknown layer {name!r}; layers are {', '.join(LAYERS)}")
        self.options.layers[name] = bool(visible)
        for actor in self.actors[name]:
            actor.visibility = bool(visible)
        if name == "traces" and visible and self.source is not None:
            for race in (INNER, OUTER):
                self.marks.update_traces(race, self.source, self.frame_index + 1, self.options)

    def set_exaggeration(self, factor: float) -> None:
        """Across-groove exaggeration factor (>= 1) for tracks, traces and ellipse centres."""
        self._set_drawing_factor("exaggeration", factor)

    def set_ellipse_scale(self, factor: float) -> None:
        """Drawn size of the contact ellipses of the frame on show / true size (at least 1; the
        painted tracks stay at true size), named in the legend."""
        self.options.ellipse_scale = max(1.0, float(factor))
        self.overlay.set_ellipse_scale(self.options.ellipse_scale)
        self.set_frame(self.frame_index)

    def _set_drawing_factor(self, option: str, factor: float) -> None:
        """Set the drawing option ``option`` to ``factor`` (at least 1), redraw from the source if
        it changed, and show the current frame again."""
        factor = max(1.0, float(factor))
        if factor != getattr(self.options, option):
            setattr(self.options, option, factor)
            self._use_source()
        self.set_frame(self.frame_index)

    def set_track_options(self, quantity: str | None = None, whole_run: bool | None = None):
        """Colour the painted tracks by ``quantity`` (:data:`viz.tracks.QUANTITIES`) and paint
        the whole run (``whole_run``) or the frames up to the current one."""
        if quantity is not None:
            self.tracks.label_colour_bar(quantity)
            self.options.track_quantity = quantity
        if whole_run is not None:
            self.options.track_whole_run = bool(whole_run)
        self.set_frame(self.frame_index)

    def set_trace_ball(self, ball: int | None) -> None:
        """Draw the traces of one ball (index) or of all balls (None)."""
        self.options.trace_ball = ball
        self.set_frame(self.frame_index)

    def set_closeup_ball(self, ball: int) -> None:
        """The ball the close-up follows (index)."""
        self.options.closeup_ball = int(ball)
        self.set_frame(self.frame_index)

    def set_camera(self, preset: str) -> None:
        """Camera preset: ``isometric``, ``axial``, ``radial``, ``inner track``, ``outer track``,
        ``close-up``.

        Always re-applies the preset (also when it is the one already on show) and frames what it
        shows with a margin of :data:`viz.camera.FRAME_MARGIN` at the render window's aspect,
        leaving the strip of the colour bar on the right free. ``isometric`` looks at the load side
        (:attr:`SceneOptions.view_azimuth`, where the outer ring is opened) from the +x side,
        where the inner-raceway contacts face, :data:`viz.camera.ISOMETRIC_TILT_DEG` off the axis:
        the inner raceway in front, the outer raceway behind it from inside; ``axial`` looks along
        +x; ``radial`` looks into the opened side, the bearing axis across the view. ``inner
        track`` frames the inner raceway's load-side half, without the balls and the cage that
        would hide it, and ``outer track`` the outer ring's far half with its raceway in the
        middle, both :data:`viz.camera.TRACK_VIEW_TILT_DEG` off the axis. ``close-up`` follows
        ball :attr:`SceneOptions.closeup_ball` alone with its contacts (:mod:`viz.closeup`).
        """
        if preset not in CAMERA_PRESETS:
            raise ValueError(
                f"unknown camera preset {preset!r}; use one of {', '.join(CAMERA_PRESETS)}"
            )
        self.closeup.on = preset == "close-up"
        self._track_clear = preset == INNER_TRACK_CLEAR
        self.camera.reset_view_angle()
        if self.closeup.on:
            self.camera.mark_framed()
            if self.source is not None:
                self.set_frame(self.frame_index)
            return
        self.closeup.show(False)
        # the close-up showed one ball alone; the inner track is seen without balls and cage
        self.bodies.show_alone(None, self.options, self._track_clear)
        self.camera.frame_preset(preset, self.options.view_azimuth)

    def framed_for_window(self) -> bool:
        """Whether the last camera preset was framed for the render window's current size."""
        return self.camera.framed_for_window()

    def trace_point_count(self, race: int) -> int:
        """Number of points in the drawn trace of ``race`` (0 when none is drawn)."""
        return self.marks.trace_point_count(race)


__all__ = ["BearingScene", "SceneOptions", "LIGHTS", "CAMERA_PRESETS"]
