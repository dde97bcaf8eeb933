"""The scene's camera: the presets, each framing what it shows at the render window's aspect.

Directions are in the inertial frame of case-format.md (x = bearing axis), lengths in m. The
presets look at the side of the load (``view_azimuth``, rad from +y towards +z), where the outer
ring is opened; the close-up follows one ball along its rolling direction.
"""

from __future__ import annotations

import math

import numpy as np
import pyvista as pv

from .layout import RacewayLayout
from .raceway import INNER, OUTER

CAMERA_PRESETS = ("isometric", "axial", "radial", "inner track", "outer track", "close-up")
VIEW_ANGLE_DEG = 30.0  # vertical view angle of the camera presets (VTK's default)
ISOMETRIC_TILT_DEG = 75.0  # isometric view direction from the bearing axis
TRACK_VIEW_TILT_DEG = 62.0  # "inner track" / "outer track" views: direction from the axis
AXIAL_TILT_DEG = 25.0  # "axial" view direction from the bearing axis
FRAME_MARGIN = 0.06  # camera presets leave this fraction of each half-size free around the bearing
SCALAR_BAR_STRIP = 0.17  # fraction of the view width on the right kept for the colour bar


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


def track_points(layout: RacewayLayout, race: int, view_azimuth: float) -> np.ndarray:
    """Points (m, drawn position) of the shoulder edges of ``race`` on the half of the raceway
    that the track presets look at (load side ``view_azimuth`` for the inner, the opposite side
    for the outer); for the outer raceway also the outer ring's half round it (its faces at its
    largest radius), so that the preset shows the opened ring whole with its raceway in the
    middle."""
    grid, groove = layout.grids[race], layout.grooves[race]
    side = view_azimuth + (0.0 if race == INNER else math.pi)
    phi = side + np.linspace(-0.5 * math.pi, 0.5 * math.pi, 37)
    pts = [groove.point(phi, a) for a in (grid.alpha_lo, grid.alpha_hi)]
    if race == OUTER:
        x, radius = layout.profiles[OUTER]
        for face in (float(np.min(x)), float(np.max(x))):
            r = float(np.max(radius))
            pts.append(np.column_stack([np.full(phi.size, face), r * np.cos(phi), r * np.sin(phi)]))
    pts = np.concatenate(pts)
    if race == OUTER:
        pts[:, 0] += layout.outer_shift
    return pts


class SceneCamera:
    """Points the camera of ``plotter`` at the bearing of ``layout``; ``outline`` (m, (n, 3)):
    the points that bound what is drawn (:func:`outline_points`)."""

    def __init__(self, plotter: pv.Plotter, layout: RacewayLayout, outline: np.ndarray):
        self.plotter = plotter
        self.layout = layout
        self.outline = outline
        self._framed_size = None

    def reset_view_angle(self) -> None:
        """Back to :data:`VIEW_ANGLE_DEG` (a mouse zoom narrows the view angle)."""
        self.plotter.camera.view_angle = VIEW_ANGLE_DEG

    def frame_preset(self, preset: str, view_azimuth: float) -> None:
        """Frame what ``preset`` (not the close-up) shows, with a margin of :data:`FRAME_MARGIN`
        at the render window's aspect, leaving the strip of the colour bar on the right free."""
        width, height = self.plotter.window_size
        direction, up = camera_directions(preset, view_azimuth)
        points = self.outline
        if preset in ("inner track", "outer track"):
            points = track_points(
                self.layout, INNER if preset == "inner track" else OUTER, view_azimuth
            )
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
        self.mark_framed()

    def mark_framed(self) -> None:
        """Record that the view was framed for the render window's current size."""
        self._framed_size = tuple(self.plotter.window_size)

    def framed_for_window(self) -> bool:
        """Whether the last preset was framed for the render window's current size."""
        return tuple(self.plotter.window_size) == self._framed_size

    def follow_ball(self, f, ball: int, ball_diameter: float) -> None:
        """Look at ball ``ball`` of frame ``f`` along its rolling direction, the bearing axis
        across."""
        psi = float(f.ball_azimuth[ball])
        e_r = np.array([0.0, math.cos(psi), math.sin(psi)])
        e_t = np.array([0.0, -math.sin(psi), math.cos(psi)])
        direction = e_t + 0.35 * np.array([1.0, 0.0, 0.0])
        centre = np.asarray(f.ball_center[ball], float)
        D = ball_diameter
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
