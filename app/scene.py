"""The 3-D bearing scene (pyvista): rings, balls, cage, painted contact tracks, ellipses, traces.

No trame here: :class:`BearingScene` draws into any ``pyvista.Plotter`` and is driven frame by frame
from a :class:`app.frames.FrameSource`. Everything is built once; a frame only moves actors (4x4
user matrices) and rewrites the points of the ellipse and trace meshes.

Frames: the scene is in the inertial frame of case-format.md (x = bearing axis), lengths in m.
Marks on a raceway (painted tracks, ellipses, traces, shoulder edges and groove bottom) are built
in that ring's own frame and share the ring's transform, so inner-raceway marks turn with the inner
ring. The painted tracks (:mod:`app.tracks`) colour the groove where the contact ellipses ran, by
dwell or by peak pressure. Across-groove positions of marks can be exaggerated about the run's mean
contact angle (``exaggeration``), clipped at the shoulders so that marks never leave the groove;
ellipse sizes are to scale unless ``ellipse_scale`` enlarges them.

Both raceways are in view at once: by default the outer ring is drawn apart from the inner one
along the bearing axis (``explode``, in ball diameters, away from the camera side) and opened as a
shell facing the camera (``outer_cutaway``): its raceway is seen from inside, past the inner ring.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pyvista as pv

from .frames import FrameSource, rot_x
from .layers import LAYERS
from .palette import ball_colours
from .raceway import (
    INNER,
    OUTER,
    Groove,
    ellipse_outline,
    exaggerate,
    groove_half_angle,
    grooves,
)
from .tracks import (
    QUANTITIES,
    QUANTITY_LABELS,
    QUANTITY_SCALE,
    TrackGrid,
    TrackPainter,
    groove_surface_arrays,
    track_colours,
)

LABEL_FONT_PX = 14
ARROW_COLOURS = {"rotation": "#1f6f3f", "load": "#b01c1c", "tilt": "#6a3d9a"}
LEGEND = (  # (text, colour) of the marks the view draws
    ("contact ellipses now", "#0096c7"),
    ("shoulder edges", "#1b1b1b"),
    ("groove bottom", "#2f5597"),
)

DEFAULT_HIDDEN = ("traces",)  # layers off unless asked for: the painted tracks show the paths
CAMERA_PRESETS = ("isometric", "axial", "radial", "inner track", "outer track", "close-up")
CLOSEUP_PATH_FRAMES = 120  # frames of recent path drawn in the close-up of one ball
CLOSEUP_DOME = 0.6  # height of the pressure half-ellipsoid at the peak pressure / semi-major axis
CLOSEUP_COLOURS = {"path": "#0b6e4f", "ball_path": "#d1495b"}
TRACK_CMAP = "YlOrRd"  # pale where a point was run over briefly, dark red where longest
EDGE_COLOURS = {"shoulder": "#1b1b1b", "bottom": "#2f5597"}
EDGE_WIDTH_PX = 2.0
ELLIPSE_POINTS = 24
MAX_TRACE_SAMPLES = 1500  # per ball and race; longer traces are decimated for drawing
_RING_COLOUR = "#b8bcc4"
# Points of the ring meshes around the inner ring and around the outer ring's half shell, and
# across the groove arc. The painted tracks' mesh uses the same ones, so that its facets lie just
# above the ring's; the tracks' detail is a texture.
RING_PHI_POINTS = (96, 72)
GROOVE_ARC_POINTS = 40
VIEW_ANGLE_DEG = 30.0  # vertical view angle of the camera presets (VTK's default)
ISOMETRIC_TILT_DEG = 75.0  # isometric view direction from the bearing axis
TRACK_VIEW_TILT_DEG = 62.0  # "inner track" / "outer track" views: direction from the axis
AXIAL_TILT_DEG = 25.0  # "axial" view direction from the bearing axis
FRAME_MARGIN = 0.06  # camera presets leave this fraction of each half-size free around the bearing
SCALAR_BAR_STRIP = 0.17  # fraction of the view width on the right kept for the colour bar
BALL_OPACITY = (0.15, 0.6)  # (plain, marked) octants of a translucent ball
CAGE_OPACITY = 0.45  # the cage hoops pass in front of the inner raceway: the track shows through
# Contact ellipses are filled to scale and outlined with a stroke of this width (pixels), so that
# one of 0.9 x 0.15 mm still shows when the whole bearing is in view (a stroke, not a size).
ELLIPSE_OUTLINE_PX = 2.0
TRACE_WIDTH_PX = 3.0
SCALAR_BAR = {  # vertical, in the strip right of the bearing (see SCALAR_BAR_STRIP)
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
_MARK_LIFT = 0.004  # fraction of the groove radius that marks are lifted off the raceway
ELLIPSE_COLOUR = "#0096c7"  # contact ellipses: one colour that stands out on the painted tracks
# Three lights that follow the camera, (position in camera coordinates: x right, y up, z towards
# the viewer; intensity): from the eye, a key light from the upper left and a fill light from the
# lower right, which lights the outer raceway seen from inside. Software rendering pays for every
# light at every pixel: three cost about 10 ms a frame less than pyvista's five-light kit at
# 820 x 670, with much the same shading.
LIGHTS = (((0.0, 0.0, 1.0), 0.5), ((-0.5, 1.0, 0.8), 0.5), ((0.5, -1.0, 0.5), 0.4))


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


def ring_profile(
    groove: Groove, ball_diameter: float, shoulder_radius: float, n_arc: int = GROOVE_ARC_POINTS
):
    """Closed (x, radius) outline of a ring cross-section, m.

    The groove arc runs between the two shoulders at groove latitude +-theta
    (:func:`groove_half_angle`).
    """
    D, r = ball_diameter, groove.r
    s = groove.sign  # +1 inner (material below the groove), -1 outer (material above)
    theta = groove_half_angle(groove, D, shoulder_radius)
    alpha = np.linspace(-theta, theta, n_arc)
    arc_x = groove.x_c - s * r * np.sin(alpha)
    arc_rho = groove.rho_c - s * r * np.cos(alpha)
    land = groove.rho_c - s * r * math.cos(theta)
    back = groove.rho_c - s * r - s * 0.45 * D  # bore (inner) or outside surface (outer)
    half_width = 0.5 * 1.9 * D
    x_lo, x_hi = min(arc_x.min(), -half_width), max(arc_x.max(), half_width)
    # the arc runs from x_hi side to x_lo side for the inner ring (s=+1) and the reverse for outer
    if arc_x[0] < arc_x[-1]:
        arc_x, arc_rho = arc_x[::-1], arc_rho[::-1]
    xs = np.concatenate([[x_lo, x_hi, x_hi], arc_x, [x_lo, x_lo]])
    rhos = np.concatenate([[back, back, land], arc_rho, [land, back]])
    return xs, rhos


def revolve(xs, rhos, n_phi: int = RING_PHI_POINTS[0], phi_range=(0.0, 2 * math.pi)):
    """Surface of revolution about +x of a closed (x, radius) outline."""
    phi = np.linspace(*phi_range, n_phi)
    X = np.repeat(np.asarray(xs)[:, None], n_phi, axis=1)
    R = np.asarray(rhos)[:, None]
    grid = pv.StructuredGrid(X, R * np.cos(phi)[None, :], R * np.sin(phi)[None, :])
    try:
        surf = grid.extract_surface(algorithm="dataset_surface")
    except TypeError:  # pyvista < 0.47 has no ``algorithm`` keyword
        surf = grid.extract_surface()
    surf = surf.triangulate().clean()
    if phi_range[1] - phi_range[0] < 2 * math.pi - 1e-9:  # a cut-away ring: close the cut faces
        caps = []
        for angle in phi_range:
            pts = np.column_stack(
                [xs, np.asarray(rhos) * math.cos(angle), np.asarray(rhos) * math.sin(angle)]
            )[:-1]  # drop closing point
            face = np.concatenate([[len(pts)], np.arange(len(pts))])
            caps.append(pv.PolyData(pts, faces=face).triangulate())
        surf = pv.merge([surf, *caps]).clean()
    return surf.compute_normals(auto_orient_normals=False, split_vertices=True)


def marked_sphere(radius: float) -> pv.PolyData:
    """Sphere with an octant checker pattern (cell data ``mark``), so its spin is visible."""
    sphere = pv.Sphere(radius=radius, theta_resolution=24, phi_resolution=16)
    c = sphere.cell_centers().points
    sphere.cell_data["mark"] = (np.sign(c[:, 0]) * np.sign(c[:, 1]) * np.sign(c[:, 2]) > 0).astype(
        float
    )
    return sphere


def cage_mesh(pitch_radius: float, ball_diameter: float, ball_count: int) -> pv.PolyData:
    """Two side hoops and one bar between each pair of pockets, at cage angle 0."""
    D = ball_diameter
    parts = []
    for x in (-0.62 * D, 0.62 * D):
        hoop = pv.ParametricTorus(
            ringradius=pitch_radius, crosssectionradius=0.07 * D, u_res=96, v_res=8
        )
        parts.append(hoop.rotate_y(90.0, inplace=False).translate((x, 0.0, 0.0), inplace=False))
    for j in range(ball_count):
        psi = 2 * math.pi * (j + 0.5) / ball_count
        centre = (0.0, pitch_radius * math.cos(psi), pitch_radius * math.sin(psi))
        parts.append(
            pv.Cylinder(
                center=centre, direction=(1, 0, 0), radius=0.07 * D, height=1.24 * D, resolution=8
            )
        )
    return pv.merge(parts)


def _fan_faces(count: int, n: int) -> np.ndarray:
    """Triangle-fan faces for ``count`` ellipses of ``n`` outline points plus a centre each."""
    faces = []
    for e in range(count):
        base = e * (n + 1)
        for k in range(n):
            faces.append((3, base, base + 1 + k, base + 1 + (k + 1) % n))
    return np.asarray(faces, dtype=np.int64).ravel()


def _outline_lines(count: int, n: int) -> np.ndarray:
    """Closed polylines along the ``n`` outline points of ``count`` fans (:func:`_fan_faces`)."""
    lines = []
    for e in range(count):
        base = e * (n + 1)
        lines.append([n + 1, *(base + 1 + np.arange(n)), base + 1])
    return np.asarray(lines, dtype=np.int64).ravel()


def _matrix(rotation: np.ndarray, translation=(0.0, 0.0, 0.0)) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3] = rotation
    m[:3, 3] = translation
    return m


def outline_points(
    inner_profile,
    outer_profile,
    cutaway=None,
    ball_top: float = 0.0,
    n_phi: int = 72,
    outer_shift: float = 0.0,
) -> np.ndarray:
    """Points (m, shape (n, 3)) that bound what is drawn, for framing the camera.

    Circles at the smallest and largest x of each ring's (x, radius) profile, at its largest
    radius; the outer ring's are moved by ``outer_shift`` (m) along x. Inside the outer ring's
    cut-away sector ``cutaway`` (rad, (start, end) ring azimuth) the outer ring is not drawn:
    there the balls' outermost points (radius ``ball_top``, m, beside the inner ring) bound it.
    """
    phi = np.linspace(0.0, 2 * math.pi, n_phi, endpoint=False)
    cut = np.zeros(n_phi, bool)
    if cutaway is not None:
        cut = np.mod(phi - cutaway[0], 2 * math.pi) < cutaway[1] - cutaway[0]
    circles = []

    def circle(x, radius, keep):
        pts = np.column_stack([np.full(n_phi, x), radius * np.cos(phi), radius * np.sin(phi)])
        circles.append(pts[keep])

    everywhere = np.ones(n_phi, bool)
    for x in (float(np.min(inner_profile[0])), float(np.max(inner_profile[0]))):
        circle(x, float(np.max(inner_profile[1])), everywhere)
        circle(x, ball_top, cut)
    for x in (float(np.min(outer_profile[0])), float(np.max(outer_profile[0]))):
        circle(x + outer_shift, float(np.max(outer_profile[1])), ~cut)
    return np.concatenate(circles)


def camera_directions(preset: str, view_azimuth: float) -> tuple[np.ndarray, np.ndarray]:
    """(unit vector from the bearing centre towards the camera, view-up vector) of a preset.

    ``view_azimuth`` (rad, from +y towards +z) is the side the isometric and radial views face
    (the load side). ``inner track`` looks down on the inner raceway there from the +x side,
    ``outer track`` up into the outer raceway on the opposite side (the far half of the opened
    outer ring).
    """
    radial = np.array([0.0, math.cos(view_azimuth), math.sin(view_azimuth)])
    across = np.array([0.0, -math.sin(view_azimuth), math.cos(view_azimuth)])
    axis = np.array([1.0, 0.0, 0.0])
    if preset == "axial":  # from the +x side, tilted towards the view side to see into the grooves
        tilt = math.radians(AXIAL_TILT_DEG)
        direction = math.cos(tilt) * axis + math.sin(tilt) * radial
        up = radial - direction * math.sin(tilt)
        return direction, up / np.linalg.norm(up)
    if preset == "radial":
        return radial, across
    tilt = math.radians(
        {"inner track": TRACK_VIEW_TILT_DEG, "outer track": TRACK_VIEW_TILT_DEG}.get(
            preset, ISOMETRIC_TILT_DEG
        )
    )
    direction = math.cos(tilt) * axis + math.sin(tilt) * radial
    up = axis - direction * math.cos(tilt)  # the bearing axis, made normal to the view direction
    return direction, up / np.linalg.norm(up)


def frame_points(
    points: np.ndarray,
    direction,
    up,
    view_angle_deg: float,
    aspect: float,
    margin: float | None = None,
    right_reserved: float = 0.0,
) -> tuple[np.ndarray, np.ndarray]:
    """Camera (position, focal point), m, of a perspective view that shows all ``points`` (m).

    The camera sits on the ``direction`` side of the focal point with ``up`` vertical and a
    vertical view angle ``view_angle_deg``; ``aspect`` is the viewport's width / height. The points
    fill the view up to ``1 - margin`` of each half-size (``margin`` defaults to
    :data:`FRAME_MARGIN`), away from a strip of ``right_reserved`` times the width on the right.
    """
    margin = FRAME_MARGIN if margin is None else margin
    direction = np.asarray(direction, float) / np.linalg.norm(direction)
    up = np.asarray(up, float) - np.dot(up, direction) * direction
    up /= np.linalg.norm(up)
    right = np.cross(up, direction)  # image right for a camera looking along -direction
    half_v = math.tan(math.radians(view_angle_deg) / 2)  # half-height of the view, tan units
    half_h = half_v * aspect
    free_lo, free_hi = -half_h, half_h * (1.0 - 2.0 * right_reserved)  # kept for the points
    centre_h = 0.5 * (free_lo + free_hi)
    fit_h = 0.5 * (free_hi - free_lo) * (1.0 - margin)
    fit_v = half_v * (1.0 - margin)
    pts = np.asarray(points, float)
    focal = pts.mean(axis=0)
    for _ in range(5):  # centre the points on the view axis, then fit the distance
        rel = pts - focal
        across, vertical, toward = rel @ right, rel @ up, rel @ direction
        distance = max(
            np.max(np.abs(across) / fit_h + toward), np.max(np.abs(vertical) / fit_v + toward)
        )
        depth = distance - toward
        mid_h = 0.5 * (np.max(across / depth) + np.min(across / depth))
        mid_v = 0.5 * (np.max(vertical / depth) + np.min(vertical / depth))
        focal = focal + distance * (mid_h * right + mid_v * up)
    focal = focal - distance * centre_h * right  # the points to the middle of the free part
    return focal + distance * direction, focal


class BearingScene:
    """Builds the bearing into ``plotter`` and moves it to a frame of a :class:`FrameSource`."""

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
        self.grooves = grooves(geometry)
        self.source: FrameSource | None = None
        self.frame_index = 0
        self._actors: dict[str, list] = {name: [] for name in LAYERS}
        self._reference = [geometry.free_contact_angle] * 2
        self.outer_shift = float(self.options.explode) * geometry.ball_diameter  # m along x
        self.painter: TrackPainter | None = None
        self._build(dark_balls)

    # ---- construction ---------------------------------------------------------------------------
    def _build(self, dark_balls: bool) -> None:
        g, p = self.geometry, self.plotter
        p.set_background("white")
        p.remove_all_lights()
        for position, intensity in LIGHTS:
            p.add_light(pv.Light(position=position, light_type="camera light", intensity=intensity))
        # The see-through balls and cage are blended in drawing order: order-independent
        # translucency looks the same here (a few hundred pixels differ) and costs about 8 ms a
        # frame in software.
        p.renderer.SetUseOIT(False)
        inner_profile = ring_profile(
            self.grooves[INNER], g.ball_diameter, g.inner_shoulder_diameter / 2
        )
        outer_profile = ring_profile(
            self.grooves[OUTER], g.ball_diameter, g.outer_shoulder_diameter / 2
        )
        self._outline_points = outline_points(
            inner_profile,
            outer_profile,
            cutaway=self.options.outer_cutaway,
            ball_top=0.5 * (g.pitch_diameter + g.ball_diameter),
            outer_shift=self.outer_shift,
        )
        self.grids = tuple(
            TrackGrid(-theta, theta)
            for theta in (
                groove_half_angle(
                    self.grooves[INNER], g.ball_diameter, g.inner_shoulder_diameter / 2
                ),
                groove_half_angle(
                    self.grooves[OUTER], g.ball_diameter, g.outer_shoulder_diameter / 2
                ),
            )
        )
        # The painted tracks lie just above the groove: drawn first, they hide the groove under them
        # before it is shaded (the depth test drops those pixels), which saves a shading pass there.
        self._build_tracks()
        inner = revolve(*inner_profile)
        # a dark sector on the inner ring makes its rotation visible
        phi = np.arctan2(inner.cell_centers().points[:, 2], inner.cell_centers().points[:, 1])
        inner.cell_data["mark"] = (np.abs(phi) < math.radians(8)).astype(float)
        self._actors["inner_ring"].append(
            p.add_mesh(
                inner,
                scalars="mark",
                cmap=[_RING_COLOUR, "#2f5597"],
                show_scalar_bar=False,
                smooth_shading=True,
                specular=0.4,
                name="inner_ring",
            )
        )
        self._actors["outer_ring"].append(
            p.add_mesh(
                revolve(
                    *outer_profile, n_phi=RING_PHI_POINTS[OUTER], phi_range=self._ring_span(OUTER)
                ),
                color=_RING_COLOUR,
                smooth_shading=True,
                specular=0.4,
                name="outer_ring",
            )
        )
        sphere = marked_sphere(0.5 * g.ball_diameter)
        colours = ["#202020", "#6a6a6a"] if dark_balls else ["#d9d9d9", "#7a7a7a"]
        if self.options.translucent_balls:
            # see-through balls: plain octants almost clear, marked octants dark enough to read
            colours = ["#9a9a9a", "#1a1a1a"] if dark_balls else ["#d0d0d0", "#4a5560"]
        # each ball's marked octants in its own colour (app.palette; the legend over the view)
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
            if self.options.translucent_balls:
                lut = actor.mapper.lookup_table
                rgba = np.array(lut.values)
                rgba[:, 3] = np.round(255 * np.asarray(BALL_OPACITY))
                lut.values = rgba
            self._actors["balls"].append(actor)
        self._actors["cage"].append(
            p.add_mesh(
                cage_mesh(0.5 * g.pitch_diameter, g.ball_diameter, g.ball_count),
                color="#c8842a",
                opacity=CAGE_OPACITY,
                smooth_shading=True,
                name="cage",
            )
        )
        self._build_edges()
        n_pts = g.ball_count * (ELLIPSE_POINTS + 1)
        self._ellipses, self._traces = [], []
        for race in (INNER, OUTER):
            mesh = pv.PolyData(
                np.zeros((n_pts, 3)),
                faces=_fan_faces(g.ball_count, ELLIPSE_POINTS),
                lines=_outline_lines(g.ball_count, ELLIPSE_POINTS),
            )
            mesh.point_data["max_pressure_GPa"] = np.zeros(n_pts)
            self._ellipses.append(mesh)
            self._actors["ellipses"].append(
                p.add_mesh(
                    mesh,
                    color=ELLIPSE_COLOUR,
                    line_width=ELLIPSE_OUTLINE_PX,
                    lighting=False,
                    name=f"ellipses_{race}",
                )
            )
            trace = pv.PolyData(np.zeros((2, 3)), lines=np.array([2, 0, 1]))
            trace.point_data["ball"] = np.zeros(2)
            self._traces.append(trace)
            self._actors["traces"].append(
                p.add_mesh(
                    trace,
                    scalars="ball",
                    cmap=ball_colours(g.ball_count),
                    n_colors=g.ball_count,
                    clim=(-0.5, g.ball_count - 0.5),
                    show_scalar_bar=False,
                    line_width=TRACE_WIDTH_PX,
                    name=f"traces_{race}",
                )
            )
        for name in LAYERS:
            for actor in self._actors[name]:
                actor.visibility = bool(self.options.layers.get(name, True))
        self._build_closeup()
        bar = p.scalar_bar
        bar.SetVerticalTitleSeparation(10)  # pixels between the title and the top label
        self._bar = bar  # the painted tracks' colour bar
        bar.SetTitle(QUANTITY_LABELS[self.options.track_quantity])
        self.set_camera("isometric")

    def _kept_phi_cells(self, race: int) -> np.ndarray:
        """Phi cells of ``race`` that are drawn: all but the outer ring's cut-away sector."""
        grid = self.grids[race]
        centres = (np.arange(grid.n_phi) + 0.5) * grid.d_phi
        return np.flatnonzero(~self._in_cutaway(race, centres))

    def _ring_span(self, race: int) -> tuple[float, float]:
        """(first, last) azimuth (rad) of the ring mesh of ``race``: the whole turn for the inner
        ring, the half shell left by the cut-away for the outer one."""
        if race == INNER:
            return 0.0, 2 * math.pi
        lo, hi = self.options.outer_cutaway
        return hi, lo + 2 * math.pi

    def _build_tracks(self) -> None:
        """One mesh per groove, on the ring's own facets, coloured by a texture of the painted
        track (one texel per cell of the fields; ring colour where no ellipse has run). A mesh of
        a quad per cell would look the same and render about 7 ms a frame slower in software."""
        self._tracks, self._track_texels = [], []
        for race in (INNER, OUTER):
            groove, grid = self.grooves[race], self.grids[race]
            pts, faces, tcoords = groove_surface_arrays(
                groove,
                grid,
                np.linspace(*self._ring_span(race), RING_PHI_POINTS[race]),
                GROOVE_ARC_POINTS,
                lift=0.5 * _MARK_LIFT * groove.r,
            )
            mesh = pv.PolyData(pts, faces=faces)
            mesh.active_texture_coordinates = tcoords
            mesh.cell_data["track"] = np.full(mesh.n_cells, np.nan)  # gives the colour bar
            self._tracks.append(mesh)
            actor = self.plotter.add_mesh(
                mesh,
                scalars="track",
                cmap=TRACK_CMAP,
                clim=(0.0, 1.0),
                nan_color=_RING_COLOUR,
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
            self._track_texels.append(pv.wrap(texture.GetInput()))
            self._actors["tracks"].append(actor)

    def _build_edges(self) -> None:
        """Both shoulder edges and the groove bottom of each ring, as lines on the groove."""
        for race in (INNER, OUTER):
            groove, grid = self.grooves[race], self.grids[race]
            kept = self._kept_phi_cells(race)
            runs = np.split(kept, np.flatnonzero(np.diff(kept) != 1) + 1)
            for kind, alpha in (
                ("shoulder", grid.alpha_lo),
                ("shoulder", grid.alpha_hi),
                ("bottom", 0.0),
            ):
                parts = []
                for run in runs:
                    if run.size == 0:
                        continue
                    phi = grid.phi_edges()[run[0] : run[-1] + 2]
                    pts = groove.point(phi, alpha, lift=_MARK_LIFT * groove.r)
                    parts.append(pv.lines_from_points(pts))
                self._actors["edges"].append(
                    self.plotter.add_mesh(
                        pv.merge(parts),
                        color=EDGE_COLOURS[kind],
                        line_width=EDGE_WIDTH_PX,
                        lighting=False,
                        name=f"edge_{race}_{kind}_{alpha:.3f}",
                    )
                )
        self._edge_race = [INNER] * 3 + [OUTER] * 3

    def _build_painter(self) -> None:
        if self.source is None:
            self.painter = None
            return
        self.painter = TrackPainter(
            self.source,
            self.grooves,
            self.grids,
            self._reference,
            exaggeration=self.options.exaggeration,
            ellipse_scale=self.options.ellipse_scale,
        )

    def _update_tracks(self, stop: int) -> None:
        if self.painter is None:
            return
        self.painter.accumulate(self.source.n_frames if self.options.track_whole_run else stop)
        q = self.options.track_quantity
        scale = QUANTITY_SCALE[q]
        lo, hi = self.painter.value_range(q)
        lo, hi = lo * scale, hi * scale
        if not hi > lo:
            hi = lo + max(abs(lo), 1.0) * 1e-3
        lut = self._actors["tracks"][INNER].mapper.lookup_table
        for race in (INNER, OUTER):
            texels = self._track_texels[race]
            texels.point_data["rgba"][:] = track_colours(
                self.painter.field(race, q) * scale,
                self.painter.painted(race),
                lo,
                hi,
                lut.values,
                lut.nan_color.int_rgba,
            )
            texels.Modified()
            self._actors["tracks"][race].mapper.scalar_range = (lo, hi)
        self.track_range = (lo, hi)

    # ---- close-up of one ball -------------------------------------------------------------------
    def _build_closeup(self) -> None:
        """Pressure half-ellipsoids, recent ellipse-centre paths (one per race) and the ball's own
        contact paths, shown with the "close-up" camera only."""
        p = self.plotter
        self._closeup = {"domes": [], "paths": [], "ball_paths": []}
        self._closeup_actors = []
        n_r, n_t = 8, ELLIPSE_POINTS
        for race in (INNER, OUTER):
            faces = []  # quads between neighbouring rings of the (rho, tau) grid
            for i in range(n_r - 1):
                for k in range(n_t):
                    a0 = i * n_t + k
                    a1 = i * n_t + (k + 1) % n_t
                    faces.append((4, a0, a1, a1 + n_t, a0 + n_t))
            mesh = pv.PolyData(np.zeros((n_r * n_t, 3)), faces=np.asarray(faces).ravel())
            mesh.point_data["pressure_GPa"] = np.zeros(n_r * n_t)
            self._closeup["domes"].append(mesh)
            self._closeup_actors.append(
                p.add_mesh(
                    mesh,
                    scalars="pressure_GPa",
                    cmap="plasma",
                    clim=(0.0, 1.0),
                    show_scalar_bar=False,
                    smooth_shading=True,
                    name=f"closeup_dome_{race}",
                )
            )
            for kind, store in (("path", "paths"), ("ball_path", "ball_paths")):
                line = pv.PolyData(np.zeros((2, 3)), lines=np.array([2, 0, 1]))
                self._closeup[store].append(line)
                self._closeup_actors.append(
                    p.add_mesh(
                        line,
                        color=CLOSEUP_COLOURS[kind],
                        line_width=3.0,
                        lighting=False,
                        name=f"closeup_{kind}_{race}",
                    )
                )
        self._closeup_n = (n_r, n_t)
        self._closeup_on = False
        for actor in self._closeup_actors:
            actor.visibility = False

    def _update_closeup(self, f, rings) -> None:
        on = self._closeup_on and self.source is not None
        for actor in self._closeup_actors:
            actor.visibility = on
        j = int(min(max(self.options.closeup_ball, 0), self.geometry.ball_count - 1))
        # the close-up shows one ball alone, its outer contact where it is (not drawn apart)
        for k, actor in enumerate(self._actors["balls"]):
            actor.visibility = self.options.layers.get("balls", True) and (not on or k == j)
        for name in ("cage", "outer_ring"):  # the outer ring is drawn apart: out of the way
            for actor in self._actors[name]:
                actor.visibility = self.options.layers.get(name, True) and not on
        if not on:
            return
        rings = [rings[INNER], _matrix(rot_x(f.ring_angle[OUTER]))]
        n_r, n_t = self._closeup_n
        rho = np.linspace(0.0, 1.0, n_r)[:, None]
        tau = np.linspace(0.0, 2 * math.pi, n_t, endpoint=False)[None, :]
        pmax = np.nan_to_num(self.source.contact["max_pressure"])
        top = max(float(pmax.max()) * 1e-9, 1e-3)
        start = max(0, f.index + 1 - CLOSEUP_PATH_FRAMES)
        for race in (INNER, OUTER):
            groove = self.grooves[race]
            loaded = bool(f.loaded[j, race])
            scale = self.options.ellipse_scale
            a = float(np.nan_to_num(f.semi_major[j, race])) * scale if loaded else 0.0
            b = float(np.nan_to_num(f.semi_minor[j, race])) * scale if loaded else 0.0
            p0 = float(np.nan_to_num(f.max_pressure[j, race])) * 1e-9 if loaded else 0.0
            alpha = float(self._display_alpha(race, f.contact_angle[j, race] if loaded else 0.0))
            phi = float(f.raceway_azimuth[j, race])
            shape = np.sqrt(np.clip(1.0 - rho**2, 0.0, 1.0))
            lift = 2 * _MARK_LIFT * groove.r + CLOSEUP_DOME * a * shape
            phis = phi + b / groove.contact_radius(alpha) * rho * np.sin(tau)
            alphas = alpha + a / groove.r * rho * np.cos(tau)
            surface = groove.point(phis, alphas)
            # towards the groove's curvature centre: out of the raceway, into the ball's space
            toward = groove.point(phis, alphas, lift=groove.r) - surface
            toward /= np.linalg.norm(toward, axis=-1, keepdims=True)
            pts = surface + lift[..., None] * toward
            dome = self._closeup["domes"][race]
            dome.points = pts.reshape(-1, 3)
            dome.point_data["pressure_GPa"] = np.broadcast_to(p0 * shape, (n_r, n_t)).ravel()
            self._closeup_actors[3 * race].mapper.scalar_range = (0.0, top)
            self._closeup_actors[3 * race].user_matrix = rings[race]
            # recent path of the ellipse centre on the raceway (ring frame)
            c = self.source.contact
            al = c["contact_angle"][start : f.index + 1, j, race]
            ok = np.isfinite(al) & (
                np.nan_to_num(c["contact_load"][start : f.index + 1, j, race]) > 0
            )
            ph = self.source.raceway_azimuth[start : f.index + 1, j, race]
            self._set_line(
                self._closeup["paths"][race],
                groove.point(
                    ph[ok], self._display_alpha(race, al[ok]), lift=3 * _MARK_LIFT * groove.r
                ),
            )
            self._closeup_actors[3 * race + 1].user_matrix = rings[race]
            # the ball's own contact path on its surface (ball-fixed frame, dynamic results)
            lat = c.get("ball_latitude")
            if lat is not None and self.source.model == "dynamic":
                la = lat[start : f.index + 1, j, race][ok]
                lo = c["ball_longitude"][start : f.index + 1, j, race][ok]
                radius = 0.5 * self.geometry.ball_diameter * 1.01
                pts = radius * np.column_stack(
                    [np.cos(la) * np.cos(lo), np.cos(la) * np.sin(lo), np.sin(la)]
                )
                self._set_line(self._closeup["ball_paths"][race], pts)
                self._closeup_actors[3 * race + 2].user_matrix = _matrix(
                    f.ball_rotation[j], f.ball_center[j]
                )
            else:
                self._closeup_actors[3 * race + 2].visibility = False

    @staticmethod
    def _set_line(mesh, pts) -> None:
        pts = np.asarray(pts, float).reshape(-1, 3)
        if len(pts) < 2:
            pts = np.zeros((2, 3))
        mesh.copy_from(pv.lines_from_points(pts))

    def has_ball_paths(self) -> bool:
        """Whether the result on show gives the contact path on the ball's surface."""
        return (
            self.source is not None
            and self.source.model == "dynamic"
            and "ball_latitude" in self.source.contact
        )

    def set_closeup_ball(self, ball: int) -> None:
        """The ball the close-up follows (index)."""
        self.options.closeup_ball = int(ball)
        self.set_frame(self.frame_index)

    def _closeup_camera(self, f) -> None:
        """Look at ball ``closeup_ball`` along its rolling direction, the bearing axis across."""
        j = int(min(max(self.options.closeup_ball, 0), self.geometry.ball_count - 1))
        psi = float(f.ball_azimuth[j])
        e_r = np.array([0.0, math.cos(psi), math.sin(psi)])
        e_t = np.array([0.0, -math.sin(psi), math.cos(psi)])
        direction = e_t + 0.35 * np.array([1.0, 0.0, 0.0])
        centre = np.asarray(f.ball_center[j], float)
        D = self.geometry.ball_diameter
        pts = np.array(
            [centre + sx * 0.95 * D * np.array([1.0, 0, 0]) + sr * 0.95 * D * e_r
             for sx in (-1, 1) for sr in (-1, 1)]
        )  # fmt: skip
        width, height = self.plotter.window_size
        position, focal = frame_points(
            pts, direction, e_r, self.plotter.camera.view_angle, width / height,
            right_reserved=SCALAR_BAR_STRIP,
        )  # fmt: skip
        self.plotter.camera_position = [tuple(position), tuple(focal), tuple(e_r)]
        self.plotter.renderer.ResetCameraClippingRange()

    # ---- teaching overlay -----------------------------------------------------------------------
    def show_facts(self, facts) -> None:
        """Labels and arrows for the operating point ``facts`` (:class:`app.teaching.Facts`):
        names of the raceways, the shaft's rotation, the radial load direction and the tilt axis
        ("fixed in space" or "turning with the ring"), and a legend of the marks."""
        from .teaching import misalignment_words

        p, g = self.plotter, self.geometry
        for actor in self._actors["labels"]:
            p.remove_actor(actor)
        self._actors["labels"] = []
        self._tilt_actor = None
        D = g.ball_diameter
        face = max(float(np.max(ring_profile(self.grooves[INNER], D, np.nan)[0])), 0.95 * D)
        bore = 0.5 * g.pitch_diameter - 1.2 * D  # inside the inner ring's bore
        side = self.options.view_azimuth
        radial = np.array([0.0, math.cos(side), math.sin(side)])
        across = np.array([0.0, -math.sin(side), math.cos(side)])
        # raceway names: at the middle of each painted half, on the groove bottom
        inner_pt = self.grooves[INNER].point(side + 0.35, 0.0)
        outer_pt = self.grooves[OUTER].point(side + math.pi - 0.35, 0.0) + [self.outer_shift, 0, 0]
        labels = [("inner raceway", inner_pt), ("outer raceway", outer_pt)]
        # shaft rotation: an arc round +x on the inner ring's face, arrow head in the turning sense
        sense = 1.0 if facts.inner_ring_speed >= 0 else -1.0
        if facts.inner_ring_speed != facts.outer_ring_speed:
            ang = side + sense * np.linspace(-0.9, 0.6, 40)
            arc = np.column_stack(
                [np.full(ang.size, face * 1.02), bore * np.cos(ang), bore * np.sin(ang)]
            )
            tip = arc[-1]
            heading = arc[-1] - arc[-3]
            self._add_overlay(
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
            self._add_overlay(
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
            actor = self._add_overlay(line.tube(radius=0.05 * D), ARROW_COLOURS["tilt"])
            if facts.misalignment_turns:
                self._tilt_actor = actor  # turns with the inner ring (set_frame)
            labels.append((words, centre + 0.9 * bore * direction))
        del across, radial
        points = np.array([pt for _, pt in labels], float)
        self._label_points = pv.PolyData(points)
        self._label_base = points.copy()
        self._label_tilt = len(labels) - 1 if self._tilt_actor is not None else None
        self._actors["labels"].append(
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
        legend = p.add_legend(
            [[text, colour] for text, colour in LEGEND],
            bcolor="white",
            border=False,
            size=(0.24, 0.08),
            loc="lower left",
            face="rectangle",
        )
        self._actors["labels"].append(legend)
        for actor in self._actors["labels"]:
            actor.visibility = bool(self.options.layers.get("labels", True))

    def _add_overlay(self, mesh, colour: str):
        actor = self.plotter.add_mesh(mesh, color=colour, lighting=True, reset_camera=False)
        self._actors["labels"].append(actor)
        return actor

    def _move_overlay(self, inner_matrix: np.ndarray) -> None:
        tilt = getattr(self, "_tilt_actor", None)
        if tilt is None:
            return
        tilt.user_matrix = inner_matrix
        i = self._label_tilt
        pts = self._label_base.copy()
        pts[i] = pts[i] @ inner_matrix[:3, :3].T
        self._label_points.points = pts

    # ---- data -----------------------------------------------------------------------------------
    def show_source(self, source: FrameSource, frame_index: int = 0) -> None:
        """Use ``source`` for the following frames (sets the colour range and reference angles)."""
        if source.ball_count != self.geometry.ball_count:
            raise ValueError(
                f"the result has {source.ball_count} balls, the scene {self.geometry.ball_count}"
            )
        self.source = source
        self._reference = [source.reference_contact_angle(r) for r in (INNER, OUTER)]
        self._build_painter()
        self.set_frame(frame_index)

    def set_frame(self, frame_index: int) -> None:
        """Move everything to frame ``frame_index`` of the current source (no render)."""
        if self.source is None:
            return
        f = self.source.frame(frame_index)
        self.frame_index = f.index
        rings = [
            _matrix(rot_x(f.ring_angle[INNER])),
            _matrix(rot_x(f.ring_angle[OUTER]), (self.outer_shift, 0.0, 0.0)),
        ]
        self._actors["inner_ring"][0].user_matrix = rings[INNER]
        self._actors["outer_ring"][0].user_matrix = rings[OUTER]
        for j, actor in enumerate(self._actors["balls"]):
            actor.user_matrix = _matrix(f.ball_rotation[j], f.ball_center[j])
        self._actors["cage"][0].user_matrix = _matrix(rot_x(f.cage_angle))
        for race in (INNER, OUTER):
            self._update_ellipses(race, f)
            self._update_traces(race, f.index + 1)
            self._actors["ellipses"][race].user_matrix = rings[race]
            self._actors["traces"][race].user_matrix = rings[race]
            self._actors["tracks"][race].user_matrix = rings[race]
        for race, actor in zip(self._edge_race, self._actors["edges"], strict=True):
            actor.user_matrix = rings[race]
        self._move_overlay(rings[INNER])
        self._update_closeup(f, rings)
        if self._closeup_on:
            self._closeup_camera(f)
        self._update_tracks(f.index + 1)

    def _display_alpha(self, race: int, alpha):
        """Exaggerated groove latitude (rad), clipped at the shoulder edges."""
        grid = self.grids[race]
        shown = exaggerate(alpha, self._reference[race], self.options.exaggeration)
        return np.clip(shown, grid.alpha_lo, grid.alpha_hi)

    def _in_cutaway(self, race: int, phi) -> np.ndarray:
        """True where a mark on ``race`` at ring azimuth ``phi`` (rad) lies in the removed sector.

        Outer-raceway marks there would float in front of the balls, so they are not drawn.
        """
        if race != OUTER:
            return np.zeros(np.shape(phi), bool)
        lo, hi = self.options.outer_cutaway
        return np.mod(np.asarray(phi) - lo, 2 * math.pi) < (hi - lo)

    def _update_ellipses(self, race: int, f) -> None:
        groove = self.grooves[race]
        loaded = f.loaded[:, race] & ~self._in_cutaway(race, f.raceway_azimuth[:, race])
        alpha = np.where(loaded, f.contact_angle[:, race], self._reference[race])
        alpha = self._display_alpha(race, alpha)
        scale = self.options.ellipse_scale
        a = np.where(loaded, np.nan_to_num(f.semi_major[:, race]), 0.0) * scale
        b = np.where(loaded, np.nan_to_num(f.semi_minor[:, race]), 0.0) * scale
        phi = f.raceway_azimuth[:, race]
        lift = 2 * _MARK_LIFT * groove.r  # above the traces
        outline = ellipse_outline(groove, phi, alpha, a, b, n=ELLIPSE_POINTS, lift=lift)
        centre = groove.point(phi, alpha, lift=lift)[:, None, :]
        pts = np.concatenate([centre, outline], axis=1).reshape(-1, 3)
        mesh = self._ellipses[race]
        mesh.points = pts
        p = np.where(loaded, np.nan_to_num(f.max_pressure[:, race]), 0.0) * 1e-9
        mesh.point_data["max_pressure_GPa"] = np.repeat(p, ELLIPSE_POINTS + 1)

    def _update_traces(self, race: int, stop: int) -> None:
        if not self.options.layers.get("traces", True):
            return  # redrawn when the layer is shown (set_layer)
        phi, alpha, loaded = self.source.trace(race, stop)
        step = max(1, math.ceil(phi.shape[1] / MAX_TRACE_SAMPLES))
        phi, alpha, loaded = phi[:, ::step], alpha[:, ::step], loaded[:, ::step]
        loaded = loaded & ~self._in_cutaway(race, phi)
        balls = (
            range(phi.shape[0]) if self.options.trace_ball is None else [self.options.trace_ball]
        )
        groove = self.grooves[race]
        lift = _MARK_LIFT * groove.r
        points, lines, ids = [], [], []
        offset = 0
        for j in balls:
            if not 0 <= j < phi.shape[0]:
                continue
            ok = loaded[j]
            if ok.sum() < 2:
                continue
            pts = groove.point(
                phi[j], self._display_alpha(race, np.where(ok, alpha[j], 0.0)), lift=lift
            )
            # split into runs of consecutive loaded samples
            idx = np.flatnonzero(ok)
            breaks = np.flatnonzero(np.diff(idx) > 1) + 1
            for run in np.split(idx, breaks):
                if len(run) < 2:
                    continue
                points.append(pts[run])
                lines.append(np.concatenate([[len(run)], offset + np.arange(len(run))]))
                ids.append(np.full(len(run), j, float))
                offset += len(run)
        mesh = self._traces[race]
        if not points:
            new = pv.PolyData(np.zeros((2, 3)), lines=np.array([2, 0, 1]))
            new.point_data["ball"] = np.zeros(2)
            self._actors["traces"][race].visibility = False
        else:
            new = pv.PolyData(np.concatenate(points), lines=np.concatenate(lines))
            new.point_data["ball"] = np.concatenate(ids)
            self._actors["traces"][race].visibility = self.options.layers.get("traces", True)
        mesh.copy_from(new)

    # ---- options --------------------------------------------------------------------------------
    def set_layer(self, name: str, visible: bool) -> None:
        """Show or hide one of :data:`LAYERS`."""
        if name not in LAYERS:
            raise ValueError(f"unknown layer {name!r}; layers are {', '.join(LAYERS)}")
        self.options.layers[name] = bool(visible)
        for actor in self._actors[name]:
            actor.visibility = bool(visible)
        if name == "traces" and visible and self.source is not None:
            for race in (INNER, OUTER):
                self._update_traces(race, self.frame_index + 1)

    def set_exaggeration(self, factor: float) -> None:
        """Across-groove exaggeration factor (>= 1) for tracks, traces and ellipse centres."""
        factor = max(1.0, float(factor))
        if factor != self.options.exaggeration:
            self.options.exaggeration = factor
            self._build_painter()
        self.set_frame(self.frame_index)

    def set_ellipse_scale(self, factor: float) -> None:
        """Drawn size of the contact ellipses (and their painted footprints) / true size, >= 1."""
        factor = max(1.0, float(factor))
        if factor != self.options.ellipse_scale:
            self.options.ellipse_scale = factor
            self._build_painter()
        self.set_frame(self.frame_index)

    def set_track_options(self, quantity: str | None = None, whole_run: bool | None = None):
        """Colour the painted tracks by ``quantity`` (:data:`app.tracks.QUANTITIES`) and paint
        the whole run (``whole_run``) or the frames up to the current one."""
        if quantity is not None:
            if quantity not in QUANTITIES:
                raise ValueError(
                    f"unknown track colouring {quantity!r}; use one of {', '.join(QUANTITIES)}"
                )
            self.options.track_quantity = quantity
            self._bar.SetTitle(QUANTITY_LABELS[quantity])
        if whole_run is not None:
            self.options.track_whole_run = bool(whole_run)
        self.set_frame(self.frame_index)

    def set_trace_ball(self, ball: int | None) -> None:
        """Draw the traces of one ball (index) or of all balls (None)."""
        self.options.trace_ball = ball
        self.set_frame(self.frame_index)

    def set_camera(self, preset: str) -> None:
        """Camera preset: ``isometric``, ``axial``, ``radial``, ``inner track``, ``outer track``.

        Always re-applies the preset (also when it is the one already on show) and frames what it
        shows with a margin of :data:`FRAME_MARGIN` at the render window's aspect, leaving the
        strip of the colour bar on the right free. ``isometric`` looks at the load side
        (:attr:`SceneOptions.view_azimuth`, where the outer ring is opened) from the +x side,
        where the inner-raceway contacts face, :data:`ISOMETRIC_TILT_DEG` off the axis: the inner
        raceway in front, the outer raceway behind it from inside; ``axial`` looks along +x;
        ``radial`` looks into the opened side, the bearing axis across the view. ``inner track``
        frames the inner raceway's load-side half and ``outer track`` the outer raceway's far
        half, both :data:`TRACK_VIEW_TILT_DEG` off the axis.
        """
        if preset not in CAMERA_PRESETS:
            raise ValueError(
                f"unknown camera preset {preset!r}; use one of {', '.join(CAMERA_PRESETS)}"
            )
        self._closeup_on = preset == "close-up"
        self.plotter.camera.view_angle = VIEW_ANGLE_DEG  # a mouse zoom narrows the view angle
        width, height = self.plotter.window_size
        if self._closeup_on:
            self._framed_size = (width, height)
            if self.source is not None:
                self.set_frame(self.frame_index)
            return
        for actor in self._closeup_actors:
            actor.visibility = False
        for name in ("balls", "cage", "outer_ring"):  # the close-up showed one ball alone
            for actor in self._actors[name]:
                actor.visibility = bool(self.options.layers.get(name, True))
        direction, up = camera_directions(
            "isometric" if preset == "close-up" else preset, self.options.view_azimuth
        )
        points = self._outline_points
        if preset in ("inner track", "outer track"):
            points = self._track_points(INNER if preset == "inner track" else OUTER)
        position, focal = frame_points(
            points,
            direction,
            up,
            view_angle_deg=self.plotter.camera.view_angle,
            aspect=width / height,
            right_reserved=SCALAR_BAR_STRIP,
        )
        self.plotter.camera_position = [tuple(position), tuple(focal), tuple(up)]
        self.plotter.renderer.ResetCameraClippingRange()
        self._framed_size = (width, height)

    def _track_points(self, race: int) -> np.ndarray:
        """Points (m, drawn position) of the shoulder edges of ``race`` on the half of the raceway
        that the track presets look at (load side for the inner, opposite side for the outer)."""
        grid, groove = self.grids[race], self.grooves[race]
        side = self.options.view_azimuth + (0.0 if race == INNER else math.pi)
        phi = side + np.linspace(-0.5 * math.pi, 0.5 * math.pi, 37)
        pts = np.concatenate([groove.point(phi, a) for a in (grid.alpha_lo, grid.alpha_hi)])
        if race == OUTER:
            pts[:, 0] += self.outer_shift
        return pts

    def framed_for_window(self) -> bool:
        """Whether the last camera preset was framed for the render window's current size."""
        return tuple(self.plotter.window_size) == getattr(self, "_framed_size", None)

    def trace_point_count(self, race: int) -> int:
        """Number of points in the drawn trace of ``race`` (0 when none is drawn)."""
        visible = self._actors["traces"][race].visibility
        return self._traces[race].n_points if visible else 0
