"""The close-up of one ball: its two contacts as pressure half-ellipsoids standing on the grooves,
the recent paths of the contact-ellipse centres on the raceways (ring frames) and, for a dynamic
result, the ball's own contact paths on its surface (ball-fixed frame). Lengths in m."""

from __future__ import annotations

import math

import numpy as np
import pyvista as pv

from solver import loaded_mask

from .frames import rot_x
from .layout import ELLIPSE_POINTS, MARK_LIFT, RacewayLayout
from .meshes import empty_line, placement, set_polyline
from .raceway import INNER, OUTER

CLOSEUP_PATH_FRAMES = 120  # frames of recent path drawn in the close-up of one ball
CLOSEUP_DOME = 0.6  # height of the pressure half-ellipsoid at the peak pressure / semi-major axis
CLOSEUP_COLOURS = {"path": "#0b6e4f", "ball_path": "#d1495b"}
DOME_RINGS = 8  # rings of points from the dome's top to its rim


class CloseUp:
    """The close-up's meshes in ``plotter``, hidden until :attr:`on`; ``actors`` per race: dome,
    path, ball path."""

    def __init__(self, plotter: pv.Plotter, ball_diameter: float, layout: RacewayLayout):
        self.layout = layout
        self.ball_diameter = ball_diameter
        self.domes, self.paths, self.ball_paths = [], [], []
        self.actors = []
        self.on = False
        n_r, n_t = DOME_RINGS, ELLIPSE_POINTS
        for race in (INNER, OUTER):
            faces = []  # quads between neighbouring rings of the (rho, tau) grid
            for i in range(n_r - 1):
                for k in range(n_t):
                    a0 = i * n_t + k
                    a1 = i * n_t + (k + 1) % n_t
                    faces.append((4, a0, a1, a1 + n_t, a0 + n_t))
            mesh = pv.PolyData(np.zeros((n_r * n_t, 3)), faces=np.asarray(faces).ravel())
            mesh.point_data["pressure_GPa"] = np.zeros(n_r * n_t)
            self.domes.append(mesh)
            self.actors.append(
                plotter.add_mesh(
                    mesh,
                    scalars="pressure_GPa",
                    cmap="plasma",
                    clim=(0.0, 1.0),
                    show_scalar_bar=False,
                    smooth_shading=True,
                    name=f"closeup_dome_{race}",
                )
            )
            for kind, store in (("path", self.paths), ("ball_path", self.ball_paths)):
                line = empty_line()
                store.append(line)
                self.actors.append(
                    plotter.add_mesh(
                        line,
                        color=CLOSEUP_COLOURS[kind],
                        line_width=3.0,
                        lighting=False,
                        name=f"closeup_{kind}_{race}",
                    )
                )
        self.show(False)

    def show(self, visible: bool) -> None:
        """Show or hide all of the close-up's meshes."""
        for actor in self.actors:
            actor.visibility = visible

    def update(self, f, ball: int, rings, source, ellipse_scale: float) -> None:
        """Draw ball ``ball``'s contacts at frame ``f`` of ``source``
        (:class:`viz.frames.FrameSource`), ellipses ``ellipse_scale`` times their size; ``rings``:
        the (inner, outer) ring matrices. The outer ring's marks are drawn where its contacts are
        (not drawn apart)."""
        layout, j = self.layout, ball
        rings = [rings[INNER], placement(rot_x(f.ring_angle[OUTER]))]
        n_r, n_t = DOME_RINGS, ELLIPSE_POINTS
        rho = np.linspace(0.0, 1.0, n_r)[:, None]
        tau = np.linspace(0.0, 2 * math.pi, n_t, endpoint=False)[None, :]
        pmax = np.nan_to_num(source.contact["max_pressure"])
        top = max(float(pmax.max()) * 1e-9, 1e-3)
        start = max(0, f.index + 1 - CLOSEUP_PATH_FRAMES)
        for race in (INNER, OUTER):
            groove = layout.grooves[race]
            loaded = bool(f.loaded[j, race])
            scale = ellipse_scale
            a = float(np.nan_to_num(f.semi_major[j, race])) * scale if loaded else 0.0
            b = float(np.nan_to_num(f.semi_minor[j, race])) * scale if loaded else 0.0
            p0 = float(np.nan_to_num(f.max_pressure[j, race])) * 1e-9 if loaded else 0.0
            alpha = float(layout.display_alpha(race, f.contact_angle[j, race] if loaded else 0.0))
            phi = float(f.raceway_azimuth[j, race])
            shape = np.sqrt(np.clip(1.0 - rho**2, 0.0, 1.0))
            lift = 2 * MARK_LIFT * groove.r + CLOSEUP_DOME * a * shape
            phis = phi + b / groove.contact_radius(alpha) * rho * np.sin(tau)
            alphas = alpha + a / groove.r * rho * np.cos(tau)
            surface = groove.point(phis, alphas)
            # towards the groove's curvature centre: out of the raceway, into the ball's space
            toward = groove.point(phis, alphas, lift=groove.r) - surface
            toward /= np.linalg.norm(toward, axis=-1, keepdims=True)
            pts = surface + lift[..., None] * toward
            dome = self.domes[race]
            dome.points = pts.reshape(-1, 3)
            dome.point_data["pressure_GPa"] = np.broadcast_to(p0 * shape, (n_r, n_t)).ravel()
            self.actors[3 * race].mapper.scalar_range = (0.0, top)
            self.actors[3 * race].user_matrix = rings[race]
            # recent path of the ellipse centre on the raceway (ring frame)
            c = source.contact
            al = c["contact_angle"][start : f.index + 1, j, race]
            ok = loaded_mask(c["contact_load"][start : f.index + 1, j, race], al)
            ph = source.raceway_azimuth[start : f.index + 1, j, race]
            set_polyline(
                self.paths[race],
                groove.point(
                    ph[ok], layout.display_alpha(race, al[ok]), lift=3 * MARK_LIFT * groove.r
                ),
            )
            self.actors[3 * race + 1].user_matrix = rings[race]
            # the ball's own contact path on its surface (ball-fixed frame, dynamic results)
            lat = c.get("ball_latitude")
            if lat is not None and source.model == "dynamic":
                la = lat[start : f.index + 1, j, race][ok]
                lo = c["ball_longitude"][start : f.index + 1, j, race][ok]
                radius = 0.5 * self.ball_diameter * 1.01
                pts = radius * np.column_stack(
                    [np.cos(la) * np.cos(lo), np.cos(la) * np.sin(lo), np.sin(la)]
                )
                set_polyline(self.ball_paths[race], pts)
                self.actors[3 * race + 2].user_matrix = placement(
                    f.ball_rotation[j], f.ball_center[j]
                )
            else:
                self.actors[3 * race + 2].visibility = False
