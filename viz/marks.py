"""Marks drawn on the raceways, in each ring's own frame (m): the shoulder edges and the groove
bottom, the contact ellipses of the frame on show and the trajectory traces of the contacts.

Across-groove positions follow :meth:`viz.layout.RacewayLayout.display_alpha` (exaggerated about
the run's mean contact angle, clipped at the shoulders); ellipse sizes are to scale unless
``ellipse_scale`` enlarges them. Marks in the outer ring's cut-away sector are not drawn.
"""

from __future__ import annotations

import math

import numpy as np
import pyvista as pv

from .layout import ELLIPSE_POINTS, MARK_LIFT, RacewayLayout
from .meshes import empty_line, fan_faces, outline_lines
from .palette import ball_colours
from .raceway import INNER, OUTER, ellipse_angles

EDGE_COLOURS = {"shoulder": "#1b1b1b", "bottom": "#2f5597"}
EDGE_WIDTH_PX = 2.0
MAX_TRACE_SAMPLES = 1500  # per ball and race; longer traces are decimated for drawing
ELLIPSE_COLOUR = "#0096c7"  # contact ellipses: one colour that stands out on the painted tracks
# Contact ellipses are filled to scale and outlined with a stroke of this width (pixels), so that
# one of 0.9 x 0.15 mm still shows when the whole bearing is in view (a stroke, not a size).
ELLIPSE_OUTLINE_PX = 2.0
TRACE_WIDTH_PX = 3.0


def ellipse_points(layout: RacewayLayout, race: int, f, ellipse_scale: float):
    """The contact ellipses of ``race`` at frame ``f`` (:class:`viz.frames.Frame`) drawn
    ``ellipse_scale`` times their size, in the ring's frame (m): (points (Z * (ELLIPSE_POINTS + 1),
    3), each ellipse's centre then its outline (:func:`viz.raceway.ellipse_angles`); peak
    pressure per ball, GPa, 0 where unloaded). Unloaded contacts and those in the outer ring's
    cut-away sector collapse to their centre."""
    groove = layout.grooves[race]
    phi = f.raceway_azimuth[:, race]
    loaded = f.loaded[:, race] & ~layout.in_cutaway(race, phi)
    alpha = np.where(loaded, f.contact_angle[:, race], layout.reference[race])
    alpha = layout.display_alpha(race, alpha)
    # semi-major, semi-minor axis and peak pressure of the contacts drawn, 0 for the others
    sizes = np.where(
        loaded, (f.semi_major[:, race], f.semi_minor[:, race], f.max_pressure[:, race]), 0.0
    )
    if not np.isfinite(sizes).all():  # NaN as 0, infinities as the largest finite numbers
        sizes = np.nan_to_num(sizes)
    a, b = sizes[0] * ellipse_scale, sizes[1] * ellipse_scale
    lift = 2 * MARK_LIFT * groove.r  # above the traces
    # the groove angles of each ellipse's centre (column 0) then its outline, placed at once
    outline_phi, outline_alpha = ellipse_angles(groove, phi, alpha, a, b, ELLIPSE_POINTS)
    phis = np.concatenate([phi[:, None], outline_phi], axis=1)
    alphas = np.concatenate([alpha[:, None], outline_alpha], axis=1)
    pts = groove.point(phis, alphas, lift=lift).reshape(-1, 3)
    return pts, sizes[2] * 1e-9


class RacewayMarks:
    """Edges, contact ellipses and traces of both raceways in ``plotter``; ``actors`` by layer."""

    def __init__(self, plotter: pv.Plotter, ball_count: int, layout: RacewayLayout):
        self.plotter = plotter
        self.layout = layout
        self.actors = {"edges": [], "ellipses": [], "traces": []}
        self._add_edges()
        n_pts = ball_count * (ELLIPSE_POINTS + 1)
        self.ellipses, self.traces = [], []
        for race in (INNER, OUTER):
            mesh = pv.PolyData(
                np.zeros((n_pts, 3)),
                faces=fan_faces(ball_count, ELLIPSE_POINTS),
                lines=outline_lines(ball_count, ELLIPSE_POINTS),
            )
            mesh.point_data["max_pressure_GPa"] = np.zeros(n_pts)
            self.ellipses.append(mesh)
            self.actors["ellipses"].append(
                plotter.add_mesh(
                    mesh,
                    color=ELLIPSE_COLOUR,
                    line_width=ELLIPSE_OUTLINE_PX,
                    lighting=False,
                    name=f"ellipses_{race}",
                )
            )
            trace = empty_line()
            trace.point_data["ball"] = np.zeros(2)
            self.traces.append(trace)
            self.actors["traces"].append(
                plotter.add_mesh(
                    trace,
                    scalars="ball",
                    cmap=ball_colours(ball_count),
                    n_colors=ball_count,
                    clim=(-0.5, ball_count - 0.5),
                    show_scalar_bar=False,
                    line_width=TRACE_WIDTH_PX,
                    name=f"traces_{race}",
                )
            )

    def _add_edges(self) -> None:
        """Both shoulder edges and the groove bottom of each ring, as lines on the groove."""
        layout = self.layout
        for race in (INNER, OUTER):
            groove, grid = layout.grooves[race], layout.grids[race]
            kept = layout.kept_phi_cells(race)
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
                    pts = groove.point(phi, alpha, lift=MARK_LIFT * groove.r)
                    parts.append(pv.lines_from_points(pts))
                self.actors["edges"].append(
                    self.plotter.add_mesh(
                        pv.merge(parts),
                        color=EDGE_COLOURS[kind],
                        line_width=EDGE_WIDTH_PX,
                        lighting=False,
                        name=f"edge_{race}_{kind}_{alpha:.3f}",
                    )
                )
        self._edge_race = [INNER] * 3 + [OUTER] * 3

    def move(self, rings) -> None:
        """Turn every mark with its ring (``rings``: (inner, outer) 4x4 matrices)."""
        for race in (INNER, OUTER):
            self.actors["ellipses"][race].user_matrix = rings[race]
            self.actors["traces"][race].user_matrix = rings[race]
        for race, actor in zip(self._edge_race, self.actors["edges"], strict=True):
            actor.user_matrix = rings[race]

    def update_ellipses(self, race: int, f, ellipse_scale: float) -> None:
        """The contact ellipses of ``race`` at frame ``f`` (:class:`viz.frames.Frame`), drawn
        ``ellipse_scale`` times their size."""
        pts, p = ellipse_points(self.layout, race, f, ellipse_scale)
        mesh = self.ellipses[race]
        mesh.points = pts
        mesh.point_data["max_pressure_GPa"] = np.repeat(p, ELLIPSE_POINTS + 1)

    def update_traces(self, race: int, source, stop: int, options) -> None:
        """The traces of ``race`` over frames ``[0, stop)`` of ``source``: every ball's, or only
        ``options.trace_ball``'s; nothing while the traces layer is hidden."""
        if not options.visible("traces"):
            return  # redrawn when the layer is shown
        layout = self.layout
        phi, alpha, loaded = source.trace(race, stop)
        step = max(1, math.ceil(phi.shape[1] / MAX_TRACE_SAMPLES))
        phi, alpha, loaded = phi[:, ::step], alpha[:, ::step], loaded[:, ::step]
        loaded = loaded & ~layout.in_cutaway(race, phi)
        balls = range(phi.shape[0]) if options.trace_ball is None else [options.trace_ball]
        groove = layout.grooves[race]
        lift = MARK_LIFT * groove.r
        points, lines, ids = [], [], []
        offset = 0
        for j in balls:
            if not 0 <= j < phi.shape[0]:
                continue
            ok = loaded[j]
            if ok.sum() < 2:
                continue
            pts = groove.point(
                phi[j], layout.display_alpha(race, np.where(ok, alpha[j], 0.0)), lift=lift
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
        mesh = self.traces[race]
        if not points:
            new = empty_line()
            new.point_data["ball"] = np.zeros(2)
            self.actors["traces"][race].visibility = False
        else:
            new = pv.PolyData(np.concatenate(points), lines=np.concatenate(lines))
            new.point_data["ball"] = np.concatenate(ids)
            self.actors["traces"][race].visibility = options.visible("traces")
        mesh.copy_from(new)

    def trace_point_count(self, race: int) -> int:
        """Number of points in the drawn trace of ``race`` (0 when none is drawn)."""
        visible = self.actors["traces"][race].visibility
        return self.traces[race].n_points if visible else 0
